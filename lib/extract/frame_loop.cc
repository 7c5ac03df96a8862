// Frame loop of the rk-extract subcommands; see frame_loop.h.
#include "extract/frame_loop.h"

#include <chrono>
#include <cmath>

#include "io/error.h"
#include "io/run_record.h"
#include "video/frame_source.h"

namespace rk::extract {
using Clock = std::chrono::steady_clock;

VideoRunStats ForEachFrame(const std::vector<std::string>& videos, const formats::FrameClock& clock,
                           const std::function<void(const cv::Mat& frame, std::int64_t k, double t_s)>& process,
                           const std::function<void(std::int64_t)>& progress, std::int64_t progress_every) {
  VideoRunStats st;
  video::FrameSource source(videos);
  cv::Mat frame;
  const auto t_start = Clock::now();
  std::int64_t k = 0;
  while (source.Read(&frame)) {
    const double t_s = clock.TimeOf(k);
    if (std::isnan(t_s)) {  // a hole in the frames file (its row skipped): no time, not measured
      ++st.frames_without_time;
      ++k;
      continue;
    }
    if (st.width_px == 0) {
      st.width_px = frame.cols;
      st.height_px = frame.rows;
      st.bit_depth = frame.depth() == CV_16U ? 16 : 8;
    }
    const auto t0 = Clock::now();
    process(frame, k, t_s);
    st.extract_s += SecondsSince(t0);
    ++k;
    if (progress && progress_every > 0 && k % progress_every == 0) progress(k);
  }
  st.wall_s = SecondsSince(t_start);
  if (st.frames_without_time > 0) {
    io::EmitWarning(clock.path() + ": " + std::to_string(st.frames_without_time) +
                    " frames have no time (their rows were skipped) and were not measured");
  }
  st.frames = k;
  if (clock.from_file() && clock.size() > k) {
    throw DataError(videos.back(), 0, 0,
                    "video is truncated: it has " + std::to_string(k) + " frames but " + clock.path() + " lists " +
                        std::to_string(clock.size()));
  }
  return st;
}

}  // namespace rk::extract

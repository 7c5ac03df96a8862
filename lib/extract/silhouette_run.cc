// Frame loop of `rk-extract silhouette`; see silhouette_run.h.
#include "extract/silhouette_run.h"

#include <chrono>

#include "io/error.h"
#include "video/frame_source.h"

namespace rk::extract {
namespace {
using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }
}  // namespace

SilhouetteRunResult RunSilhouette(const std::vector<std::string>& videos, const FrameClock& clock,
                                  const SilhouetteOptions& opt, const std::function<void(std::int64_t)>& progress) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  SilhouetteRunResult res;
  video::FrameSource source(videos);
  cv::Mat frame;
  const auto t_start = Clock::now();
  std::int64_t k = 0;
  while (source.Read(&frame)) {
    SilhouetteFrameRow row;
    row.frame = k;
    row.t_s = clock.TimeOf(k);
    if (k == 0) {
      res.width_px = frame.cols;
      res.height_px = frame.rows;
      res.bit_depth = frame.depth() == CV_16U ? 16 : 8;
    }
    const auto t0 = Clock::now();
    row.result = ExtractSilhouette(frame, opt);
    res.extract_s += Seconds(t0, Clock::now());
    ++res.by_status[static_cast<std::size_t>(row.result.status)];
    res.rows.push_back(row);
    ++k;
    if (progress && k % 20 == 0) progress(k);
  }
  res.wall_s = Seconds(t_start, Clock::now());
  res.frames = k;
  if (clock.from_file() && clock.size() > k) {
    throw DataError(videos.back(), 0, 0,
                    "video is truncated: it has " + std::to_string(k) + " frames but " + clock.path() + " lists " +
                        std::to_string(clock.size()));
  }
  if (res.by_status[static_cast<std::size_t>(SilhouetteStatus::kOk)] == 0) {
    throw ProcessingError("nothing detected: no frame of the " + std::to_string(k) +
                          " gave the nose and tail points of a cylindrical target");
  }
  return res;
}

io::CsvWriter SilhouettePointsCsv(const std::vector<SilhouetteFrameRow>& rows) {
  io::CsvWriter w({"frame", "t_s", "id", "x_px", "y_px", "status", "detail", "width_px", "length_px"});
  const char* ids[3] = {"nose", "tail1", "tail2"};
  for (const SilhouetteFrameRow& r : rows) {
    const bool ok = r.result.status == SilhouetteStatus::kOk;
    const char* status = ok ? "ok" : (r.result.status == SilhouetteStatus::kNotFound ? "lost" : "invalid");
    for (int i = 0; i < 3; ++i) {
      w.Add(r.frame).Add(r.t_s, 9).Add(ids[i]);
      if (ok) {
        w.Add(r.result.px[static_cast<std::size_t>(i)].x(), 4).Add(r.result.px[static_cast<std::size_t>(i)].y(), 4);
      } else {
        w.AddEmpty().AddEmpty();
      }
      w.Add(status).Add(SilhouetteStatusName(r.result.status));
      if (ok) {
        w.Add(r.result.width_px, 4).Add(r.result.length_px, 4);
      } else {
        w.AddEmpty().AddEmpty();
      }
      w.EndRow();
    }
  }
  return w;
}

}  // namespace rk::extract

// Frame loop of `rk-extract beacon`; see beacon_run.h.
#include "extract/beacon_run.h"

#include <chrono>

#include "io/error.h"
#include "video/frame_source.h"

namespace rk::extract {
namespace {
using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }
}  // namespace

BeaconRunResult RunBeacon(const std::vector<std::string>& videos, const FrameClock& clock,
                          const BeaconTrackOptions& opt, const std::function<void(std::int64_t)>& progress) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  BeaconRunResult res;
  video::FrameSource source(videos);
  BeaconTracker tracker(opt);
  cv::Mat frame;
  const auto t_start = Clock::now();
  std::int64_t k = 0;
  while (source.Read(&frame)) {
    const double t_s = clock.TimeOf(k);
    if (k == 0) {
      res.width_px = frame.cols;
      res.height_px = frame.rows;
      res.bit_depth = frame.depth() == CV_16U ? 16 : 8;
    }
    const auto t0 = Clock::now();
    res.rows.push_back(tracker.Process(frame, k, t_s));
    res.extract_s += Seconds(t0, Clock::now());
    ++k;
    if (progress && k % 100 == 0) progress(k);
  }
  res.wall_s = Seconds(t_start, Clock::now());
  res.frames = k;
  res.summary = tracker.summary();
  if (clock.from_file() && clock.size() > k) {
    throw DataError(videos.back(), 0, 0,
                    "video is truncated: it has " + std::to_string(k) + " frames but " + clock.path() + " lists " +
                        std::to_string(clock.size()));
  }
  if (res.summary.ok + res.summary.reacquired == 0) {
    throw ProcessingError("nothing detected: no beacon found in any of the " + std::to_string(k) + " frames");
  }
  return res;
}

DecodeResult DecodeOnly(const std::vector<std::string>& videos) {
  DecodeResult r;
  video::FrameSource source(videos);
  cv::Mat frame;
  const auto t0 = Clock::now();
  while (source.Read(&frame)) ++r.frames;
  r.wall_s = Seconds(t0, Clock::now());
  return r;
}

io::CsvWriter BeaconTrackCsv(const std::vector<BeaconFrameResult>& rows, int bit_depth) {
  (void)bit_depth;
  io::CsvWriter w({"frame", "t_s", "x_px", "y_px", "peak", "area_px", "status", "ncc", "sigma_x_px", "sigma_y_px"});
  for (const auto& r : rows) {
    w.Add(static_cast<std::int64_t>(r.frame)).Add(r.t_s, 9);
    if (r.has_xy) {
      w.Add(r.x_px, 4).Add(r.y_px, 4);
    } else {
      w.AddEmpty().AddEmpty();
    }
    if (r.has_spot) {
      w.Add(static_cast<std::int64_t>(std::llround(r.peak_dn))).Add(r.area_px);
    } else {
      w.AddEmpty().AddEmpty();
    }
    w.Add(BeaconStatusName(r.status));
    if (r.has_ncc) {
      w.Add(r.ncc, 4);
    } else {
      w.AddEmpty();
    }
    if (r.has_xy) {
      w.Add(r.sigma_x_px, 5).Add(r.sigma_y_px, 5);
    } else {
      w.AddEmpty().AddEmpty();
    }
    w.EndRow();
  }
  return w;
}

}  // namespace rk::extract

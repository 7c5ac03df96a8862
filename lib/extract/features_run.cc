// Frame loop of `rk-extract features`; see features_run.h.
#include "extract/features_run.h"

#include <chrono>

#include "io/error.h"
#include "video/frame_source.h"

namespace rk::extract {
namespace {
using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }
}  // namespace

FeatureRunResult RunFeatures(const std::vector<std::string>& videos, const FrameClock& clock, const TargetModel& model,
                             const FeatureTrackOptions& options, const std::function<void(std::int64_t)>& progress) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  FeatureRunResult res;
  video::FrameSource source(videos);
  FeatureTracker tracker(model, options);
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
    if (progress && k % 20 == 0) progress(k);
  }
  res.wall_s = Seconds(t_start, Clock::now());
  res.frames = k;
  res.summary = tracker.summary();
  if (clock.from_file() && clock.size() > k) {
    throw DataError(videos.back(), 0, 0,
                    "video is truncated: it has " + std::to_string(k) + " frames but " + clock.path() + " lists " +
                        std::to_string(clock.size()));
  }
  if (res.summary.measured == 0) {
    std::string extra;
    if (res.summary.ambiguous > 0) {
      extra = " (" + std::to_string(res.summary.ambiguous) +
              " frames had an ambiguous identification: is the marker layout symmetric?)";
    }
    throw ProcessingError("nothing detected: the target's markers were not identified in any of the " +
                          std::to_string(k) + " frames" + extra);
  }
  return res;
}

io::CsvWriter FeaturePointsCsv(const std::vector<FeatureFrameResult>& rows, const TargetModel& model) {
  io::CsvWriter w({"frame", "t_s", "id", "x_px", "y_px", "status", "sigma_px", "ncc", "radius_px"});
  for (const FeatureFrameResult& r : rows) {
    for (std::size_t i = 0; i < model.size(); ++i) {
      const FeaturePoint& p = r.points[i];
      w.Add(r.frame).Add(r.t_s, 9).Add(model.ids[i]);
      if (p.has_xy) {
        w.Add(p.px.x(), 4).Add(p.px.y(), 4);
      } else {
        w.AddEmpty().AddEmpty();
      }
      w.Add(RowStatusName(p.status));
      if (p.has_xy) {
        w.Add(p.sigma_px, 5).Add(p.ncc, 4).Add(p.radius_px, 3);
      } else {
        w.AddEmpty().AddEmpty().AddEmpty();
      }
      w.EndRow();
    }
  }
  return w;
}

}  // namespace rk::extract

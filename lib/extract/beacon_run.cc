// `rk-extract beacon` over the shared frame loop (frame_loop.h); see beacon_run.h.
#include "extract/beacon_run.h"

#include <chrono>

#include "io/error.h"
#include "io/json_util.h"
#include "video/frame_source.h"

namespace rk::extract {
using Clock = std::chrono::steady_clock;

BeaconRunResult RunBeacon(const std::vector<std::string>& videos, const formats::FrameClock& clock,
                          const BeaconTrackOptions& opt, const std::function<void(std::int64_t)>& progress,
                          const std::function<void(const BeaconFrameResult&)>& on_row) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  BeaconRunResult res;
  BeaconTracker tracker(opt);
  static_cast<VideoRunStats&>(res) = ForEachFrame(
      videos, clock,
      [&](const cv::Mat& frame, std::int64_t k, double t_s) {
        res.rows.push_back(tracker.Process(frame, k, t_s));
        if (on_row) on_row(res.rows.back());
      },
      progress, 1);  // every frame: io::ProgressMeter throttles the redraws
  res.summary = tracker.summary();
  if (res.summary.ok + res.summary.reacquired == 0) {
    throw ProcessingError("nothing detected: no beacon found in any of the " + std::to_string(res.frames) + " frames");
  }
  return res;
}

DecodeResult DecodeOnly(const std::vector<std::string>& videos) {
  DecodeResult r;
  video::FrameSource source(videos);
  cv::Mat frame;
  const auto t0 = Clock::now();
  while (source.Read(&frame)) ++r.frames;
  r.wall_s = SecondsSince(t0);
  return r;
}

io::CsvWriter BeaconTrackCsv(const std::vector<BeaconFrameResult>& rows, int bit_depth) {
  (void)bit_depth;
  io::CsvWriter w({"frame", "t_s", "x_px", "y_px", "peak", "area_px", "status", "ncc", "sigma_x_px", "sigma_y_px"});
  for (const auto& r : rows) AppendBeaconTrackRow(&w, r);
  return w;
}

void AppendBeaconTrackRow(io::CsvWriter* out, const BeaconFrameResult& r) {
  io::CsvWriter& w = *out;
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

io::RunSummary BeaconRunResult::Summary(const BeaconTrackOptions& opt) const {
  const BeaconTrackSummary& s = summary;
  io::RunSummary out;
  out.CountRows(RowStatus::kOk, static_cast<std::size_t>(s.ok));
  out.CountRows(RowStatus::kReacquired, static_cast<std::size_t>(s.reacquired));
  out.CountRows(RowStatus::kPredicted, static_cast<std::size_t>(s.predicted));
  out.CountRows(RowStatus::kLost, static_cast<std::size_t>(s.lost));
  out.CountRows(RowStatus::kInvalid, static_cast<std::size_t>(s.invalid));
  if (frames > 0) {
    out.AddFigure("tracked frames", static_cast<double>(s.ok) / static_cast<double>(frames), "fraction",
                  std::to_string(s.ok) + " of " + std::to_string(frames) + " frames");
  }
  io::Json& d = out.details;
  d["video"] = {{"width_px", width_px}, {"height_px", height_px}, {"bit_depth", bit_depth}};
  d["frames"] = frames;
  d["status_counts"] = {{"ok", s.ok}, {"reacquired", s.reacquired}, {"lost", s.lost}, {"predicted", s.predicted},
                        {"invalid", s.invalid}};
  d["acquisitions"] = s.acquisitions;
  d["full_frame_searches"] = s.full_frame_searches;
  d["mean_ncc"] = s.mean_ncc();
  d["summary"] = SummaryJson();
  d["restarts"] = s.restarts;
  d["centroid_estimator"] = {{"per_lamp", s.per_lamp}, {"cluster", s.ok + s.reacquired - s.per_lamp}};
  d["options"] = opt.ToJson();
  return out;
}

nlohmann::json BeaconRunResult::SummaryJson() const {
  return {{"frames", frames}, {"mean_ncc", summary.mean_ncc()}, {"restarts", summary.restarts}};
}

}  // namespace rk::extract

// `rk-extract features` over the shared frame loop (frame_loop.h); see features_run.h.
#include "extract/features_run.h"

#include "formats/image_points.h"
#include "io/error.h"
#include "io/json_util.h"

namespace rk::extract {

FeatureRunResult RunFeatures(const std::vector<std::string>& videos, const formats::FrameClock& clock, const target::FeatureModel& model,
                             const FeatureTrackOptions& options, const std::function<void(std::int64_t)>& progress,
                             const std::function<void(const FeatureFrameResult&)>& on_row) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  FeatureRunResult res;
  FeatureTracker tracker(model, options);
  static_cast<VideoRunStats&>(res) = ForEachFrame(
      videos, clock,
      [&](const cv::Mat& frame, std::int64_t k, double t_s) {
        res.rows.push_back(tracker.Process(frame, k, t_s));
        if (on_row) on_row(res.rows.back());
      },
      progress, 1);  // every frame: io::ProgressMeter throttles the redraws
  res.summary = tracker.summary();
  if (res.summary.measured == 0) {
    std::string extra;
    if (res.summary.ambiguous > 0) {
      extra = " (" + std::to_string(res.summary.ambiguous) +
              " frames had an ambiguous identification: is the marker layout symmetric?)";
    }
    throw ProcessingError("nothing detected: the target's markers were not identified in any of the " +
                          std::to_string(res.frames) + " frames" + extra);
  }
  return res;
}

io::CsvWriter FeaturePointsCsv(const std::vector<FeatureFrameResult>& rows, const target::FeatureModel& model) {
  io::CsvWriter w(formats::ImagePointsColumns({"sigma_px", "ncc", "radius_px"}));
  for (const FeatureFrameResult& r : rows) AppendFeaturePointRows(&w, r, model);
  return w;
}

void AppendFeaturePointRows(io::CsvWriter* out, const FeatureFrameResult& r, const target::FeatureModel& model) {
  io::CsvWriter& w = *out;
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

io::RunSummary FeatureRunResult::Summary(const target::FeatureModel& model, const FeatureTrackOptions& opt) const {
  const FeatureTrackSummary& s = summary;
  io::RunSummary out;
  io::Json st = io::Json::object();
  for (int k = 0; k < 5; ++k) {
    out.CountRows(static_cast<RowStatus>(k), static_cast<std::size_t>(s.rows_by_status[static_cast<std::size_t>(k)]));
    st[RowStatusName(static_cast<RowStatus>(k))] = s.rows_by_status[static_cast<std::size_t>(k)];
  }
  if (s.ambiguous > 0) {
    out.Warn("ambiguous", std::to_string(s.ambiguous) +
                              " frames had an ambiguous identification and got no points "
                              "(a symmetric marker layout cannot be identified without tracking)");
  }
  if (out.TotalRows() > 0) {
    out.AddFigure("feature points ok",
                  static_cast<double>(out.Rows(RowStatus::kOk)) / static_cast<double>(out.TotalRows()), "fraction",
                  std::to_string(out.TotalRows()) + " rows");
  }
  io::Json& d = out.details;
  d["video"] = {{"width_px", width_px}, {"height_px", height_px}, {"bit_depth", bit_depth}};
  d["frames"] = frames;
  d["markers"] = model.size();
  d["status_counts"] = st;
  d["acquisitions"] = {{"tried", s.acquisitions}, {"ok", s.acquisitions_ok}, {"ambiguous", s.ambiguous}};
  d["rejected_by_constellation"] = s.rejected;
  d["frames_with_4_points"] = s.frames_with_4;
  d["mean_ncc"] = s.mean_ncc;
  d["summary"] = SummaryJson();
  d["options"] = opt.ToJson();
  return out;
}

nlohmann::json FeatureRunResult::SummaryJson() const {
  return {{"frames", frames}, {"mean_ncc", summary.mean_ncc}, {"frames_with_4_points", summary.frames_with_4}};
}

}  // namespace rk::extract

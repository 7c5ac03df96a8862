// `rk-extract silhouette` over the shared frame loop (frame_loop.h); see silhouette_run.h.
#include "extract/silhouette_run.h"

#include "formats/image_points.h"
#include "io/error.h"
#include "io/json_util.h"

namespace rk::extract {

SilhouetteRunResult RunSilhouette(const std::vector<std::string>& videos, const formats::FrameClock& clock,
                                  const SilhouetteOptions& opt, const std::function<void(std::int64_t)>& progress,
                                  const std::function<void(const SilhouetteFrameRow&)>& on_row) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  SilhouetteRunResult res;
  static_cast<VideoRunStats&>(res) = ForEachFrame(
      videos, clock,
      [&](const cv::Mat& frame, std::int64_t k, double t_s) {
        SilhouetteFrameRow row;
        row.frame = k;
        row.t_s = t_s;
        row.result = ExtractSilhouette(frame, opt);
        ++res.by_status[static_cast<std::size_t>(row.result.status)];
        res.rows.push_back(row);
        if (on_row) on_row(res.rows.back());
      },
      progress, 1);  // every frame: io::ProgressMeter throttles the redraws
  if (res.by_status[static_cast<std::size_t>(SilhouetteStatus::kOk)] == 0) {
    throw ProcessingError("nothing detected: no frame of the " + std::to_string(res.frames) +
                          " gave the nose and tail points of a cylindrical target");
  }
  return res;
}

io::CsvWriter SilhouettePointsCsv(const std::vector<SilhouetteFrameRow>& rows) {
  io::CsvWriter w(formats::ImagePointsColumns({"detail", "width_px", "length_px"}));
  for (const SilhouetteFrameRow& r : rows) AppendSilhouettePointRows(&w, r);
  return w;
}

void AppendSilhouettePointRows(io::CsvWriter* out, const SilhouetteFrameRow& r) {
  io::CsvWriter& w = *out;
  const char* ids[3] = {"nose", "tail1", "tail2"};
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

io::RunSummary SilhouetteRunResult::Summary(const SilhouetteOptions& opt) const {
  using S = SilhouetteStatus;
  const auto n = [&](S s) { return by_status[static_cast<std::size_t>(s)]; };
  io::RunSummary out;
  const std::int64_t bad = frames - n(S::kOk);
  if (bad > 0) {
    out.Warn("frames_without_points",
             std::to_string(bad) + " of " + std::to_string(frames) + " frames without points (not_found " +
                 std::to_string(n(S::kNotFound)) + ", touches_border " + std::to_string(n(S::kTouchesBorder)) +
                 ", too_small " + std::to_string(n(S::kTooSmall)) + ", bad_fit " + std::to_string(n(S::kBadFit)) +
                 ")");
  }
  if (frames > 0) {
    out.AddFigure("frames with points", static_cast<double>(n(S::kOk)) / static_cast<double>(frames), "fraction",
                  std::to_string(n(S::kOk)) + " of " + std::to_string(frames) + " frames");
  }
  io::Json counts = io::Json::object();
  for (int s = 0; s < 5; ++s) counts[SilhouetteStatusName(static_cast<S>(s))] = by_status[static_cast<std::size_t>(s)];
  io::Json& d = out.details;
  d["video"] = {{"width_px", width_px}, {"height_px", height_px}, {"bit_depth", bit_depth}};
  d["frames"] = frames;
  d["status_counts"] = counts;
  d["summary"] = SummaryJson();
  d["options"] = opt.ToJson();
  return out;
}

nlohmann::json SilhouetteRunResult::SummaryJson() const {
  return {{"frames", frames}, {"frames_with_points", by_status[static_cast<std::size_t>(SilhouetteStatus::kOk)]}};
}

}  // namespace rk::extract

// `rk-extract points` over the shared frame loop; see points_run.h.
#include "extract/points_run.h"

#include <algorithm>

#include "formats/image_points.h"
#include "io/error.h"
#include "io/json_util.h"

namespace rk::extract {
namespace {

// Every seed inside the first frame (pixel centres −0.5 … size − 0.5).
void CheckSeedsInside(const formats::Seeds& seeds, int width, int height) {
  for (const formats::SeedRow& s : seeds.rows) {
    if (s.x_px < -0.5 || s.y_px < -0.5 || s.x_px > width - 0.5 || s.y_px > height - 0.5) {
      throw DataError(seeds.source, s.line, s.col_x,
                      "seed of '" + s.id + "' at (" + io::Json(s.x_px).dump() + ", " + io::Json(s.y_px).dump() +
                          ") is outside the " + std::to_string(width) + "x" + std::to_string(height) + " image");
    }
  }
}

}  // namespace

PointsRunResult RunPoints(const std::vector<std::string>& videos, const formats::FrameClock& clock,
                          const formats::Seeds& seeds, const PointsTrackOptions& options,
                          const std::function<void(std::int64_t)>& progress,
                          const std::function<void(const PointsFrameResult&)>& on_row) {
  PointsRunResult res;
  PointsTracker tracker(seeds, options);
  const formats::SeedRow* last = &seeds.rows.front();
  for (const formats::SeedRow& s : seeds.rows) {
    if (s.frame > last->frame) last = &s;
  }
  bool first = true;
  std::size_t sent = 0;  // rows passed to on_row
  std::int64_t last_frame = -1;
  static_cast<VideoRunStats&>(res) = ForEachFrame(
      videos, clock,
      [&](const cv::Mat& frame, std::int64_t k, double t_s) {
        if (first) {
          CheckSeedsInside(seeds, frame.cols, frame.rows);
          first = false;
        }
        res.rows.push_back(tracker.Process(frame, k, t_s));
        last_frame = k;
        if (on_row && k >= last->frame) {
          for (; sent < res.rows.size(); ++sent) on_row(res.rows[sent]);
        }
      },
      progress, 1);
  if (last_frame < last->frame) {
    throw DataError(seeds.source, last->line, last->col_frame,
                    "seed of '" + last->id + "' at frame " + std::to_string(last->frame) +
                        " is past the end of the recording (" + std::to_string(res.frames) + " frames)");
  }
  res.points = tracker.summary();
  res.seed_failures = tracker.seed_failures();
  std::int64_t measured = 0;
  for (const PointSummary& p : res.points) {
    measured += p.rows_by_status[static_cast<int>(RowStatus::kOk)] +
                p.rows_by_status[static_cast<int>(RowStatus::kReacquired)];
  }
  if (measured == 0) {
    std::string why;
    for (const PointsTracker::SeedFailure& f : res.seed_failures) {
      why += "; line " + std::to_string(f.line) + ", '" + f.id + "': " + f.why;
    }
    throw ProcessingError("nothing measured: no seeded point was found by its method in any of the " +
                          std::to_string(res.frames) + " frames" + (why.empty() ? "" : " (at the seeds" + why + ")"));
  }
  return res;
}

io::CsvWriter PointsTrackCsv(const std::vector<PointsFrameResult>& rows, const formats::Seeds& seeds) {
  io::CsvWriter w(formats::ImagePointsColumns({"sigma_x_px", "sigma_y_px", "score"}));
  for (const PointsFrameResult& r : rows) AppendPointsTrackRows(&w, r, seeds);
  return w;
}

void AppendPointsTrackRows(io::CsvWriter* out, const PointsFrameResult& r, const formats::Seeds& seeds) {
  io::CsvWriter& w = *out;
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const PointRow& p = r.points[i];
    w.Add(r.frame).Add(r.t_s, 9).Add(seeds.ids[i]);
    if (p.has_xy) {
      w.Add(p.px.x(), 4).Add(p.px.y(), 4);
    } else {
      w.AddEmpty().AddEmpty();
    }
    w.Add(RowStatusName(p.status));
    if (p.has_xy) {
      w.Add(p.sigma_px.x(), 5).Add(p.sigma_px.y(), 5);
    } else {
      w.AddEmpty().AddEmpty();
    }
    if (p.has_score) {
      w.Add(p.score, 4);
    } else {
      w.AddEmpty();
    }
    w.EndRow();
  }
}

io::RunSummary PointsRunResult::Summary(const PointsTrackOptions& opt) const {
  io::RunSummary out;
  io::Json per = io::Json::array();
  std::int64_t ok_rows = 0, rows_all = 0;
  for (const PointSummary& p : points) {
    io::Json st = io::Json::object();
    for (int k = 0; k < 5; ++k) {
      out.CountRows(static_cast<RowStatus>(k), static_cast<std::size_t>(p.rows_by_status[k]));
      st[RowStatusName(static_cast<RowStatus>(k))] = p.rows_by_status[k];
    }
    ok_rows += p.rows_by_status[0] + p.rows_by_status[1];
    for (int k = 0; k < 5; ++k) rows_all += p.rows_by_status[k];
    per.push_back({{"id", p.id}, {"method", formats::PointMethodName(p.method)}, {"status_counts", st},
                   {"seeds", p.seeds}, {"seed_failures", p.seed_failures}, {"restarts", p.restarts},
                   {"lookalikes_refused", p.lookalikes_refused}, {"ambiguous", p.ambiguous},
                   {"mean_score", p.scored ? p.score_sum / static_cast<double>(p.scored) : 0.0}});
  }
  for (const PointsTracker::SeedFailure& f : seed_failures) {
    out.Warn("seed-not-found", "seeds line " + std::to_string(f.line) + ": point '" + f.id +
                                   "' not found by its method at the seed (" + f.why + "): its row there is invalid");
  }
  if (rows_all > 0) {
    out.AddFigure("point rows measured", static_cast<double>(ok_rows) / static_cast<double>(rows_all), "fraction",
                  std::to_string(rows_all) + " rows of " + std::to_string(points.size()) + " points");
  }
  io::Json& d = out.details;
  d["video"] = {{"width_px", width_px}, {"height_px", height_px}, {"bit_depth", bit_depth}};
  d["frames"] = frames;
  d["points"] = per;
  d["summary"] = SummaryJson();
  d["options"] = opt.ToJson();
  return out;
}

nlohmann::json PointsRunResult::SummaryJson() const {
  std::int64_t ok = 0, total = 0;
  for (const PointSummary& p : points) {
    ok += p.rows_by_status[0] + p.rows_by_status[1];
    for (int k = 0; k < 5; ++k) total += p.rows_by_status[k];
  }
  return {{"frames", frames}, {"points", points.size()},
          {"measured_fraction", total ? static_cast<double>(ok) / static_cast<double>(total) : 0.0}};
}

}  // namespace rk::extract

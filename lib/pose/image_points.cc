// Image-points CSV reader; format in image_points.h.
#include "pose/image_points.h"

#include <set>

#include "io/error.h"

namespace rk::pose {

ImagePoints ReadImagePoints(const io::CsvTable& table, const target::FeatureModel& model) {
  ImagePoints out;
  out.source = table.name();
  const int c_t = table.RequireColumn("t_s");
  const int c_id = table.RequireColumn("id");
  const int c_x = table.RequireColumn("x_px");
  const int c_y = table.RequireColumn("y_px");
  const int c_frame = table.Column("frame");
  const int c_status = table.Column("status");
  const int c_sigma = table.Column("sigma_px");
  out.has_frame = c_frame >= 0;
  table.RequireNonDecreasing(c_t);
  out.rows = table.rows();

  std::set<std::int64_t> done_frames;  // frames already closed (to catch split frames)
  std::vector<char> seen(model.size(), 0);
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const double t = table.Double(r, c_t);
    std::optional<std::int64_t> frame;
    if (c_frame >= 0) frame = table.Int(r, c_frame);
    bool new_frame = out.frames.empty();
    if (!new_frame) {
      const PointFrame& cur = out.frames.back();
      new_frame = frame ? *frame != *cur.frame : t != cur.t_s;
    }
    if (new_frame) {
      if (frame) {
        if (!out.frames.empty()) {
          const std::int64_t prev = *out.frames.back().frame;
          done_frames.insert(prev);
          if (*frame < prev) throw table.CellError(r, c_frame, "frame numbers go backwards");
        }
        if (done_frames.count(*frame)) {
          throw table.CellError(r, c_frame,
                                "frame " + std::to_string(*frame) + " appears again: the rows of a frame must be contiguous");
        }
      }
      PointFrame f;
      f.frame = frame;
      f.t_s = t;
      f.first_line = table.Line(r);
      out.frames.push_back(f);
      std::fill(seen.begin(), seen.end(), 0);
    } else if (t != out.frames.back().t_s) {
      throw table.CellError(r, c_t, "frame " + std::to_string(*frame) + " has two different times");
    }
    PointFrame& f = out.frames.back();
    ++f.rows;

    const std::string id(table.Cell(r, c_id));
    const int idx = model.Find(id);
    if (idx < 0) {
      throw table.CellError(r, c_id,
                            "id '" + id + "' is not in the target model " + model.source + " (ids: " + model.IdList() + ")");
    }
    if (seen[static_cast<std::size_t>(idx)]) {
      throw table.CellError(r, c_id, "id '" + id + "' appears twice in one frame");
    }
    seen[static_cast<std::size_t>(idx)] = 1;

    RowStatus status = RowStatus::kOk;
    if (c_status >= 0 && !table.IsEmpty(r, c_status)) {
      if (!ParseRowStatus(table.Cell(r, c_status), &status)) {
        throw table.CellError(r, c_status,
                              "unknown status '" + std::string(table.Cell(r, c_status)) +
                                  "' (expected ok, reacquired, predicted, lost or invalid)");
      }
    }
    const auto x = table.OptionalDouble(r, c_x);
    const auto y = table.OptionalDouble(r, c_y);
    std::optional<double> sigma;
    if (c_sigma >= 0) {
      sigma = table.OptionalDouble(r, c_sigma);
      if (sigma && !(*sigma > 0.0)) throw table.CellError(r, c_sigma, "sigma_px must be > 0");
    }
    const bool measured = status == RowStatus::kOk || status == RowStatus::kReacquired;
    if (!x || !y || !measured) {
      ++out.unusable_rows;
      continue;
    }
    ImagePoint p;
    p.model_index = idx;
    p.px = {*x, *y};
    p.sigma_px = sigma;
    p.line = table.Line(r);
    p.col_x = table.CharColumn(r, c_x);
    f.points.push_back(p);
  }
  return out;
}

io::CsvRowRule ImagePointsRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.texts = {"id"};
  rule.optional_numbers = {"x_px", "y_px", "sigma_px"};
  rule.integers = {"frame"};
  return rule;
}

}  // namespace rk::pose

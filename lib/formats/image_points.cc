// Image-points reader; format in image_points.h.
#include "formats/image_points.h"

#include <map>

#include "io/error.h"
#include "io/number_text.h"

namespace rk::formats {
namespace {

// The row's 1σ: sigma_x_px,sigma_y_px (both needed), else sigma_px for both; each > 0 where given.
std::optional<Eigen::Vector2d> RowSigma(const io::CsvTable& t, std::size_t r, int c_sx, int c_sy, int c_s) {
  auto read = [&](int c, const char* name) -> std::optional<double> {
    if (c < 0) return std::nullopt;
    const std::optional<double> v = t.OptionalDouble(r, c);
    if (v && !(*v > 0.0)) throw t.CellError(r, c, std::string(name) + " must be > 0");
    return v;
  };
  const std::optional<double> sx = read(c_sx, "sigma_x_px"), sy = read(c_sy, "sigma_y_px");
  const std::optional<double> s = read(c_s, "sigma_px");
  if (sx && sy) return Eigen::Vector2d(*sx, *sy);
  if (s) return Eigen::Vector2d::Constant(*s);
  return std::nullopt;
}

}  // namespace

ImagePoints ReadImagePoints(const io::CsvTable& table) {
  ImagePoints out;
  out.source = table.name();
  const int c_t = table.RequireColumn("t_s");
  const int c_id = table.RequireColumn("id");
  const int c_x = table.RequireColumn("x_px");
  const int c_y = table.RequireColumn("y_px");
  const int c_frame = table.Column("frame");
  const int c_status = table.Column("status");
  const int c_sx = table.Column("sigma_x_px"), c_sy = table.Column("sigma_y_px"), c_s = table.Column("sigma_px");
  out.has_frame = c_frame >= 0;
  out.rows = table.rows();
  table.RequireNonDecreasing(c_t);
  std::map<std::int64_t, std::size_t> frame_line;  // frame → its first line (the rows of a frame are together)
  std::map<std::string, std::size_t, std::less<>> id_line;  // id → line, in the current frame
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const double t = table.Double(r, c_t);
    std::optional<std::int64_t> frame;
    if (c_frame >= 0) {
      frame = table.Int(r, c_frame);
      if (*frame < 0) throw table.CellError(r, c_frame, "frame must be >= 0");
    }
    const bool new_frame =
        out.frames.empty() || (frame ? out.frames.back().frame != frame : out.frames.back().t_s != t);
    if (new_frame) {
      if (frame) {
        const auto [it, inserted] = frame_line.emplace(*frame, table.Line(r));
        if (!inserted) {
          throw table.CellError(r, c_frame, "frame " + std::to_string(*frame) + " appears again (first at line " +
                                                std::to_string(it->second) + "): the rows of a frame must be together");
        }
        if (!out.frames.empty() && *frame < *out.frames.back().frame) {
          throw table.CellError(r, c_frame, "frame numbers go backwards");
        }
      }
      ImagePointFrame f;
      f.frame = frame;
      f.t_s = t;
      f.line = table.Line(r);
      out.frames.push_back(std::move(f));
      id_line.clear();
    }
    ImagePointFrame& f = out.frames.back();
    if (t != f.t_s) {
      throw table.CellError(r, c_t, "t_s " + io::NumberText(t) + " differs from " + io::NumberText(f.t_s) + " on line " +
                                        std::to_string(f.line) + " of the same frame");
    }
    ImagePoint p;
    p.id = std::string(table.Cell(r, c_id));
    if (p.id.empty()) throw table.CellError(r, c_id, "empty point id");
    const auto [seen, first] = id_line.emplace(p.id, table.Line(r));
    if (!first) {
      throw table.CellError(r, c_id, "point '" + p.id + "' given twice in one frame (also line " +
                                         std::to_string(seen->second) + ")");
    }
    if (c_status >= 0 && !table.IsEmpty(r, c_status) && !ParseRowStatus(table.Cell(r, c_status), &p.status)) {
      throw table.CellError(r, c_status, "unknown status '" + std::string(table.Cell(r, c_status)) +
                                             "' (expected ok, reacquired, predicted, lost or invalid)");
    }
    const std::optional<double> x = table.OptionalDouble(r, c_x), y = table.OptionalDouble(r, c_y);
    if (x && y) p.px = Eigen::Vector2d(*x, *y);
    p.sigma_px = RowSigma(table, r, c_sx, c_sy, c_s);
    p.line = table.Line(r);
    p.col_id = table.CharColumn(r, c_id);
    p.col_x = table.CharColumn(r, c_x);
    f.points.push_back(std::move(p));
  }
  return out;
}

std::vector<std::pair<std::string, Track>> TracksById(const ImagePoints& points) {
  std::vector<std::pair<std::string, Track>> out;
  std::map<std::string, std::size_t, std::less<>> index;
  for (const ImagePointFrame& f : points.frames) {
    for (const ImagePoint& p : f.points) {
      auto [it, fresh] = index.try_emplace(p.id, out.size());
      if (fresh) {
        Track t;
        t.source = points.source + " (id " + p.id + ")";
        t.has_frame = points.has_frame;
        out.emplace_back(p.id, std::move(t));
      }
      TrackRow r;
      r.frame = f.frame;
      r.t_s = f.t_s;
      r.px = p.px;
      r.status = p.px ? p.status : RowStatus::kLost;
      r.sigma_px = p.sigma_px;
      out[it->second].second.rows.push_back(r);
    }
  }
  return out;
}

io::CsvRowRule ImagePointsRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.texts = {"id"};
  rule.optional_numbers = {"x_px", "y_px", "sigma_px", "sigma_x_px", "sigma_y_px"};
  rule.integers = {"frame"};
  return rule;
}

std::vector<std::string> ImagePointsColumns(const std::vector<std::string>& extra) {
  std::vector<std::string> c = {"frame", "t_s", "id", "x_px", "y_px", "status"};
  c.insert(c.end(), extra.begin(), extra.end());
  return c;
}

}  // namespace rk::formats

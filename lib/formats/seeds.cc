// The seeds file; format in seeds.h.
#include "formats/seeds.h"

#include <array>
#include <map>
#include <utility>

#include "io/error.h"

namespace rk::formats {
namespace {

constexpr std::array<std::pair<PointMethod, const char*>, 5> kMethods{{
    {PointMethod::kCorrelation, "correlation"},
    {PointMethod::kCentroidDark, "centroid-dark"},
    {PointMethod::kCentroidBright, "centroid-bright"},
    {PointMethod::kQuadrant, "quadrant"},
    {PointMethod::kCircle, "circle"},
}};

std::optional<double> PositiveCell(const io::CsvTable& t, std::size_t r, int c, const char* name) {
  if (c < 0) return std::nullopt;
  const std::optional<double> v = t.OptionalDouble(r, c);
  if (v && !(*v > 0.0)) throw t.CellError(r, c, std::string(name) + " must be > 0");
  return v;
}

}  // namespace

const char* PointMethodName(PointMethod m) {
  for (const auto& [k, name] : kMethods) {
    if (k == m) return name;
  }
  return "?";
}

std::optional<PointMethod> ParsePointMethod(std::string_view s) {
  for (const auto& [k, name] : kMethods) {
    if (s == name) return k;
  }
  return std::nullopt;
}

std::string PointMethodList() {
  std::string out;
  for (std::size_t i = 0; i < kMethods.size(); ++i) {
    if (i > 0) out += i + 1 == kMethods.size() ? " or " : ", ";
    out += kMethods[i].second;
  }
  return out;
}

Seeds ReadSeeds(const io::CsvTable& t) {
  Seeds out;
  out.source = t.name();
  const int c_id = t.RequireColumn("id"), c_frame = t.RequireColumn("frame");
  const int c_x = t.RequireColumn("x_px"), c_y = t.RequireColumn("y_px"), c_m = t.RequireColumn("method");
  const int c_size = t.Column("size_px"), c_search = t.Column("search_px");
  std::map<std::pair<std::string, std::int64_t>, std::size_t> seen;  // (id, frame) → line
  std::map<std::string, std::pair<PointMethod, std::size_t>, std::less<>> method_of;  // id → method, line
  for (std::size_t r = 0; r < t.rows(); ++r) {
    SeedRow s;
    s.id = std::string(t.Cell(r, c_id));
    if (s.id.empty()) throw t.CellError(r, c_id, "empty point id");
    s.frame = t.Int(r, c_frame);
    if (s.frame < 0) throw t.CellError(r, c_frame, "frame must be >= 0");
    s.x_px = t.Double(r, c_x);
    s.y_px = t.Double(r, c_y);
    const std::string_view m = t.Cell(r, c_m);
    const std::optional<PointMethod> method = ParsePointMethod(m);
    if (!method) {
      throw t.CellError(r, c_m, "unknown method '" + std::string(m) + "' (one of " + PointMethodList() + ")");
    }
    s.method = *method;
    s.size_px = PositiveCell(t, r, c_size, "size_px");
    s.search_px = PositiveCell(t, r, c_search, "search_px");
    s.line = t.Line(r);
    s.col_frame = t.CharColumn(r, c_frame);
    s.col_x = t.CharColumn(r, c_x);
    const auto [it, fresh] = seen.emplace(std::make_pair(s.id, s.frame), s.line);
    if (!fresh) {
      throw t.CellError(r, c_id, "point '" + s.id + "' is seeded twice at frame " + std::to_string(s.frame) +
                                     " (first on line " + std::to_string(it->second) + ")");
    }
    const auto [mt, first] = method_of.emplace(s.id, std::make_pair(s.method, s.line));
    if (first) {
      out.ids.push_back(s.id);
    } else if (mt->second.first != s.method) {
      throw t.CellError(r, c_m, "point '" + s.id + "' was seeded with method " + PointMethodName(mt->second.first) +
                                    " on line " + std::to_string(mt->second.second) + ": a point keeps its method");
    }
    out.rows.push_back(std::move(s));
  }
  if (out.rows.empty()) throw DataError(t.name(), t.header_line(), 0, "no seeds (a header and no rows)");
  return out;
}

Seeds ReadSeeds(const std::string& path) { return ReadSeeds(io::CsvTable::Read(path)); }

std::vector<std::string> SeedsColumns() { return {"id", "frame", "x_px", "y_px", "method", "size_px", "search_px"}; }

}  // namespace rk::formats

// Located-target writer and reader; format in located.h.
#include "formats/located.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "geo/angles.h"
#include "formats/vector_cells.h"
#include "io/error.h"

namespace rk::formats {
namespace {

constexpr int kTimeDecimals = 9;
constexpr int kAngleDecimals = 9;      // 1e-9° = 3.6e-6″
constexpr int kLengthDecimals = 6;     // µm
constexpr int kGeodeticDecimals = 10;  // 1e-10° ≈ 11 µm
constexpr int kCorrelationDecimals = 6;

std::vector<std::string> Columns(const LocatedLayout& l) {
  std::vector<std::string> c;
  if (l.frame) c.push_back("frame");
  c.push_back("t_s");
  if (l.id) c.push_back("id");
  for (const char* n : {"az_deg", "el_deg", "range_m", "e_m", "n_m", "u_m", "status"}) c.push_back(n);
  if (l.locate_extras) {
    for (const char* n : {"range_status", "boresight_az_deg", "boresight_el_deg"}) c.push_back(n);
  }
  for (const char* n : {"sigma_az_deg", "sigma_el_deg", "sigma_range_m"}) c.push_back(n);
  if (l.sigma_enu) {
    for (const char* n : {"sigma_e_m", "sigma_n_m", "sigma_u_m"}) c.push_back(n);
  }
  if (l.corr) c.push_back("corr_az_el");
  if (l.geodetic) {
    for (const char* n : {"lat_deg", "lon_deg", "h_m"}) c.push_back(n);
  }
  return c;
}

std::optional<double> Deg(const std::optional<double>& rad) {
  return rad ? std::optional<double>(geo::RadToDeg(*rad)) : std::nullopt;
}

std::optional<double> Part(const std::optional<Eigen::Vector3d>& v, int i) {
  return v ? std::optional<double>((*v)(i)) : std::nullopt;
}

}  // namespace

LocatedWriter::LocatedWriter(const LocatedLayout& layout) : layout_(layout), w_(Columns(layout)) {}

void LocatedWriter::Add(const LocatedRecord& row) {
  if (layout_.frame) {
    if (row.frame) {
      w_.Add(*row.frame);
    } else {
      w_.AddEmpty();
    }
  }
  w_.Add(row.t_s, kTimeDecimals);
  if (layout_.id) w_.Add(row.id);
  w_.Add(Deg(row.az_rad), kAngleDecimals).Add(Deg(row.el_rad), kAngleDecimals);
  w_.Add(row.range_m, kLengthDecimals);
  for (int i = 0; i < 3; ++i) w_.Add(Part(row.enu_m, i), kLengthDecimals);
  w_.Add(RowStatusName(row.status));
  if (layout_.locate_extras) {
    w_.Add(row.range_status);
    w_.Add(Deg(row.boresight_az_rad), kAngleDecimals).Add(Deg(row.boresight_el_rad), kAngleDecimals);
  }
  w_.Add(Deg(row.sigma_az_rad), layout_.sigma_angle_decimals).Add(Deg(row.sigma_el_rad), layout_.sigma_angle_decimals);
  w_.Add(row.sigma_range_m, layout_.sigma_length_decimals);
  if (layout_.sigma_enu) {
    for (int i = 0; i < 3; ++i) w_.Add(Part(row.sigma_enu_m, i), layout_.sigma_length_decimals);
  }
  if (layout_.corr) w_.Add(row.corr_az_el, kCorrelationDecimals);
  if (layout_.geodetic) {
    const auto& g = row.geodetic;
    w_.Add(g ? std::optional<double>(g->lat_deg) : std::nullopt, kGeodeticDecimals);
    w_.Add(g ? std::optional<double>(g->lon_deg) : std::nullopt, kGeodeticDecimals);
    w_.Add(g ? std::optional<double>(g->h_m) : std::nullopt, kLengthDecimals);
  }
  w_.EndRow();
}

namespace {

// The position columns of LocatedRead::kPositions; the WGS-84 ones are required.
struct PositionColumns {
  int enu[3] = {-1, -1, -1}, sigma[3] = {-1, -1, -1}, geo[3] = {-1, -1, -1};
};

PositionColumns FindPositionColumns(const io::CsvTable& table) {
  PositionColumns p;
  const char* enu[3] = {"e_m", "n_m", "u_m"};
  const char* sigma[3] = {"sigma_e_m", "sigma_n_m", "sigma_u_m"};
  const char* geo[3] = {"lat_deg", "lon_deg", "h_m"};
  for (int k = 0; k < 3; ++k) {
    p.enu[k] = table.Column(enu[k]);
    p.sigma[k] = table.Column(sigma[k]);
    p.geo[k] = table.Column(geo[k]);
    if (p.geo[k] < 0) {
      throw DataError(table.name(), table.header_line(), 1,
                      "no WGS-84 columns lat_deg, lon_deg, h_m: a located target without its station's position "
                      "(rk-locate writes them with --station)");
    }
  }
  return p;
}

void ReadPositions(const io::CsvTable& table, std::size_t i, const PositionColumns& p, LocatedRecord* r) {
  r->enu_m = internal::VectorCells(table, i, p.enu);
  r->sigma_enu_m = internal::VectorCells(table, i, p.sigma);
  if (r->sigma_enu_m) {
    for (int k = 0; k < 3; ++k) {
      if ((*r->sigma_enu_m)(k) < 0.0) throw table.CellError(i, p.sigma[k], "a 1-sigma must not be negative");
    }
  }
  const std::optional<Eigen::Vector3d> g = internal::VectorCells(table, i, p.geo);
  if (!g) return;
  if (!((*g)(0) >= -90.0 && (*g)(0) <= 90.0)) throw table.CellError(i, p.geo[0], "latitude must be in [-90, 90]");
  if (!((*g)(1) >= -180.0 && (*g)(1) <= 360.0)) throw table.CellError(i, p.geo[1], "longitude must be in [-180, 360]");
  r->geodetic = geo::Geodetic{(*g)(0), (*g)(1), (*g)(2)};
}

}  // namespace

LocatedFile ReadLocated(const io::CsvTable& table, LocatedRead what) {
  LocatedFile out;
  out.source = table.name();
  const int c_t = table.RequireColumn("t_s"), c_az = table.RequireColumn("az_deg"),
            c_el = table.RequireColumn("el_deg");
  const int c_r = table.Column("range_m"), c_st = table.Column("status");
  const int c_saz = table.Column("sigma_az_deg"), c_sel = table.Column("sigma_el_deg"),
            c_sr = table.Column("sigma_range_m"), c_corr = table.Column("corr_az_el");
  out.has_range = c_r >= 0;
  out.has_sigma = c_saz >= 0 && c_sel >= 0;
  const int c_id = table.Column("id");
  out.has_id = c_id >= 0;
  const std::optional<PositionColumns> positions =
      what == LocatedRead::kPositions ? std::optional<PositionColumns>(FindPositionColumns(table)) : std::nullopt;
  std::map<std::string, std::pair<double, std::size_t>, std::less<>> last;  // id → its last t_s, line
  if (out.has_id) {
    table.RequireNonDecreasing(c_t);
  } else {
    table.RequireIncreasing(c_t);
  }
  auto positive = [&](std::size_t i, int c, const char* name) -> std::optional<double> {
    if (c < 0) return std::nullopt;
    const std::optional<double> v = table.OptionalDouble(i, c);
    if (v && !(*v > 0.0)) throw table.CellError(i, c, std::string(name) + " must be > 0");
    return v;
  };
  out.rows.reserve(table.rows());
  for (std::size_t i = 0; i < table.rows(); ++i) {
    LocatedRecord r;
    r.line = table.Line(i);
    r.t_s = table.Double(i, c_t);
    if (out.has_id) {
      r.id = std::string(table.Cell(i, c_id));
      if (r.id.empty()) throw table.CellError(i, c_id, "empty id");
      const auto [it, first] = last.try_emplace(r.id, r.t_s, r.line);
      if (!first && !(r.t_s > it->second.first)) {
        throw table.CellError(i, c_t, "time of '" + r.id + "' does not increase (line " +
                                          std::to_string(it->second.second) + " has the same)");
      }
      it->second = {r.t_s, r.line};
    }
    if (c_st >= 0 && !table.IsEmpty(i, c_st) && !ParseRowStatus(table.Cell(i, c_st), &r.status)) {
      throw table.CellError(i, c_st, "unknown status");
    }
    const std::optional<double> a = table.OptionalDouble(i, c_az), e = table.OptionalDouble(i, c_el);
    if (a) r.az_rad = geo::DegToRad(*a);
    if (e) r.el_rad = geo::DegToRad(*e);
    if (c_r >= 0) r.range_m = table.OptionalDouble(i, c_r);
    const std::optional<double> saz = positive(i, c_saz, "sigma_az_deg"), sel = positive(i, c_sel, "sigma_el_deg");
    if (saz) r.sigma_az_rad = geo::DegToRad(*saz);
    if (sel) r.sigma_el_rad = geo::DegToRad(*sel);
    r.sigma_range_m = positive(i, c_sr, "sigma_range_m");
    if (c_corr >= 0) {
      r.corr_az_el = table.OptionalDouble(i, c_corr);
      if (r.corr_az_el && !(std::abs(*r.corr_az_el) <= 1.0)) {
        throw table.CellError(i, c_corr, "corr_az_el must be in [-1, 1]");
      }
    }
    if (positions) ReadPositions(table, i, *positions, &r);
    out.rows.push_back(std::move(r));
  }
  return out;
}

std::vector<std::string> LocatedFile::Ids() const {
  std::vector<std::string> ids;
  for (const LocatedRecord& r : rows) {
    if (std::find(ids.begin(), ids.end(), r.id) == ids.end()) ids.push_back(r.id);
  }
  if (ids.empty()) ids.push_back("");
  return ids;
}

io::CsvRowRule LocatedRowRule(LocatedRead what) {
  io::CsvRowRule rule;
  rule.numbers = {"t_s"};
  rule.optional_numbers = {"az_deg", "el_deg", "range_m", "sigma_az_deg", "sigma_el_deg", "sigma_range_m", "corr_az_el"};
  if (what == LocatedRead::kPositions) {
    for (const char* c : {"e_m", "n_m", "u_m", "sigma_e_m", "sigma_n_m", "sigma_u_m", "lat_deg", "lon_deg", "h_m"}) {
      rule.optional_numbers.push_back(c);
    }
  }
  // Non-decreasing overall (a points track's ids share their frames' times), strictly increasing per id, or over
  // the whole file when it has no id column: a repeated time is a duplicated record, dropped with a warning.
  rule.non_decreasing = "t_s";
  rule.increasing_per = "id";
  rule.texts = {"id"};
  return rule;
}

}  // namespace rk::formats

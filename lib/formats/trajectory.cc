// Trajectory reader; format in trajectory.h.
#include "formats/trajectory.h"

#include <map>

#include "formats/vector_cells.h"
#include "io/error.h"

namespace rk::formats {
namespace {

struct TrajectoryColumnsAt {
  int t = -1, id = -1, enu[3] = {-1, -1, -1}, lat = -1, lon = -1, h = -1, sigma[3] = {-1, -1, -1}, n = -1, status = -1,
      rms = -1;
};

TrajectoryColumnsAt FindColumns(const io::CsvTable& table) {
  TrajectoryColumnsAt c;
  c.t = table.RequireColumn("t_s");
  const std::vector<std::string>& names = TrajectoryColumns();
  for (int k = 0; k < 3; ++k) c.enu[k] = table.RequireColumn(names[k]);
  c.lat = table.RequireColumn("lat_deg");
  c.lon = table.RequireColumn("lon_deg");
  c.h = table.RequireColumn("h_m");
  for (int k = 0; k < 3; ++k) c.sigma[k] = table.RequireColumn(names[6 + k]);
  c.n = table.RequireColumn("n_stations");
  c.status = table.RequireColumn("status");
  c.rms = table.Column("rms_residual_arcsec");
  c.id = table.Column("id");
  return c;
}

std::optional<geo::Geodetic> Wgs84(const io::CsvTable& table, std::size_t i, const TrajectoryColumnsAt& c,
                                   RowStatus status) {
  const int cols[3] = {c.lat, c.lon, c.h};
  if (!RowStatusHasValues(status)) return std::nullopt;  // lost, invalid: empty by SPEC, never placed
  for (int col : cols) {
    if (table.IsEmpty(i, col)) {
      throw table.CellError(i, col, std::string("empty, but the row's status '") + RowStatusName(status) +
                                        "' has a position");
    }
  }
  const geo::Geodetic g{table.Double(i, c.lat), table.Double(i, c.lon), table.Double(i, c.h)};
  if (!(g.lat_deg >= -90.0 && g.lat_deg <= 90.0)) throw table.CellError(i, c.lat, "latitude must be in [-90, 90]");
  if (!(g.lon_deg >= -180.0 && g.lon_deg <= 360.0)) throw table.CellError(i, c.lon, "longitude must be in [-180, 360]");
  return g;
}

}  // namespace

TrajectoryFile ReadTrajectory(const io::CsvTable& table) {
  TrajectoryFile out;
  out.source = table.name();
  const TrajectoryColumnsAt c = FindColumns(table);
  out.has_id = c.id >= 0;
  table.RequireNonDecreasing(c.t);
  std::map<std::string, std::pair<double, std::size_t>, std::less<>> last;  // id → its last t_s, line
  out.rows.reserve(table.rows());
  for (std::size_t i = 0; i < table.rows(); ++i) {
    TrajectoryRecord r;
    r.line = table.Line(i);
    r.t_s = table.Double(i, c.t);
    if (out.has_id) {
      r.id = std::string(table.Cell(i, c.id));
      if (r.id.empty()) throw table.CellError(i, c.id, "empty id");
    }
    const auto [it, first] = last.try_emplace(r.id, r.t_s, r.line);
    if (!first && !(r.t_s > it->second.first)) {
      throw table.CellError(i, c.t, (out.has_id ? "time of '" + r.id + "'" : std::string("time")) +
                                        " does not increase (line " + std::to_string(it->second.second) +
                                        " has the same)");
    }
    it->second = {r.t_s, r.line};
    if (!ParseRowStatus(table.Cell(i, c.status), &r.status)) throw table.CellError(i, c.status, "unknown status");
    r.enu_m = internal::VectorCells(table, i, c.enu);
    r.geodetic = Wgs84(table, i, c, r.status);
    r.sigma_enu_m = internal::VectorCells(table, i, c.sigma);
    if (r.sigma_enu_m) {
      for (int k = 0; k < 3; ++k) {
        if ((*r.sigma_enu_m)(k) < 0.0) throw table.CellError(i, c.sigma[k], "a 1-sigma must not be negative");
      }
    }
    if (!table.IsEmpty(i, c.n)) {
      const std::int64_t n = table.Int(i, c.n);
      if (n < 0) throw table.CellError(i, c.n, "n_stations must not be negative");
      r.n_stations = static_cast<int>(n);
    }
    if (c.rms >= 0) r.rms_residual_arcsec = table.OptionalDouble(i, c.rms);
    out.rows.push_back(std::move(r));
  }
  return out;
}

io::CsvRowRule TrajectoryRowRule() {
  io::CsvRowRule rule;
  rule.numbers = {"t_s"};
  rule.optional_numbers = {"e_m", "n_m", "u_m", "lat_deg", "lon_deg", "h_m", "sigma_e_m", "sigma_n_m", "sigma_u_m",
                           "rms_residual_arcsec"};
  rule.optional_integers = {"n_stations"};
  rule.texts = {"status", "id"};
  // Non-decreasing overall (the trajectories of several ids share the output times), strictly increasing per id
  // or over a file without ids, as ReadTrajectory requires: a duplicated record is skipped, not a stop.
  rule.non_decreasing = "t_s";
  rule.increasing_per = "id";
  return rule;
}

}  // namespace rk::formats

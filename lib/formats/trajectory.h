// Trajectory (SPEC.md §2.1 and §7: `t_s,e_m,n_m,u_m,lat_deg,lon_deg,h_m,sigma_e_m,sigma_n_m,sigma_u_m,n_stations,
// status` + `rms_residual_arcsec`; + `id` when the located files carry ids, one trajectory per id): written by
// rk-intersect (intersect::TrajectoryCsv, with these column names and its own after them), read by rk-export.
// Positions in the origin's ENU frame (m) and WGS-84 (degrees, ellipsoidal height in m); 1σ per ENU axis (m).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geo/wgs84.h"
#include "io/csv.h"
#include "io/row_status.h"

namespace rk::formats {

// The SPEC columns after t_s (and id), in the order rk-intersect writes them.
inline const std::vector<std::string>& TrajectoryColumns() {
  static const std::vector<std::string> columns = {"e_m",       "n_m",       "u_m",       "lat_deg",
                                                   "lon_deg",   "h_m",       "sigma_e_m", "sigma_n_m",
                                                   "sigma_u_m", "n_stations", "status",   "rms_residual_arcsec"};
  return columns;
}

struct TrajectoryRecord {
  double t_s = 0.0;
  std::string id;  // "" without an id column
  std::optional<Eigen::Vector3d> enu_m;
  std::optional<geo::Geodetic> geodetic;     // the WGS-84 columns: present exactly where the status has values
  std::optional<Eigen::Vector3d> sigma_enu_m;
  std::optional<double> rms_residual_arcsec;
  int n_stations = 0;
  RowStatus status = RowStatus::kOk;
  std::size_t line = 0;  // where the row is (reading)
};

struct TrajectoryFile {
  std::string source;
  bool has_id = false;  // an id column: one trajectory per id
  std::vector<TrajectoryRecord> rows;
};

// Reads every row (DataError at file:line:col): the SPEC columns present (rms_residual_arcsec and id may be
// absent); t_s not decreasing over the file and increasing per id (without an id column: increasing); an id not
// empty where the column is; status in the SPEC vocabulary; a row whose status has values (ok, reacquired,
// predicted: RowStatusHasValues) has lat_deg, lon_deg and h_m, latitude in [-90, 90], longitude in [-180, 360];
// σ not negative.
TrajectoryFile ReadTrajectory(const io::CsvTable& table);
// The cells ReadTrajectory needs of every row (io::CsvReadOptions::rule, --bad-rows skip): t_s a number that does
// not go back, the numbers numbers or empty, a status.
io::CsvRowRule TrajectoryRowRule();

}  // namespace rk::formats

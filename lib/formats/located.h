// Located target (SPEC.md §2.1 `t_s,az_deg,el_deg,range_m,e_m,n_m,u_m,status` + 1σ, WGS-84 and corr_az_el):
// written by rk-locate (locate::LocatedCsv) and rk-sim multistation, read by rk-intersect
// (intersect::StationTrack) and, with its positions, by rk-export. Angles are radians here, degrees in the file.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geo/wgs84.h"
#include "io/csv.h"
#include "io/row_status.h"

namespace rk::formats {

struct LocatedRecord {
  std::optional<std::int64_t> frame;  // written (LocatedLayout::frame); not read
  double t_s = 0.0;
  std::string id;                     // the point's id (LocatedLayout::id, a points track's); "" without
  std::optional<double> az_rad, el_rad, range_m;
  std::optional<Eigen::Vector3d> enu_m;
  RowStatus status = RowStatus::kOk;
  // rk-locate's own columns (LocatedLayout::locate_extras): the range's status and the logged boresight.
  std::string range_status;
  std::optional<double> boresight_az_rad, boresight_el_rad;
  // 1σ (rad, m) and the correlation of the azimuth and elevation errors.
  std::optional<double> sigma_az_rad, sigma_el_rad, sigma_range_m;
  std::optional<Eigen::Vector3d> sigma_enu_m;
  std::optional<double> corr_az_el;
  std::optional<geo::Geodetic> geodetic;  // WGS-84 of enu_m
  std::size_t line = 0;                   // where the row is (reading)

  // A line of sight to use: both angles and status ok or reacquired (or no status column).
  bool measured() const {
    return az_rad && el_rad && (status == RowStatus::kOk || status == RowStatus::kReacquired);
  }
};

// Which columns a writer gives, in SPEC order: [frame,]t_s[,id],az_deg,el_deg,range_m,e_m,n_m,u_m,status
// [,range_status,boresight_az_deg,boresight_el_deg],sigma_az_deg,sigma_el_deg,sigma_range_m
// [,sigma_e_m,sigma_n_m,sigma_u_m][,corr_az_el][,lat_deg,lon_deg,h_m].
struct LocatedLayout {
  bool frame = false;
  bool id = false;  // written after t_s
  bool locate_extras = false;
  bool sigma_enu = false;
  bool corr = false;
  bool geodetic = false;
  int sigma_angle_decimals = 9;   // of sigma_az_deg, sigma_el_deg
  int sigma_length_decimals = 9;  // of sigma_range_m, sigma_e_m, sigma_n_m, sigma_u_m
};

class LocatedWriter {
 public:
  explicit LocatedWriter(const LocatedLayout& layout);
  void Add(const LocatedRecord& row);
  io::CsvWriter& csv() { return w_; }
  io::CsvWriter Take() { return std::move(w_); }

 private:
  LocatedLayout layout_;
  io::CsvWriter w_;
};

struct LocatedFile {
  std::string source;
  bool has_range = false;  // a range_m column
  bool has_sigma = false;  // sigma_az_deg and sigma_el_deg columns
  bool has_id = false;     // an id column: one located series per id (rk-locate of a points track)
  std::vector<LocatedRecord> rows;
  // The distinct ids in order of first appearance ({""} without an id column).
  std::vector<std::string> Ids() const;
};

// What ReadLocated reads besides the lines of sight (angles, range, their σ): kPositions also the ENU position and
// its 1σ (e_m,n_m,u_m, sigma_e_m,sigma_n_m,sigma_u_m where present) and the WGS-84 columns lat_deg,lon_deg,h_m,
// which must then be in the header (rk-locate writes them with --station; DataError naming the file otherwise).
// A row's position is all three values or none (a row without a range has none).
enum class LocatedRead { kLinesOfSight, kPositions };

// Reads every row: t_s strictly increasing (one row per frame; with an id column, per id, and non-decreasing
// over the file: the rows of a frame together), an id not empty where the column is, status in the SPEC vocabulary, σ > 0 and
// corr_az_el in [−1, 1] where given (DataError at file:line:col).
LocatedFile ReadLocated(const io::CsvTable& table, LocatedRead what = LocatedRead::kLinesOfSight);
// The cells ReadLocated needs of every row (for io::CsvReadOptions::rule, --bad-rows skip): t_s a number that
// does not go back (a time repeated without an id column is ReadLocated's error, never a dropped row).
io::CsvRowRule LocatedRowRule(LocatedRead what = LocatedRead::kLinesOfSight);

}  // namespace rk::formats

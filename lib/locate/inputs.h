// Readers for the inputs of rk-locate (SPEC.md §2.1): beacon track, turret
// log, range log. Columns are found by name; every complaint names
// file:line:col. Angles are converted to radians here (file boundary).
#pragma once

#include "io/row_status.h"

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/csv.h"

namespace rk::locate {

// Per-frame status of a beacon track row (SPEC.md §2 statuses).
using TrackStatus = RowStatus;  // SPEC.md §2 statuses (io/row_status.h)
inline bool ParseTrackStatus(const std::string& text, TrackStatus* status) { return ParseRowStatus(text, status); }
inline std::string TrackStatusName(TrackStatus status) { return RowStatusName(status); }

struct TrackRow {
  std::optional<std::int64_t> frame;  // `frame` column when present
  double t_s = 0.0;                   // frame time (s since the trial epoch)
  std::optional<Eigen::Vector2d> px;  // beacon centre (x_px, y_px); nullopt = no measurement
  TrackStatus status = TrackStatus::kOk;
  std::optional<Eigen::Vector2d> sigma_px;  // 1σ of x_px, y_px (sigma_x_px, sigma_y_px) when the track has them
};

// Beacon track `frame,t_s,x_px,y_px[,...,status]`. Required: t_s, x_px, y_px.
// `status` is optional: without it (e.g. rk-sim's truth/beacon.csv) a row
// with both x_px and y_px is `ok` and one without is `lost`. A row whose
// x_px or y_px is empty is `lost` whatever its status says (no measurement).
// t_s must be non-decreasing. Optional `sigma_x_px,sigma_y_px` (rk-extract beacon's centroid 1σ): a row
// with both (finite, >= 0) carries them; rk-locate's σ propagation uses them instead of --sigma-px.
struct Track {
  std::string source;
  bool has_frame = false;
  std::vector<TrackRow> rows;
};
Track ReadTrack(const io::CsvTable& table);
// The cells ReadTrack needs of every row (for io::CsvReadOptions::rule, --bad-rows skip).
io::CsvRowRule TrackRowRule();

// Turret log `t_s,az_deg,el_deg` (boresight). Empty angle = sample not
// available (breaks the interpolation interval). el must be in [−90, 90];
// az any value (wrapped through 0/360). t_s non-decreasing.
// Held as three columns of doubles, NaN for an empty angle (24 bytes a sample: a 300 MB log of 7.3 M
// rows is 175 MB here, and BoresightSource::FromLog takes the columns over without a copy).
struct TurretLog {
  std::string source;
  std::vector<double> t_s;
  std::vector<double> az_rad, el_rad;  // NaN = empty
  std::size_t empty_samples = 0;
};
TurretLog ReadTurretLog(const io::CsvTable& table);
// The cells ReadTurretLog needs of every row.
io::CsvRowRule TurretLogRowRule();

// Range log `t_s,range_m[,status]`: status 0 (or empty, or no column) = ok,
// anything else = device error code; an empty range_m is a device error too.
// Usable ranges must be > 0. t_s non-decreasing.
struct RangeLog {
  std::string source;
  std::vector<double> t_s;
  std::vector<std::optional<double>> range_m;  // nullopt = device error
  std::size_t device_errors = 0;
};
RangeLog ReadRangeLog(const io::CsvTable& table);
// The cells ReadRangeLog needs of every row.
io::CsvRowRule RangeLogRowRule();

}  // namespace rk::locate

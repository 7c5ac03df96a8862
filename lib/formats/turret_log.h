// Turret or theodolite log (SPEC.md §2.1 `t_s,az_deg,el_deg`, the boresight): written by rk-capture and the
// simulators, read through track::BoresightSource by rk-locate, rk-attitude, rk-calibrate pointing. Angles
// are converted to radians here (file boundary).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/csv.h"

namespace rk::formats {

// Empty angle = sample not available (breaks the interpolation interval). el must be in [−90, 90]; az any
// value (wrapped through 0/360). t_s non-decreasing.
// Held as three columns of doubles, NaN for an empty angle (24 bytes a sample: a 300 MB log of 7.3 M rows is
// 175 MB here, and track::BoresightSource::FromLog takes the columns over without a copy).
struct TurretLog {
  std::string source;
  std::vector<double> t_s;
  std::vector<double> az_rad, el_rad;  // NaN = empty
  std::size_t empty_samples = 0;
};
TurretLog ReadTurretLog(const io::CsvTable& table);
// The cells ReadTurretLog needs of every row.
io::CsvRowRule TurretLogRowRule();
// The header of a turret log's writer.
inline std::vector<std::string> TurretLogColumns() { return {"t_s", "az_deg", "el_deg"}; }

}  // namespace rk::formats

// Radar plots from a radar feed (SPEC.md §2.1 "radar plots" with the ASTERIX columns, written by rk-import
// asterix) and radars.json (SPEC.md §1.1: a radar's name and WGS-84 position by its SAC/SIC). rk-register reads the
// plots through registration/input.h, which takes the same columns by name.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geo/wgs84.h"

namespace rk::formats {

// Columns of a plots file made from ASTERIX, in order: the radar plots' own, then the ASTERIX ones.
inline constexpr const char* kAsterixPlotsColumns =
    "t_s,radar,range_m,az_deg,el_deg,track_id,sac,sic,flight_level,height_m,mode3a,address,el_source";

// How el_deg was found: from a 3-D radar's height (I048/110), from the Mode C flight level taken as a height,
// or not at all (el_deg empty).
enum class ElevationSource : std::uint8_t { kNone, k3d, kModeC };
const char* ElevationSourceName(ElevationSource s);  // "", "3d", "mode_c"

// One plot; NaN / −1 = empty cell. 56 octets: a feed holds millions of them until they are sorted by time.
struct AsterixPlotRow {
  double t_s = 0.0;
  double range_m = 0.0, az_deg = 0.0;
  double el_deg = 0.0;       // NaN: a 2-D plot
  std::int32_t track_id = -1;
  std::uint16_t radar = 0;   // index into the writer's radar names
  std::uint8_t sac = 0, sic = 0;
  float flight_level = 0.0f;  // NaN: none (or not validated); quarters of a flight level are exact in a float
  float height_m = 0.0f;      // NaN: none; multiples of 25 ft (7.62 m), written to the centimetre
  std::int32_t address = -1;  // 24-bit, written as 6 hex digits
  std::int16_t mode3a = -1;   // 12-bit code, written as 4 octal digits
  ElevationSource el_source = ElevationSource::kNone;
};

// Writes the rows (in the order given) after `comments` ("# " lines), atomically ("-" = stdout).
void WriteAsterixPlots(const std::string& path, const std::vector<std::string>& radar_names,
                       const std::vector<AsterixPlotRow>& rows, const std::vector<std::string>& comments);

// radars.json: {"radars": [{"name": "r1", "sac": 25, "sic": 10, "lat_deg": .., "lon_deg": .., "h_m": ..}]}; the
// position is optional (all three or none). Errors name the file, line and column (exit 3; unreadable: exit 4).
struct RadarSite {
  std::string name;  // [A-Za-z0-9_.-]+, unique
  int sac = 0, sic = 0;
  std::optional<geo::Geodetic> position;
};
std::vector<RadarSite> ParseRadars(const std::string& text, const std::string& path);
std::vector<RadarSite> LoadRadars(const std::string& path);

}  // namespace rk::formats

// A trajectory as CZML 1.0 (Cesium; rk-export czml, docs/rk-export.md): a JSON array of packets,
//   {"id": "document", "name", "version": "1.0", "description", "clock": {interval, currentTime, ...}}
//   then one packet per path (id "trajectory", or "trajectory/<id>" for each id of the file):
//   {"id", "name", "description",
//    "availability": ["START/STOP", ...]             one ISO-8601 interval per run (contiguous placed rows),
//    "position": {"epoch", "interpolationAlgorithm": "LAGRANGE", "interpolationDegree": 1,
//                 "cartographicDegrees": [t, lon, lat, h, ...]}   t seconds after the epoch (= t_s), degrees,
//                                                                 h above the WGS-84 ellipsoid (m, as in the file),
//    "point", "path": the marker and the line (colour per path),
//    "properties": {"sigma_e_m"|"sigma_n_m"|"sigma_u_m": {"epoch", "number": [t, v, ...]},
//                   "status": [{"interval", "string"}, ...]}}
// CZML positions are time-tagged against an absolute epoch: without one (no --epoch-utc) t_s = 0 is put at
// kStandInEpoch, said in the document's description and as a warning by the tool.
#pragma once

#include <string>

#include "exports/export_common.h"
#include "exports/geo_track.h"
#include "io/options.h"

namespace rk::exports {

// The epoch CZML's times are written against when the trajectory has none (2000-01-01T00:00:00Z).
inline constexpr const char* kStandInEpoch = "2000-01-01T00:00:00Z";
inline constexpr double kStandInEpochUnixS = 946684800.0;

struct CzmlOptions {
  double path_width_px = 2.0;  // the paths' line width (pixels)
  double point_size_px = 6.0;  // the moving marker's size (pixels)

  static const io::OptionTable<CzmlOptions>& Table();
  bool Check(std::string* why) const { return Table().Check(*this, why); }
  io::Json ToJson() const { return Table().ToJson(*this); }
};

// The CZML document (UTF-8 JSON text: the array with one packet a line).
std::string CzmlText(const GeoTrack& track, const ExportHeader& header, const CzmlOptions& options);

}  // namespace rk::exports

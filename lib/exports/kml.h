// A trajectory as OGC KML 2.2 (rk-export kml; docs/rk-export.md): plain KML 2.2 elements only (no gx:
// extension), valid against the OGC schema ogckml22.xsd.
//
//   Document: name, description (source, epoch, heights), one line Style and one point Style per path, the Schema
//             "rk_sample" of the samples' data (t_s, status, sigma_e_m, sigma_n_m, sigma_u_m, n_stations,
//             h_ellipsoid_m)
//     Folder per path (id):
//       Placemark per run (contiguous placed rows, at least two): LineString of every placed row, altitudeMode
//                 absolute, TimeSpan of the run with an epoch, ExtendedData: rows, t_first_s, t_last_s
//       Folder "samples": Placemark per marked sample (SampleMarks): Point, TimeStamp with an epoch,
//                 ExtendedData/SchemaData with the row's σ and status
// Heights: KML's absolute altitude is above mean sea level (Google Earth: the EGM96 geoid); the files' h_m is
// above the WGS-84 ellipsoid. Written: h_m − N with N = --geoid-undulation (the geoid's height above the ellipsoid
// at the range, metres; default 0, i.e. ellipsoidal heights drawn as if above sea level: N metres too high).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "exports/export_common.h"
#include "exports/geo_track.h"
#include "io/options.h"

namespace rk::exports {

struct KmlOptions {
  double sample_interval_s = 1.0;   // a sample Placemark at most every this many seconds of a run (0: every row)
  double geoid_undulation_m = 0.0;  // N (m): geoid above the WGS-84 ellipsoid at the range; altitude = h_m − N
  double path_width_px = 2.0;       // the paths' line width (pixels)
  bool extrude = false;             // draw each path and sample down to the ground

  static const io::OptionTable<KmlOptions>& Table();
  bool Check(std::string* why) const { return Table().Check(*this, why); }
  io::Json ToJson() const { return Table().ToJson(*this); }
};

// The samples of `path` that get a Placemark: the first and last of each run, and between them every sample at
// least `interval_s` after the last one marked (every sample for 0). Indices into path.samples, increasing.
std::vector<std::size_t> SampleMarks(const GeoPath& path, double interval_s);

struct KmlCounts {
  std::size_t lines = 0;       // LineString Placemarks (runs of two or more samples)
  std::size_t placemarks = 0;  // sample Placemarks
};

// The KML document (UTF-8 text). `counts` (optional) gets what it holds.
std::string KmlText(const GeoTrack& track, const ExportHeader& header, const KmlOptions& options,
                    KmlCounts* counts = nullptr);

}  // namespace rk::exports

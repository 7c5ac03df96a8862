// Station ENU ↔ WGS-84 ↔ ECEF (SPEC.md §3: "Station frame: local ENU …; its geodetic position, where needed,
// is WGS-84 lat/lon/h"). GeographicLib (LocalCartesian, Geocentric) at the station's position: exact (no
// flat-earth approximation), ellipsoidal heights. The one place rangekit holds a geodetic position and the
// only module that includes GeographicLib (docs/architecture.md).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

namespace rk::geo {

// A geodetic position: latitude and longitude in degrees, height above the WGS-84 ellipsoid in metres.
struct Geodetic {
  double lat_deg = 0.0;  // [-90, 90]
  double lon_deg = 0.0;  // any (GeographicLib reduces it to [-180, 180))
  double h_m = 0.0;
};

// Earth-centred, Earth-fixed position (m) of `g` and, when R_ecef_enu is given, the rotation whose columns are
// the local east, north and up axes there, in ECEF (GeographicLib::Geocentric).
Eigen::Vector3d EcefFromGeodetic(const Geodetic& g, Eigen::Matrix3d* R_ecef_enu = nullptr);
Geodetic GeodeticFromEcef(const Eigen::Vector3d& x_ecef_m);

// Parses "LAT,LON,H" (degrees, degrees, metres); false with the reason in *why for a malformed text or a
// latitude outside [-90, 90], a longitude outside [-180, 360] or a non-finite value.
bool ParseGeodetic(const std::string& text, Geodetic* out, std::string* why);

// The ENU frame of SPEC.md §3 at a station (x east, y north, z up, origin at the station).
class LocalEnu {
 public:
  explicit LocalEnu(const Geodetic& origin);
  ~LocalEnu();
  LocalEnu(const LocalEnu&) = delete;
  LocalEnu& operator=(const LocalEnu&) = delete;
  LocalEnu(LocalEnu&&) noexcept;
  LocalEnu& operator=(LocalEnu&&) noexcept;

  Geodetic ToGeodetic(const Eigen::Vector3d& p_enu_m) const;
  Eigen::Vector3d ToEnu(const Geodetic& p) const;
  const Geodetic& origin() const { return origin_; }

 private:
  struct Impl;
  Geodetic origin_;
  std::unique_ptr<Impl> impl_;
};

// The elevation (rad, up from the site's horizontal plane) of the straight line that leaves `site` at azimuth
// `az_rad` (clockwise from north) and reaches ellipsoidal height `height_m` after the slant range `range_m`: a
// radar plot's elevation from a target height (a 3-D radar's, or Mode C). Geometric, on the WGS-84 ellipsoid
// (no refraction): a first value on the sphere of the Euler radius of curvature in that azimuth, then Newton
// steps on the exact height until it is within 0.1 mm. nullopt when no elevation in [−90°, 90°] reaches that
// height at that range (range_m <= 0, or the height is further above or below the site than the range).
std::optional<double> ElevationToHeight(const LocalEnu& site, double range_m, double az_rad, double height_m);

}  // namespace rk::geo

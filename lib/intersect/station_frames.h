// Station frames on WGS-84 (GeographicLib): each station's own ENU frame relative to the origin's
// (solver.h "Frames"), and origin ENU ↔ WGS-84 latitude, longitude, ellipsoidal height.
#pragma once

#include <memory>

#include "intersect/solver.h"

namespace rk::intersect {

struct Geodetic {
  double lat_deg = 0.0;  // WGS-84 latitude (degrees), [−90, 90]
  double lon_deg = 0.0;  // WGS-84 longitude (degrees)
  double h_m = 0.0;      // height above the ellipsoid (m)
};

// StationFrame of a station at `station` for the ENU frame at `origin`: M_i = R_iᵀ R_o, c_i = R_iᵀ(o − s_i)
// (R: ECEF from local ENU, GeographicLib::Geocentric), a_i = −M_iᵀ c_i.
StationFrame MakeStationFrame(const Geodetic& origin, const Geodetic& station);

// Origin ENU (m) → WGS-84 (GeographicLib::LocalCartesian). Holds the converter (no allocation per call).
class OriginFrame {
 public:
  explicit OriginFrame(const Geodetic& origin);
  ~OriginFrame();
  OriginFrame(const OriginFrame&) = delete;
  OriginFrame& operator=(const OriginFrame&) = delete;
  Geodetic ToGeodetic(const Eigen::Vector3d& p_enu) const;
  Eigen::Vector3d ToEnu(const Geodetic& g) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rk::intersect

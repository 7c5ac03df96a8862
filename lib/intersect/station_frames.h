// Station frames on WGS-84 (geo/wgs84.h): each station's own ENU frame relative to the origin's
// (solver.h "Frames"); origin ENU ↔ WGS-84 is geo::LocalEnu.
#pragma once

#include "geo/wgs84.h"
#include "intersect/solver.h"

namespace rk::intersect {

// StationFrame of a station at `station` for the ENU frame at `origin`: M_i = R_iᵀ R_o, c_i = R_iᵀ(o − s_i)
// (R: ECEF from local ENU, geo::EcefFromGeodetic), a_i = −M_iᵀ c_i.
StationFrame MakeStationFrame(const geo::Geodetic& origin, const geo::Geodetic& station);

}  // namespace rk::intersect

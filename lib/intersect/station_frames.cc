// Station frames on WGS-84; see station_frames.h.
#include "intersect/station_frames.h"

namespace rk::intersect {

StationFrame MakeStationFrame(const geo::Geodetic& origin, const geo::Geodetic& station) {
  Eigen::Matrix3d Ro, Rs;
  const Eigen::Vector3d o = geo::EcefFromGeodetic(origin, &Ro);
  const Eigen::Vector3d s = geo::EcefFromGeodetic(station, &Rs);
  StationFrame f;
  f.M = Rs.transpose() * Ro;
  f.c = Rs.transpose() * (o - s);
  f.a = -f.M.transpose() * f.c;
  return f;
}

}  // namespace rk::intersect

// Station frames from GeographicLib; see station_frames.h.
#include "intersect/station_frames.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <vector>

namespace rk::intersect {
namespace {

// ECEF position (m) and R_ecef_enu (columns east, north, up) of a WGS-84 point.
void Ecef(const Geodetic& g, Eigen::Vector3d* x, Eigen::Matrix3d* R) {
  std::vector<double> M(9);
  GeographicLib::Geocentric::WGS84().Forward(g.lat_deg, g.lon_deg, g.h_m, (*x)(0), (*x)(1), (*x)(2), M);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) (*R)(r, c) = M[3 * r + c];  // GeographicLib: row-major, ECEF = M · ENU
  }
}

}  // namespace

StationFrame MakeStationFrame(const Geodetic& origin, const Geodetic& station) {
  Eigen::Vector3d o, s;
  Eigen::Matrix3d Ro, Rs;
  Ecef(origin, &o, &Ro);
  Ecef(station, &s, &Rs);
  StationFrame f;
  f.M = Rs.transpose() * Ro;
  f.c = Rs.transpose() * (o - s);
  f.a = -f.M.transpose() * f.c;
  return f;
}

struct OriginFrame::Impl {
  GeographicLib::LocalCartesian lc;
};

OriginFrame::OriginFrame(const Geodetic& origin) : impl_(std::make_unique<Impl>()) {
  impl_->lc.Reset(origin.lat_deg, origin.lon_deg, origin.h_m);
}
OriginFrame::~OriginFrame() = default;

Geodetic OriginFrame::ToGeodetic(const Eigen::Vector3d& p_enu) const {
  Geodetic g;
  impl_->lc.Reverse(p_enu(0), p_enu(1), p_enu(2), g.lat_deg, g.lon_deg, g.h_m);
  return g;
}

Eigen::Vector3d OriginFrame::ToEnu(const Geodetic& g) const {
  Eigen::Vector3d p;
  impl_->lc.Forward(g.lat_deg, g.lon_deg, g.h_m, p(0), p(1), p(2));
  return p;
}

}  // namespace rk::intersect

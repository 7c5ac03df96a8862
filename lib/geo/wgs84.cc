// Station ENU ↔ WGS-84; see wgs84.h.
#include "geo/wgs84.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace rk::geo {

Eigen::Vector3d EcefFromGeodetic(const Geodetic& g, Eigen::Matrix3d* R_ecef_enu) {
  Eigen::Vector3d x;
  if (!R_ecef_enu) {
    GeographicLib::Geocentric::WGS84().Forward(g.lat_deg, g.lon_deg, g.h_m, x.x(), x.y(), x.z());
    return x;
  }
  std::vector<double> M(9);
  GeographicLib::Geocentric::WGS84().Forward(g.lat_deg, g.lon_deg, g.h_m, x.x(), x.y(), x.z(), M);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) (*R_ecef_enu)(r, c) = M[3 * r + c];  // GeographicLib: row-major, ECEF = M · ENU
  }
  return x;
}

Geodetic GeodeticFromEcef(const Eigen::Vector3d& x) {
  Geodetic g;
  GeographicLib::Geocentric::WGS84().Reverse(x.x(), x.y(), x.z(), g.lat_deg, g.lon_deg, g.h_m);
  return g;
}

bool ParseGeodetic(const std::string& text, Geodetic* out, std::string* why) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && item[used] == ' ') ++used;
    if (item.empty() || used != item.size() || !std::isfinite(x)) {
      *why = "'" + text + "' is not LAT,LON,H (three numbers: degrees, degrees, metres)";
      return false;
    }
    v.push_back(x);
  }
  if (v.size() != 3 || (!text.empty() && text.back() == ',')) {
    *why = "'" + text + "' is not LAT,LON,H (three numbers: degrees, degrees, metres)";
    return false;
  }
  if (v[0] < -90.0 || v[0] > 90.0) {
    *why = "latitude of '" + text + "' is outside [-90, 90] degrees";
    return false;
  }
  if (v[1] < -180.0 || v[1] > 360.0) {
    *why = "longitude of '" + text + "' is outside [-180, 360] degrees";
    return false;
  }
  *out = {v[0], v[1], v[2]};
  return true;
}

struct LocalEnu::Impl {
  GeographicLib::LocalCartesian lc;
};

LocalEnu::LocalEnu(const Geodetic& origin)
    : origin_(origin), impl_(std::make_unique<Impl>(Impl{GeographicLib::LocalCartesian(
                           origin.lat_deg, origin.lon_deg, origin.h_m, GeographicLib::Geocentric::WGS84())})) {}

LocalEnu::~LocalEnu() = default;
LocalEnu::LocalEnu(LocalEnu&&) noexcept = default;
LocalEnu& LocalEnu::operator=(LocalEnu&&) noexcept = default;

Geodetic LocalEnu::ToGeodetic(const Eigen::Vector3d& p) const {
  Geodetic g;
  impl_->lc.Reverse(p.x(), p.y(), p.z(), g.lat_deg, g.lon_deg, g.h_m);
  return g;
}

Eigen::Vector3d LocalEnu::ToEnu(const Geodetic& g) const {
  Eigen::Vector3d p;
  impl_->lc.Forward(g.lat_deg, g.lon_deg, g.h_m, p.x(), p.y(), p.z());
  return p;
}

std::optional<double> ElevationToHeight(const LocalEnu& site, double range_m, double az_rad, double height_m) {
  if (!(range_m > 0) || !std::isfinite(range_m) || !std::isfinite(height_m) || !std::isfinite(az_rad)) {
    return std::nullopt;
  }
  const GeographicLib::Geocentric& earth = GeographicLib::Geocentric::WGS84();
  const double a = earth.EquatorialRadius(), e2 = earth.Flattening() * (2 - earth.Flattening());
  const double s = std::sin(site.origin().lat_deg * M_PI / 180.0);
  const double w = 1 - e2 * s * s;
  const double meridian = a * (1 - e2) / (w * std::sqrt(w)), normal = a / std::sqrt(w);
  const double ca = std::cos(az_rad), sa = std::sin(az_rad);
  const double radius = 1.0 / (ca * ca / meridian + sa * sa / normal);  // Euler's radius in this azimuth
  const double ra = radius + site.origin().h_m, rt = radius + height_m;
  double sin_el = (rt * rt - ra * ra - range_m * range_m) / (2 * ra * range_m);
  if (!(std::abs(sin_el) <= 1.0 + 1e-9)) return std::nullopt;
  double el = std::asin(std::clamp(sin_el, -1.0, 1.0));
  for (int iter = 0; iter < 10; ++iter) {
    const double ce = std::cos(el);
    const Geodetic g = site.ToGeodetic(range_m * Eigen::Vector3d(ce * sa, ce * ca, std::sin(el)));
    const double f = g.h_m - height_m;
    if (std::abs(f) < 1e-4) return el;
    const double slope = ra * range_m * std::max(ce, 1e-6) / rt;  // dh/d(el) on the sphere
    el = std::clamp(el - f / slope, -M_PI / 2, M_PI / 2);
  }
  return std::nullopt;
}

}  // namespace rk::geo

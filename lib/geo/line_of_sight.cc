#include "geo/line_of_sight.h"

#include <cmath>

#include "geo/angles.h"

namespace rk::geo {

Eigen::Matrix3d RotationEnuFromTurret(double az_rad, double el_rad) {
  return RotationEnuFromTurretT<double>(az_rad, el_rad);
}

Eigen::Vector3d DirectionFromAzEl(double az_rad, double el_rad) {
  const double ce = std::cos(el_rad);
  return {std::sin(az_rad) * ce, std::cos(az_rad) * ce, std::sin(el_rad)};
}

AzEl AzElFromEnu(const Eigen::Vector3d& v) {
  AzEl out;
  out.az_rad = WrapTwoPi(std::atan2(v.x(), v.y()));
  out.el_rad = std::atan2(v.z(), std::hypot(v.x(), v.y()));
  return out;
}

}  // namespace rk::geo

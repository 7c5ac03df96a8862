// Exact line-of-sight geometry of SPEC.md §3 (no small-angle approximation).
//
// Station frame: local ENU (x east, y north, z up), origin at the turret /
// theodolite rotation centre. For boresight azimuth A (clockwise from north)
// and elevation E (up positive) the turret frame has axes, in ENU:
//   b = ( sinA cosE,  cosA cosE,  sinE)   boresight (image z)
//   r = ( cosA,      -sinA,       0   )   image x (right)
//   d = ( sinA sinE,  cosA sinE, -cosE)   image y (down)
// so R_enu_turret = [r d b] maps turret-frame vectors (x right, y down, z along
// the boresight) to ENU. A normalised image ray m = ((x-cx)/fx, (y-cy)/fy, 1)
// maps to ray_enu = m0 r + m1 d + m2 b.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace rk::geo {

// Columns r, d, b of SPEC.md §3. Angles in radians.
Eigen::Matrix3d RotationEnuFromTurret(double az_rad, double el_rad);

// The same for any scalar type with sin/cos found by argument-dependent lookup (e.g. ceres::Jet for
// automatic differentiation); RotationEnuFromTurret(double, double) is this with T = double.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationEnuFromTurretT(const T& az_rad, const T& el_rad) {
  using std::cos;
  using std::sin;
  const T sa = sin(az_rad), ca = cos(az_rad), se = sin(el_rad), ce = cos(el_rad);
  Eigen::Matrix<T, 3, 3> R;
  R(0, 0) = ca;
  R(1, 0) = -sa;
  R(2, 0) = T(0.0);  // r: image x (right)
  R(0, 1) = sa * se;
  R(1, 1) = ca * se;
  R(2, 1) = -ce;  // d: image y (down)
  R(0, 2) = sa * ce;
  R(1, 2) = ca * ce;
  R(2, 2) = se;  // b: boresight
  return R;
}

// Unit direction in ENU for an azimuth/elevation pair (radians).
Eigen::Vector3d DirectionFromAzEl(double az_rad, double el_rad);

struct AzEl {
  double az_rad = 0.0;  // [0, 2 pi), clockwise from north
  double el_rad = 0.0;  // [-pi/2, pi/2], up positive
};
// Azimuth/elevation of any non-zero ENU vector: az = atan2(e, n) mod 2 pi,
// el = atan2(u, hypot(e, n)).
AzEl AzElFromEnu(const Eigen::Vector3d& v_enu);

}  // namespace rk::geo

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

#include "geo/pointing.h"  // RotationEnuFromTurretT: the closed form below is written there

namespace rk::geo {

// Columns r, d, b of SPEC.md §3 (geo::RotationEnuFromTurretT, geo/pointing.h). Angles in radians.
Eigen::Matrix3d RotationEnuFromTurret(double az_rad, double el_rad);

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

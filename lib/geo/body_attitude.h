// Attitude of a rigid body relative to the station (SPEC.md §3 "Target attitude").
//
// Body frame: x forward (nose), y right, z down. Local NED at the station: x north, y east,
// z down. Attitude = aerospace Z-Y-X Euler angles of the body relative to NED:
//   R_ned_body = Rz(yaw) · Ry(pitch) · Rx(roll)
// yaw clockwise from north (seen from above), pitch nose-up, roll right-side-down; each
// Rk(a) is the right-handed rotation by a about axis k (R v rotates v, frames compose as
// R_ned_body · v_body = v_ned). Written out:
//   R_ned_body = [ cψcθ   cψsθsφ − sψcφ   cψsθcφ + sψsφ ]
//                [ sψcθ   sψsθsφ + cψcφ   sψsθcφ − cψsφ ]
//                [ −sθ    cθsφ            cθcφ          ]
// so yaw = atan2(R10, R00), pitch = atan2(−R20, hypot(R21, R22)), roll = atan2(R21, R22).
// Station frame (ENU, x east, y north, z up) and NED share the origin:
//   v_ned = R_ned_enu · v_enu,  R_ned_enu = [[0,1,0],[1,0,0],[0,0,−1]] (its own inverse).
// Ranges returned: yaw [0, 2π), pitch [−π/2, π/2], roll (−π, π]. Radians throughout.
// Header-only (inline): used by lib/sim (truth) and lib/pose (estimates).
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "geo/angles.h"

namespace rk::geo {

struct EulerZyx {
  double yaw_rad = 0.0;    // [0, 2π), clockwise from north
  double pitch_rad = 0.0;  // [−π/2, π/2], nose up
  double roll_rad = 0.0;   // (−π, π], right side down
};

inline Eigen::Matrix3d RotationNedFromEnu() {
  Eigen::Matrix3d R;
  R << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  return R;
}

// R_ned_body = Rz(yaw) · Ry(pitch) · Rx(roll).
inline Eigen::Matrix3d RotationNedFromBody(double yaw_rad, double pitch_rad, double roll_rad) {
  const double cy = std::cos(yaw_rad), sy = std::sin(yaw_rad);
  const double cp = std::cos(pitch_rad), sp = std::sin(pitch_rad);
  const double cr = std::cos(roll_rad), sr = std::sin(roll_rad);
  Eigen::Matrix3d R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,   //
      -sp, cp * sr, cp * cr;
  return R;
}
inline Eigen::Matrix3d RotationNedFromBody(const EulerZyx& e) {
  return RotationNedFromBody(e.yaw_rad, e.pitch_rad, e.roll_rad);
}

// Euler angles of a rotation matrix R_ned_body (orthonormal, det +1). At pitch ±90°
// (gimbal lock) yaw and roll are not separable; the split returned is then arbitrary.
inline EulerZyx EulerFromRotationNedBody(const Eigen::Matrix3d& R) {
  EulerZyx e;
  e.yaw_rad = WrapTwoPi(std::atan2(R(1, 0), R(0, 0)));
  e.pitch_rad = std::atan2(-R(2, 0), std::hypot(R(2, 1), R(2, 2)));
  e.roll_rad = WrapPi(std::atan2(R(2, 1), R(2, 2)));
  return e;
}

// Body attitude from a body-to-station rotation R_enu_body, and back.
inline EulerZyx EulerFromRotationEnuBody(const Eigen::Matrix3d& R_enu_body) {
  return EulerFromRotationNedBody(RotationNedFromEnu() * R_enu_body);
}
inline Eigen::Matrix3d RotationEnuFromBody(const EulerZyx& e) {
  return RotationNedFromEnu() * RotationNedFromBody(e);  // R_enu_ned = R_ned_enu
}

}  // namespace rk::geo

// The turret pointing model of SPEC.md §3.1: a real turret's azimuth zero is not north, its vertical
// axis is not vertical and its elevation axis is not square to it. With the logged angles A, E:
//
//   R_enu_turret(A, E) = Ry(tilt_east) · Rx(−tilt_north) · Rz(−(A + az_offset)) · Ry(el_axis_tilt) · Rx(E) · C
//   C = [[1, 0, 0], [0, 0, 1], [0, −1, 0]]     (columns: image x r, image y d, boresight b at A = E = 0)
//
// Rx, Ry, Rz are the standard right-handed rotations, multiplied as written. With every term zero this is
// SPEC.md §3's [r d b] (geo::RotationEnuFromTurretT). Terms, radians inside (degrees only in files):
//   az_offset     true azimuth = logged azimuth + az_offset (encoder zero / north alignment)
//   tilt_north    the top of the azimuth axis leans this far toward north (levelling)
//   tilt_east     … toward east
//   el_axis_tilt  positive lowers the right-hand end of the elevation axis (seen from behind the boresight)
// The camera's own misalignment (mount yaw/pitch/roll) is camera::CameraModel's: it is per camera, the
// pointing model is what all cameras on the turret share.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <type_traits>

namespace rk::geo {

struct PointingTerms {
  double az_offset_rad = 0.0;
  double tilt_north_rad = 0.0;
  double tilt_east_rad = 0.0;
  double el_axis_tilt_rad = 0.0;
  bool IsZero() const {
    return az_offset_rad == 0.0 && tilt_north_rad == 0.0 && tilt_east_rad == 0.0 && el_axis_tilt_rad == 0.0;
  }
};

// Standard right-handed rotations about x, y, z for any scalar with sin/cos found by argument-dependent
// lookup (double, ceres::Jet).
template <typename T>
Eigen::Matrix<T, 3, 3> RotX(const T& a) {
  using std::cos;
  using std::sin;
  const T c = cos(a), s = sin(a);
  Eigen::Matrix<T, 3, 3> R;
  R << T(1), T(0), T(0), T(0), c, -s, T(0), s, c;
  return R;
}
template <typename T>
Eigen::Matrix<T, 3, 3> RotY(const T& a) {
  using std::cos;
  using std::sin;
  const T c = cos(a), s = sin(a);
  Eigen::Matrix<T, 3, 3> R;
  R << c, T(0), s, T(0), T(1), T(0), -s, T(0), c;
  return R;
}
template <typename T>
Eigen::Matrix<T, 3, 3> RotZ(const T& a) {
  using std::cos;
  using std::sin;
  const T c = cos(a), s = sin(a);
  Eigen::Matrix<T, 3, 3> R;
  R << c, -s, T(0), s, c, T(0), T(0), T(0), T(1);
  return R;
}

// The §3.1 product itself, for every scalar and every value of the terms.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationEnuFromTurretProductT(const T& az_rad, const T& el_rad, const T& az_offset_rad,
                                                     const T& tilt_north_rad, const T& tilt_east_rad,
                                                     const T& el_axis_tilt_rad) {
  Eigen::Matrix<T, 3, 3> C;
  C << T(1), T(0), T(0), T(0), T(0), T(1), T(0), T(-1), T(0);
  return RotY<T>(tilt_east_rad) * RotX<T>(-tilt_north_rad) * RotZ<T>(-(az_rad + az_offset_rad)) *
         RotY<T>(el_axis_tilt_rad) * RotX<T>(el_rad) * C;
}

// R_enu_turret with every pointing term zero (SPEC.md §3's [r d b]), the product below multiplied out:
//   r = (cos A, −sin A, 0),  d = (sin A sin E, cos A sin E, −cos E),  b = (sin A cos E, cos A cos E, sin E).
// For any scalar with sin/cos found by argument-dependent lookup (double, ceres::Jet). The property test
// (tests/camera/test_projection.cc) checks that it equals the product bit for bit.
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

// R_enu_turret of SPEC.md §3.1 with the pointing terms as separate scalars (for automatic
// differentiation with respect to any of them). Angles in radians. For plain numbers with every term zero this
// is the multiplied-out form above (two sines and cosines instead of six); a jet always takes the product, so
// its derivatives with respect to terms that happen to be zero are kept.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationEnuFromTurretT(const T& az_rad, const T& el_rad, const T& az_offset_rad,
                                              const T& tilt_north_rad, const T& tilt_east_rad,
                                              const T& el_axis_tilt_rad) {
  if constexpr (std::is_floating_point_v<T>) {
    if (az_offset_rad == T(0) && tilt_north_rad == T(0) && tilt_east_rad == T(0) && el_axis_tilt_rad == T(0)) {
      return RotationEnuFromTurretT<T>(az_rad, el_rad);
    }
  }
  return RotationEnuFromTurretProductT<T>(az_rad, el_rad, az_offset_rad, tilt_north_rad, tilt_east_rad,
                                          el_axis_tilt_rad);
}

inline Eigen::Matrix3d RotationEnuFromTurret(double az_rad, double el_rad, const PointingTerms& p) {
  return RotationEnuFromTurretT<double>(az_rad, el_rad, p.az_offset_rad, p.tilt_north_rad, p.tilt_east_rad,
                                        p.el_axis_tilt_rad);
}

// Camera-to-turret rotation of a mount (SPEC.md §3.1): R_turret_cam = Ry(yaw) · Rx(pitch) · Rz(roll),
// about the turret frame's r, d, b axes.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationTurretFromCameraT(const T& yaw_rad, const T& pitch_rad, const T& roll_rad) {
  return RotY<T>(yaw_rad) * RotX<T>(pitch_rad) * RotZ<T>(roll_rad);
}

}  // namespace rk::geo

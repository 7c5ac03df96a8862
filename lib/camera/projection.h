// The camera and turret geometry of SPEC.md §3 and §3.1, written once, for double and for ceres::Jet
// (forward-mode automatic differentiation). Every path from a pixel to a line of sight and back goes through
// here: camera::CameraModel's methods, rk-locate's 1σ, rk-analyze budget, rk-calibrate pointing's residual,
// the lens-board renderer of rk-sim lens. Nothing else writes these equations.
//
//   normalised point n = (xn, yn)         the camera-frame direction (xn, yn, 1); camera x right, y down
//   distorted point  d = D(n)             OpenCV's (k1, k2, p1, p2, k3), r² = xn² + yn²:
//       d_x = xn (1 + k1 r² + k2 r⁴ + k3 r⁶) + 2 p1 xn yn + p2 (r² + 2 xn²)
//       d_y = yn (1 + k1 r² + k2 r⁴ + k3 r⁶) + p1 (r² + 2 yn²) + 2 p2 xn yn
//   pixel            p = (fx s d_x + cx, fy s d_y + cy)     s = focal-length scale (1 = the camera's own)
//   line of sight    ray_enu = R_enu_turret(A, E; pointing terms) · (R_turret_cam(mount) · (xn, yn, 1)) / |…|
// R_enu_turret is geo::RotationEnuFromTurretT (SPEC.md §3.1, pointing terms zero = §3), R_turret_cam
// geo::RotationTurretFromCameraT. Pixel → n inverts D by Newton's method (to ~1e-15, not OpenCV's fixed five
// iterations); for a jet the value is that Newton solution and the derivative follows from the implicit-function
// theorem, ∂n = (∂D/∂n)⁻¹ ∂d — exact first derivatives, which is all automatic differentiation asks.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>  // Matrix2d::inverse
#include <array>
#include <cmath>
#include <type_traits>

#include "geo/pointing.h"

namespace rk::camera {

// The lens as plain numbers (cheap to copy into a cost functor).
struct Intrinsics {
  double fx = 1.0, fy = 1.0;          // focal length in pixels
  double cx = 0.0, cy = 0.0;          // principal point, px
  std::array<double, 5> k{};          // k1, k2, p1, p2, k3 (OpenCV order)
  bool HasDistortion() const { return k[0] != 0.0 || k[1] != 0.0 || k[2] != 0.0 || k[3] != 0.0 || k[4] != 0.0; }
};

// Every quantity of the line of sight an estimator may differentiate: the logged turret angles, the turret's
// pointing model (SPEC.md §3.1), the camera's mount and a focal-length scale. Radians.
template <typename T>
struct SightParams {
  T az_rad = T(0.0), el_rad = T(0.0);
  T az_offset_rad = T(0.0), tilt_north_rad = T(0.0), tilt_east_rad = T(0.0), el_axis_tilt_rad = T(0.0);
  T mount_yaw_rad = T(0.0), mount_pitch_rad = T(0.0), mount_roll_rad = T(0.0);
  T focal_scale = T(1.0);

  void SetPointing(const geo::PointingTerms& p) {
    az_offset_rad = T(p.az_offset_rad);
    tilt_north_rad = T(p.tilt_north_rad);
    tilt_east_rad = T(p.tilt_east_rad);
    el_axis_tilt_rad = T(p.el_axis_tilt_rad);
  }
  // The same numbers as another scalar type (double → jet: constants, no derivative).
  template <typename U>
  SightParams<U> cast() const {
    return {U(az_rad),        U(el_rad),        U(az_offset_rad),   U(tilt_north_rad), U(tilt_east_rad),
            U(el_axis_tilt_rad), U(mount_yaw_rad), U(mount_pitch_rad), U(mount_roll_rad), U(focal_scale)};
  }
};

// The value of a scalar: itself for a floating-point type, the value part (.a) of a ceres::Jet.
template <typename T>
double ValuePart(const T& x) {
  if constexpr (std::is_floating_point_v<T>) {
    return static_cast<double>(x);
  } else {
    return x.a;
  }
}

// D(n) and, when J is given, ∂D/∂n.
template <typename T>
Eigen::Matrix<T, 2, 1> DistortT(const std::array<double, 5>& k, const T& x, const T& y,
                                Eigen::Matrix<T, 2, 2>* J = nullptr) {
  const T k1(k[0]), k2(k[1]), p1(k[2]), p2(k[3]), k3(k[4]);
  const T r2 = x * x + y * y;
  const T radial = T(1.0) + r2 * (k1 + r2 * (k2 + r2 * k3));
  Eigen::Matrix<T, 2, 1> d(x * radial + T(2.0) * p1 * x * y + p2 * (r2 + T(2.0) * x * x),
                           y * radial + p1 * (r2 + T(2.0) * y * y) + T(2.0) * p2 * x * y);
  if (J) {
    const T dradial_dr2 = k1 + r2 * (T(2.0) * k2 + T(3.0) * k3 * r2);
    const T drx = T(2.0) * x, dry = T(2.0) * y;  // ∂r²/∂x, ∂r²/∂y
    (*J)(0, 0) = radial + x * dradial_dr2 * drx + T(2.0) * p1 * y + p2 * (drx + T(4.0) * x);
    (*J)(0, 1) = x * dradial_dr2 * dry + T(2.0) * p1 * x + p2 * dry;
    (*J)(1, 0) = y * dradial_dr2 * drx + p1 * drx + T(2.0) * p2 * y;
    (*J)(1, 1) = radial + y * dradial_dr2 * dry + p1 * (dry + T(4.0) * y) + T(2.0) * p2 * x;
  }
  return d;
}

// n with D(n) = d by Newton's method from `start` (the distorted point itself when none is given; the
// lens-board renderer starts from the neighbouring pixel's solution). Stops when a step is below 1e-15.
inline Eigen::Vector2d Undistort(const std::array<double, 5>& k, const Eigen::Vector2d& d,
                                 const Eigen::Vector2d& start) {
  Eigen::Vector2d n = start;
  for (int it = 0; it < 30; ++it) {
    Eigen::Matrix2d J;
    const Eigen::Vector2d r = DistortT<double>(k, n.x(), n.y(), &J) - d;
    // J⁻¹ r written out (det(J) ≈ 1 for any lens that maps the sensor one-to-one): 1.6× faster than an LU.
    const double det = J(0, 0) * J(1, 1) - J(0, 1) * J(1, 0);
    const Eigen::Vector2d step((J(1, 1) * r.x() - J(0, 1) * r.y()) / det, (J(0, 0) * r.y() - J(1, 0) * r.x()) / det);
    n -= step;
    if (step.norm() < 1e-15) break;
  }
  return n;
}
inline Eigen::Vector2d Undistort(const std::array<double, 5>& k, const Eigen::Vector2d& d) {
  return Undistort(k, d, d);
}

// Pixel → normalised point n.
template <typename T>
Eigen::Matrix<T, 2, 1> NormalisedFromPixelT(const Intrinsics& in, const T& x_px, const T& y_px,
                                            const T& focal_scale = T(1.0)) {
  const T dx = (x_px - T(in.cx)) / (T(in.fx) * focal_scale);
  const T dy = (y_px - T(in.cy)) / (T(in.fy) * focal_scale);
  if (!in.HasDistortion()) return {dx, dy};
  const Eigen::Vector2d d0(ValuePart(dx), ValuePart(dy));
  const Eigen::Vector2d n0 = Undistort(in.k, d0);
  if constexpr (std::is_floating_point_v<T>) {
    return n0;
  } else {
    Eigen::Matrix2d J;
    DistortT<double>(in.k, n0.x(), n0.y(), &J);
    const Eigen::Matrix2d Ji = J.inverse();
    const T ex = dx - T(d0.x()), ey = dy - T(d0.y());  // value 0: only the derivative of d
    return {T(n0.x()) + Ji(0, 0) * ex + Ji(0, 1) * ey, T(n0.y()) + Ji(1, 0) * ex + Ji(1, 1) * ey};
  }
}

// The same for plain numbers, the Newton iteration started from `*start` when given (a neighbouring pixel's
// solution: the lens-board renderer inverts every pixel corner of the sensor this way, 2–3 steps each).
inline Eigen::Vector2d NormalisedFromPixel(const Intrinsics& in, const Eigen::Vector2d& px,
                                           const Eigen::Vector2d* start = nullptr) {
  const Eigen::Vector2d d((px.x() - in.cx) / in.fx, (px.y() - in.cy) / in.fy);
  return in.HasDistortion() ? Undistort(in.k, d, start ? *start : d) : d;
}

// Normalised point → pixel.
template <typename T>
Eigen::Matrix<T, 2, 1> PixelFromNormalisedT(const Intrinsics& in, const T& xn, const T& yn,
                                            const T& focal_scale = T(1.0)) {
  const Eigen::Matrix<T, 2, 1> d = in.HasDistortion() ? DistortT<T>(in.k, xn, yn) : Eigen::Matrix<T, 2, 1>(xn, yn);
  return {T(in.fx) * focal_scale * d.x() + T(in.cx), T(in.fy) * focal_scale * d.y() + T(in.cy)};
}

// R_enu_turret of SPEC.md §3.1 at the logged angles under the pointing terms of `s`.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationEnuFromTurretT(const SightParams<T>& s) {
  return geo::RotationEnuFromTurretT<T>(s.az_rad, s.el_rad, s.az_offset_rad, s.tilt_north_rad, s.tilt_east_rad,
                                        s.el_axis_tilt_rad);
}
// R_turret_cam of the mount of `s`.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationTurretFromCameraT(const SightParams<T>& s) {
  return geo::RotationTurretFromCameraT<T>(s.mount_yaw_rad, s.mount_pitch_rad, s.mount_roll_rad);
}

// Unit line of sight in ENU through pixel (x_px, y_px): the one entry point from a pixel to a direction.
template <typename T>
Eigen::Matrix<T, 3, 1> RayEnuT(const Intrinsics& in, const T& x_px, const T& y_px, const SightParams<T>& s) {
  using std::sqrt;
  const Eigen::Matrix<T, 2, 1> n = NormalisedFromPixelT<T>(in, x_px, y_px, s.focal_scale);
  const Eigen::Matrix<T, 3, 1> m_cam(n.x(), n.y(), T(1.0));
  const Eigen::Matrix<T, 3, 1> ray = RotationEnuFromTurretT<T>(s) * (RotationTurretFromCameraT<T>(s) * m_cam);
  return ray / sqrt(ray.squaredNorm());
}

// ENU direction → pixel: the inverse of RayEnuT. False (and *px untouched) when the direction is not in front of
// the camera.
template <typename T>
bool ProjectEnuT(const Intrinsics& in, const Eigen::Matrix<T, 3, 1>& dir_enu, const SightParams<T>& s,
                 Eigen::Matrix<T, 2, 1>* px) {
  const Eigen::Matrix<T, 3, 1> p_cam =
      RotationTurretFromCameraT<T>(s).transpose() * (RotationEnuFromTurretT<T>(s).transpose() * dir_enu);
  if (!(p_cam.z() > T(0.0))) return false;
  *px = PixelFromNormalisedT<T>(in, p_cam.x() / p_cam.z(), p_cam.y() / p_cam.z(), s.focal_scale);
  return true;
}

// Azimuth (clockwise from north; not wrapped, for derivatives) and elevation of an ENU vector.
template <typename T>
void AzElT(const Eigen::Matrix<T, 3, 1>& v, T* az_rad, T* el_rad) {
  using std::atan2;
  using std::sqrt;
  *az_rad = atan2(v(0), v(1));
  *el_rad = atan2(v(2), sqrt(v(0) * v(0) + v(1) * v(1)));
}

}  // namespace rk::camera

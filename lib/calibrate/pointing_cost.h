// The pixel residual of one pointing observation (pointing_solve.h "Model"), templated for ceres::Jet.
// Parameter blocks: x (kNumPointingParams), the cluster's turret-reading error c (az, el; radians), the
// target's direction error t (two tangent components; radians). Residual: (predicted − observed) / σ.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "calibrate/pointing_observations.h"
#include "calibrate/pointing_solve.h"
#include "camera/camera_model.h"
#include "geo/pointing.h"

namespace rk::calibrate {

// The camera's intrinsics as plain numbers (the functor copies them).
struct Intrinsics {
  double fx = 1.0, fy = 1.0, cx = 0.0, cy = 0.0;
  std::array<double, 5> k{};  // k1, k2, p1, p2, k3 (OpenCV order)
  static Intrinsics Of(const camera::CameraModel& c) {
    return {c.fx(), c.fy(), c.principal_point_px.x(), c.principal_point_px.y(), c.distortion};
  }
};

// Normalised camera point → distorted pixel (SPEC.md §3, camera::CameraModel::Project), focal scaled.
template <typename T>
Eigen::Matrix<T, 2, 1> ProjectNormalisedT(const Intrinsics& in, const T& xn, const T& yn, const T& focal_scale) {
  const T r2 = xn * xn + yn * yn;
  const T radial = T(1) + T(in.k[0]) * r2 + T(in.k[1]) * r2 * r2 + T(in.k[4]) * r2 * r2 * r2;
  const T xd = xn * radial + T(2 * in.k[2]) * xn * yn + T(in.k[3]) * (r2 + T(2) * xn * xn);
  const T yd = yn * radial + T(in.k[2]) * (r2 + T(2) * yn * yn) + T(2 * in.k[3]) * xn * yn;
  return {T(in.fx) * focal_scale * xd + T(in.cx), T(in.fy) * focal_scale * yd + T(in.cy)};
}

// Two unit vectors orthogonal to d (the target's direction-error axes).
inline void TangentBasis(const Eigen::Vector3d& d, Eigen::Vector3d* e1, Eigen::Vector3d* e2) {
  const Eigen::Vector3d up = std::abs(d.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  *e1 = up.cross(d).normalized();
  *e2 = d.cross(*e1).normalized();
}

struct PointingPixelCost {
  PointingObservation o;
  Intrinsics in;
  double tau0_s = 0.0;
  Eigen::Vector3d e1, e2;

  PointingPixelCost(const PointingObservation& obs, const Intrinsics& intr, double tau0)
      : o(obs), in(intr), tau0_s(tau0) {
    TangentBasis(o.dir_enu, &e1, &e2);
  }

  template <typename T>
  bool operator()(const T* x, const T* c, const T* t, T* r) const {
    const T dt = x[kParamTimeOffset] - T(tau0_s);
    const T az = T(o.az_log_rad) + T(o.az_rate_rps) * dt + c[0];
    const T el = T(o.el_log_rad) + T(o.el_rate_rps) * dt + c[1];
    const Eigen::Matrix<T, 3, 3> R_enu_cam =
        geo::RotationEnuFromTurretT<T>(az, el, x[kParamAzOffset], x[kParamTiltNorth], x[kParamTiltEast],
                                       x[kParamElAxisTilt]) *
        geo::RotationTurretFromCameraT<T>(x[kParamMountYaw], x[kParamMountPitch], x[kParamMountRoll]);
    const Eigen::Matrix<T, 3, 1> dir = o.dir_enu.cast<T>() + o.dir_rate_enu.cast<T>() * dt + e1.cast<T>() * t[0] +
                                       e2.cast<T>() * t[1];
    const Eigen::Matrix<T, 3, 1> v = R_enu_cam.transpose() * dir;
    if (!(v.z() > T(0))) return false;
    const Eigen::Matrix<T, 2, 1> p = ProjectNormalisedT<T>(in, v.x() / v.z(), v.y() / v.z(), T(1) + x[kParamFocal]);
    r[0] = (p.x() - T(o.px.x())) / T(o.sigma_px.x());
    r[1] = (p.y() - T(o.px.y())) / T(o.sigma_px.y());
    return true;
  }
};

}  // namespace rk::calibrate

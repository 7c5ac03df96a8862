// The pixel residual of one pointing observation (pointing_solve.h "Model"), templated for ceres::Jet.
// Parameter blocks: x (kNumPointingParams), the cluster's turret-reading error c (az, el; radians), the
// target's direction error t (two tangent components; radians). Residual: (predicted − observed) / σ, the
// prediction by the one projection of camera/projection.h.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "calibrate/pointing_observations.h"
#include "calibrate/pointing_solve.h"
#include "camera/camera_model.h"
#include "camera/projection.h"

namespace rk::calibrate {

using camera::Intrinsics;  // the camera's lens as numbers (camera/projection.h); the functor copies them

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
    camera::SightParams<T> s;
    s.az_rad = az;
    s.el_rad = el;
    s.az_offset_rad = x[kParamAzOffset];
    s.tilt_north_rad = x[kParamTiltNorth];
    s.tilt_east_rad = x[kParamTiltEast];
    s.el_axis_tilt_rad = x[kParamElAxisTilt];
    s.mount_yaw_rad = x[kParamMountYaw];
    s.mount_pitch_rad = x[kParamMountPitch];
    s.mount_roll_rad = x[kParamMountRoll];
    s.focal_scale = T(1) + x[kParamFocal];
    const Eigen::Matrix<T, 3, 1> dir = o.dir_enu.cast<T>() + o.dir_rate_enu.cast<T>() * dt + e1.cast<T>() * t[0] +
                                       e2.cast<T>() * t[1];
    Eigen::Matrix<T, 2, 1> p;
    if (!camera::ProjectEnuT<T>(in, dir, s, &p)) return false;
    r[0] = (p.x() - T(o.px.x())) / T(o.sigma_px.x());
    r[1] = (p.y() - T(o.px.y())) / T(o.sigma_px.y());
    return true;
  }
};

}  // namespace rk::calibrate

// Helpers for automatic differentiation of line-of-sight computations (ceres::Jet, forward mode) in the
// error-budget models. The pixel → normalised ray undistortion (a Newton inversion in the camera model) is
// differentiated through its linearisation at the nominal pixel: m(px) = m(px0) + (∂m/∂px)(px0) (px − px0),
// with ∂m/∂px = camera::CameraModel::NormalisedRayJacobian — exact for the first derivatives at px0, which is
// all a Jacobian needs. Use only with jets whose value part equals px0.
#pragma once

#include <ceres/jet.h>

#include <Eigen/Core>

#include "camera/camera_model.h"
#include "geo/line_of_sight.h"

namespace rk::analysis {

// Unit ENU line of sight through pixel (px, py) for boresight (az, el), SPEC.md §3, as a function of jets.
template <typename T>
Eigen::Matrix<T, 3, 1> RayEnuAutodiff(const camera::CameraModel& cam, const Eigen::Vector2d& px0, const T& px,
                                      const T& py, const T& az_rad, const T& el_rad) {
  const Eigen::Vector3d m0 = cam.NormalisedRay(px0);
  const Eigen::Matrix2d J = cam.NormalisedRayJacobian(px0);
  const T dx = px - T(px0.x()), dy = py - T(px0.y());
  Eigen::Matrix<T, 3, 1> m_cam(T(m0.x()) + J(0, 0) * dx + J(0, 1) * dy, T(m0.y()) + J(1, 0) * dx + J(1, 1) * dy,
                               T(1.0));
  const Eigen::Matrix<T, 3, 3> R_turret_cam = cam.RotationTurretFromCamera().cast<T>();
  const Eigen::Matrix<T, 3, 1> ray = geo::RotationEnuFromTurretT<T>(az_rad, el_rad) * (R_turret_cam * m_cam);
  using std::sqrt;
  return ray / sqrt(ray.squaredNorm());
}

// Azimuth (clockwise from north, not wrapped: derivatives only) and elevation of an ENU vector.
template <typename T>
void AzElAutodiff(const Eigen::Matrix<T, 3, 1>& v, T* az_rad, T* el_rad) {
  using std::atan2;
  using std::sqrt;
  *az_rad = atan2(v(0), v(1));
  *el_rad = atan2(v(2), sqrt(v(0) * v(0) + v(1) * v(1)));
}

}  // namespace rk::analysis

// 1σ of a located row; model in locate_sigma.h.
#include "locate/locate_sigma.h"

#include <ceres/jet.h>

#include <cmath>

#include "camera/projection.h"
#include "geo/angles.h"
#include "geo/pointing.h"
#include "io/error.h"

namespace rk::locate {
namespace {

enum SigmaIndex {
  kPx = 0, kPy = 1, kAz = 2, kEl = 3, kTerm0 = 4, kMount0 = 8, kFocal = 11, kRange = 12, kTau = 13
};

// y(x) for any scalar (double or jet), through the one line of sight (camera/projection.h).
template <typename T>
Eigen::Matrix<T, kSigmaOutputs, 1> Located(const camera::CameraModel& cam, const SigmaPoint& p,
                                           const Eigen::Matrix<T, kSigmaInputs, 1>& x) {
  camera::SightParams<T> s;
  s.az_rad = x(kAz) + T(p.az_rate) * x(kTau);
  s.el_rad = x(kEl) + T(p.el_rate) * x(kTau);
  s.az_offset_rad = x(kTerm0);
  s.tilt_north_rad = x(kTerm0 + 1);
  s.tilt_east_rad = x(kTerm0 + 2);
  s.el_axis_tilt_rad = x(kTerm0 + 3);
  s.mount_yaw_rad = x(kMount0);
  s.mount_pitch_rad = x(kMount0 + 1);
  s.mount_roll_rad = x(kMount0 + 2);
  s.focal_scale = x(kFocal) / T(cam.focal_length_mm);
  const Eigen::Matrix<T, 3, 1> ray = camera::RayEnuT<T>(cam.ToIntrinsics(), x(kPx), x(kPy), s);
  const T range = x(kRange) + T(p.range_rate_mps) * x(kTau);
  Eigen::Matrix<T, kSigmaOutputs, 1> y;
  camera::AzElT<T>(ray, &y(0), &y(1));
  y(2) = range;
  for (int k = 0; k < 3; ++k) y(3 + k) = range * ray(k);
  return y;
}

}  // namespace

void CameraSigma(const camera::CameraModel& camera, const std::string& where, SigmaSources* s) {
  const camera::CalibrationSigma c = camera::CameraCalibrationSigma(camera, where);
  s->mount_rad = c.mount_rad;
  s->focal_mm = c.focal_mm;
  s->time_offset_s = c.time_offset_s;
}

void PointingSigma(const camera::PointingModel& pointing, SigmaSources* s) {
  for (int i = 0; i < 4; ++i) s->pointing_rad[i] = pointing.sigma_rad[i].value_or(0.0);
}

SigmaInputVector SigmaNominal(const camera::CameraModel& camera, const geo::PointingTerms& terms,
                              const SigmaPoint& p) {
  SigmaInputVector x;
  x << p.px.x(), p.px.y(), p.az_rad, p.el_rad, terms.az_offset_rad, terms.tilt_north_rad, terms.tilt_east_rad,
      terms.el_axis_tilt_rad, camera.mount_yaw_rad, camera.mount_pitch_rad, camera.mount_roll_rad,
      camera.focal_length_mm, p.range_m, 0.0;
  return x;
}

Eigen::Matrix<double, kSigmaOutputs, 1> LocatedFunction(const camera::CameraModel& camera, const SigmaPoint& p,
                                                        const SigmaInputVector& x) {
  return Located<double>(camera, p, x);
}

LocatedJacobian LocatedJacobianAt(const camera::CameraModel& camera, const geo::PointingTerms& terms,
                                  const SigmaPoint& p) {
  using J = ceres::Jet<double, kSigmaInputs>;
  const SigmaInputVector x0 = SigmaNominal(camera, terms, p);
  Eigen::Matrix<J, kSigmaInputs, 1> x;
  for (int i = 0; i < kSigmaInputs; ++i) x(i) = J(x0(i), i);
  const Eigen::Matrix<J, kSigmaOutputs, 1> y = Located<J>(camera, p, x);
  LocatedJacobian D;
  for (int k = 0; k < kSigmaOutputs; ++k) D.row(k) = y(k).v.transpose();
  return D;
}

LocatedCovariance LocatedCovarianceAt(const camera::CameraModel& camera, const geo::PointingTerms& terms,
                                      const SigmaPoint& p, const SigmaSources& s) {
  SigmaInputVector var;
  var << p.sigma_px.x() * p.sigma_px.x(), p.sigma_px.y() * p.sigma_px.y(), s.turret_rad * s.turret_rad,
      s.turret_rad * s.turret_rad, 0, 0, 0, 0, 0, 0, 0, s.focal_mm * s.focal_mm, s.range_m * s.range_m,
      s.time_offset_s * s.time_offset_s;
  for (int i = 0; i < 4; ++i) var(kTerm0 + i) = s.pointing_rad[i] * s.pointing_rad[i];
  for (int i = 0; i < 3; ++i) var(kMount0 + i) = s.mount_rad[i] * s.mount_rad[i];
  const LocatedJacobian D = LocatedJacobianAt(camera, terms, p);
  return D * var.asDiagonal() * D.transpose();
}

}  // namespace rk::locate

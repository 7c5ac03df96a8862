// 1σ of a located row; model in locate_sigma.h.
#include "locate/locate_sigma.h"

#include <ceres/jet.h>

#include <cmath>

#include "geo/angles.h"
#include "geo/pointing.h"
#include "io/error.h"

namespace rk::locate {
namespace {

enum SigmaIndex {
  kPx = 0, kPy = 1, kAz = 2, kEl = 3, kTerm0 = 4, kMount0 = 8, kFocal = 11, kRange = 12, kTau = 13
};

double SigmaNumber(const io::Json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || j.at(key).is_null()) return 0.0;
  const double v = io::RequireNumber(j, key, where);
  if (!std::isfinite(v) || v < 0.0) throw DataError(where, 0, 0, std::string(key) + " must be finite and >= 0");
  return v;
}

// y(x) for any scalar (double or jet); the undistortion linearised about the nominal pixel px0 with focal f0.
template <typename T>
Eigen::Matrix<T, kSigmaOutputs, 1> Located(const camera::CameraModel& cam, const SigmaPoint& p,
                                           const Eigen::Matrix<T, kSigmaInputs, 1>& x) {
  using std::atan2;
  using std::sqrt;
  const Eigen::Vector3d m0 = cam.NormalisedRay(p.px);
  // d(xn, yn)/d(xd, yd): the inverse distortion Jacobian at the nominal pixel.
  Eigen::Matrix2d Jd = cam.NormalisedRayJacobian(p.px);
  Jd.col(0) *= cam.fx();
  Jd.col(1) *= cam.fy();
  const T xd = (x(kPx) - T(cam.principal_point_px.x())) * T(cam.pixel_size_mm[0]) / x(kFocal);
  const T yd = (x(kPy) - T(cam.principal_point_px.y())) * T(cam.pixel_size_mm[1]) / x(kFocal);
  const T dx = xd - T((p.px.x() - cam.principal_point_px.x()) / cam.fx());
  const T dy = yd - T((p.px.y() - cam.principal_point_px.y()) / cam.fy());
  const Eigen::Matrix<T, 3, 1> m(T(m0.x()) + Jd(0, 0) * dx + Jd(0, 1) * dy, T(m0.y()) + Jd(1, 0) * dx + Jd(1, 1) * dy,
                                 T(1.0));
  const T az = x(kAz) + T(p.az_rate) * x(kTau);
  const T el = x(kEl) + T(p.el_rate) * x(kTau);
  const Eigen::Matrix<T, 3, 3> R = geo::RotationEnuFromTurretT<T>(az, el, x(kTerm0), x(kTerm0 + 1), x(kTerm0 + 2),
                                                                  x(kTerm0 + 3)) *
                                   geo::RotationTurretFromCameraT<T>(x(kMount0), x(kMount0 + 1), x(kMount0 + 2));
  Eigen::Matrix<T, 3, 1> ray = R * m;
  ray /= sqrt(ray.squaredNorm());
  const T range = x(kRange) + T(p.range_rate_mps) * x(kTau);
  Eigen::Matrix<T, kSigmaOutputs, 1> y;
  y(0) = atan2(ray(0), ray(1));
  y(1) = atan2(ray(2), sqrt(ray(0) * ray(0) + ray(1) * ray(1)));
  y(2) = range;
  for (int k = 0; k < 3; ++k) y(3 + k) = range * ray(k);
  return y;
}

}  // namespace

void CameraSigma(const camera::CameraModel& camera, const std::string& where, SigmaSources* s) {
  s->mount_rad = {0.0, 0.0, 0.0};
  s->focal_mm = 0.0;
  s->time_offset_s = 0.0;
  if (!camera.calibration.is_object() || !camera.calibration.contains("sigma")) return;
  const io::Json& sig = camera.calibration.at("sigma");
  const std::string w = where + ": calibration.sigma";
  if (sig.is_null()) return;
  if (!sig.is_object()) throw DataError(where, 0, 0, "calibration.sigma must be an object");
  if (sig.contains("mount_deg") && !sig.at("mount_deg").is_null()) {
    const io::Json& m = sig.at("mount_deg");
    if (!m.is_object()) throw DataError(where, 0, 0, "calibration.sigma.mount_deg must be an object");
    const char* keys[] = {"yaw", "pitch", "roll"};
    for (int i = 0; i < 3; ++i) s->mount_rad[i] = geo::DegToRad(SigmaNumber(m, keys[i], w + ".mount_deg"));
  }
  s->focal_mm = SigmaNumber(sig, "focal_length_mm", w);
  s->time_offset_s = SigmaNumber(sig, "time_offset_s", w);
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
  camera::CameraModel c = camera;
  c.focal_length_mm = x(kFocal);
  c.mount_yaw_rad = x(kMount0);
  c.mount_pitch_rad = x(kMount0 + 1);
  c.mount_roll_rad = x(kMount0 + 2);
  const geo::PointingTerms terms{x(kTerm0), x(kTerm0 + 1), x(kTerm0 + 2), x(kTerm0 + 3)};
  const Eigen::Vector3d ray = c.RayEnu(Eigen::Vector2d(x(kPx), x(kPy)), x(kAz) + p.az_rate * x(kTau),
                                       x(kEl) + p.el_rate * x(kTau), terms);
  const double range = x(kRange) + p.range_rate_mps * x(kTau);
  Eigen::Matrix<double, kSigmaOutputs, 1> y;
  y << std::atan2(ray.x(), ray.y()), std::atan2(ray.z(), std::hypot(ray.x(), ray.y())), range, range * ray;
  return y;
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

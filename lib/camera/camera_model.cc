#include "camera/camera_model.h"

#include <Eigen/Dense>
#include <cmath>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "geo/pointing.h"
#include "io/error.h"

namespace rk::camera {
namespace {

// Applies distortion to a normalised point; optionally returns the Jacobian.
Eigen::Vector2d Distort(const std::array<double, 5>& k, const Eigen::Vector2d& n, Eigen::Matrix2d* J) {
  const double x = n.x(), y = n.y();
  const double k1 = k[0], k2 = k[1], p1 = k[2], p2 = k[3], k3 = k[4];
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  Eigen::Vector2d d(x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
                    y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y);
  if (J) {
    const double dradial_dr2 = k1 + r2 * (2 * k2 + 3 * k3 * r2);
    const double drx = 2 * x, dry = 2 * y;  // d r2 / dx, dy
    (*J)(0, 0) = radial + x * dradial_dr2 * drx + 2 * p1 * y + p2 * (drx + 4 * x);
    (*J)(0, 1) = x * dradial_dr2 * dry + 2 * p1 * x + p2 * dry;
    (*J)(1, 0) = y * dradial_dr2 * drx + p1 * drx + 2 * p2 * y;
    (*J)(1, 1) = radial + y * dradial_dr2 * dry + p1 * (dry + 4 * y) + 2 * p2 * x;
  }
  return d;
}

}  // namespace

bool CameraModel::HasDistortion() const {
  for (double k : distortion) {
    if (k != 0.0) return true;
  }
  return false;
}

Eigen::Vector3d CameraModel::NormalisedRay(const Eigen::Vector2d& px) const {
  Eigen::Vector2d d((px.x() - principal_point_px.x()) / fx(), (px.y() - principal_point_px.y()) / fy());
  if (!HasDistortion()) return {d.x(), d.y(), 1.0};
  Eigen::Vector2d n = d;
  for (int it = 0; it < 30; ++it) {
    Eigen::Matrix2d J;
    Eigen::Vector2d r = Distort(distortion, n, &J) - d;
    Eigen::Vector2d step = J.partialPivLu().solve(r);
    n -= step;
    if (step.norm() < 1e-15) break;
  }
  return {n.x(), n.y(), 1.0};
}

Eigen::Matrix2d CameraModel::NormalisedRayJacobian(const Eigen::Vector2d& px) const {
  Eigen::Matrix2d scale = Eigen::Matrix2d::Zero();
  scale(0, 0) = 1.0 / fx();
  scale(1, 1) = 1.0 / fy();
  if (!HasDistortion()) return scale;
  const Eigen::Vector3d m = NormalisedRay(px);
  Eigen::Matrix2d J;
  Distort(distortion, Eigen::Vector2d(m.x(), m.y()), &J);
  return J.inverse() * scale;
}

std::optional<Eigen::Vector2d> CameraModel::Project(const Eigen::Vector3d& p_cam) const {
  if (!(p_cam.z() > 0.0)) return std::nullopt;
  Eigen::Vector2d n(p_cam.x() / p_cam.z(), p_cam.y() / p_cam.z());
  Eigen::Vector2d d = HasDistortion() ? Distort(distortion, n, nullptr) : n;
  return Eigen::Vector2d(fx() * d.x() + principal_point_px.x(), fy() * d.y() + principal_point_px.y());
}

Eigen::Matrix3d CameraModel::RotationTurretFromCamera() const {
  return geo::RotationTurretFromCameraT(mount_yaw_rad, mount_pitch_rad, mount_roll_rad);
}

Eigen::Vector3d CameraModel::RayEnu(const Eigen::Vector2d& px, double az_rad, double el_rad) const {
  Eigen::Vector3d m_cam = NormalisedRay(px);
  Eigen::Vector3d ray = geo::RotationEnuFromTurret(az_rad, el_rad) * (RotationTurretFromCamera() * m_cam);
  return ray.normalized();
}

Eigen::Vector3d CameraModel::RayEnu(const Eigen::Vector2d& px, double az_rad, double el_rad,
                                    const geo::PointingTerms& pointing) const {
  if (pointing.IsZero()) return RayEnu(px, az_rad, el_rad);
  Eigen::Vector3d m_cam = NormalisedRay(px);
  Eigen::Vector3d ray = geo::RotationEnuFromTurret(az_rad, el_rad, pointing) * (RotationTurretFromCamera() * m_cam);
  return ray.normalized();
}

std::optional<Eigen::Vector2d> CameraModel::ProjectEnu(const Eigen::Vector3d& dir_enu, double az_rad,
                                                       double el_rad) const {
  Eigen::Vector3d p_cam =
      RotationTurretFromCamera().transpose() * (geo::RotationEnuFromTurret(az_rad, el_rad).transpose() * dir_enu);
  return Project(p_cam);
}

CameraModel DefaultCamera() { return CameraModel{}; }

CameraModel CameraModelFromJson(const io::Json& j, const std::string& where) {
  if (!j.is_object()) throw DataError(where, 0, 0, "camera model must be a JSON object");
  CameraModel c;
  double w = io::RequireNumber(j, "width_px", where);
  double h = io::RequireNumber(j, "height_px", where);
  if (w < 1 || h < 1 || w != std::floor(w) || h != std::floor(h) || w > 100000 || h > 100000) {
    throw DataError(where, 0, 0, "width_px and height_px must be positive whole numbers");
  }
  c.width_px = static_cast<int>(w);
  c.height_px = static_cast<int>(h);
  auto ps = io::RequireNumbers(j, "pixel_size_mm", 1, 2, where);
  c.pixel_size_mm = {ps[0], ps.size() > 1 ? ps[1] : ps[0]};
  if (!(c.pixel_size_mm[0] > 0) || !(c.pixel_size_mm[1] > 0)) {
    throw DataError(where, 0, 0, "pixel_size_mm must be positive");
  }
  c.focal_length_mm = io::RequireNumber(j, "focal_length_mm", where);
  if (!(c.focal_length_mm > 0)) throw DataError(where, 0, 0, "focal_length_mm must be positive");
  auto pp = io::RequireNumbers(j, "principal_point_px", 2, 2, where);
  c.principal_point_px = {pp[0], pp[1]};
  if (j.contains("distortion") && !j.at("distortion").is_null()) {
    auto k = io::RequireNumbers(j, "distortion", 0, 5, where);
    for (std::size_t i = 0; i < k.size(); ++i) c.distortion[i] = k[i];
  }
  if (j.contains("mount_deg") && !j.at("mount_deg").is_null()) {
    const auto& m = j.at("mount_deg");
    std::string mw = where + ": mount_deg";
    c.mount_yaw_rad = geo::DegToRad(io::NumberOr(m, "yaw", 0.0, mw));
    c.mount_pitch_rad = geo::DegToRad(io::NumberOr(m, "pitch", 0.0, mw));
    c.mount_roll_rad = geo::DegToRad(io::NumberOr(m, "roll", 0.0, mw));
  }
  c.time_offset_s = io::NumberOr(j, "time_offset_s", 0.0, where);
  if (!std::isfinite(c.time_offset_s) || std::abs(c.time_offset_s) > 10.0) {
    throw DataError(where, 0, 0, "time_offset_s must be finite and within ±10 s");
  }
  if (j.contains("calibration") && !j.at("calibration").is_null()) c.calibration = j.at("calibration");
  return c;
}

CameraModel LoadCameraModel(const std::string& path) { return CameraModelFromJson(io::LoadJson(path), path); }

io::Json CameraModelToJson(const CameraModel& c) {
  io::Json j;
  j["width_px"] = c.width_px;
  j["height_px"] = c.height_px;
  j["pixel_size_mm"] = {c.pixel_size_mm[0], c.pixel_size_mm[1]};
  j["focal_length_mm"] = c.focal_length_mm;
  j["principal_point_px"] = {c.principal_point_px.x(), c.principal_point_px.y()};
  j["distortion"] = c.distortion;
  j["mount_deg"] = {{"yaw", geo::RadToDeg(c.mount_yaw_rad)},
                    {"pitch", geo::RadToDeg(c.mount_pitch_rad)},
                    {"roll", geo::RadToDeg(c.mount_roll_rad)}};
  // Written only when set, so camera files of trials without a latency stay as they were.
  if (c.time_offset_s != 0.0) j["time_offset_s"] = c.time_offset_s;
  if (!c.calibration.is_null()) j["calibration"] = c.calibration;
  return j;
}

}  // namespace rk::camera

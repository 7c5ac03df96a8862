#include "camera/camera_model.h"

#include <Eigen/Dense>
#include <cmath>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::camera {

bool CameraModel::HasDistortion() const { return ToIntrinsics().HasDistortion(); }

Intrinsics CameraModel::ToIntrinsics() const {
  return {fx(), fy(), principal_point_px.x(), principal_point_px.y(), distortion};
}

SightParams<double> CameraModel::Sight(double az_rad, double el_rad, const geo::PointingTerms& pointing) const {
  SightParams<double> s;
  s.az_rad = az_rad;
  s.el_rad = el_rad;
  s.SetPointing(pointing);
  s.mount_yaw_rad = mount_yaw_rad;
  s.mount_pitch_rad = mount_pitch_rad;
  s.mount_roll_rad = mount_roll_rad;
  return s;
}

Eigen::Vector3d CameraModel::NormalisedRay(const Eigen::Vector2d& px) const {
  const Eigen::Vector2d n = NormalisedFromPixelT<double>(ToIntrinsics(), px.x(), px.y());
  return {n.x(), n.y(), 1.0};
}

Eigen::Matrix2d CameraModel::NormalisedRayJacobian(const Eigen::Vector2d& px) const {
  Eigen::Matrix2d scale = Eigen::Matrix2d::Zero();
  scale(0, 0) = 1.0 / fx();
  scale(1, 1) = 1.0 / fy();
  if (!HasDistortion()) return scale;
  const Eigen::Vector3d m = NormalisedRay(px);
  Eigen::Matrix2d J;
  DistortT<double>(distortion, m.x(), m.y(), &J);
  return J.inverse() * scale;
}

std::optional<Eigen::Vector2d> CameraModel::Project(const Eigen::Vector3d& p_cam) const {
  if (!(p_cam.z() > 0.0)) return std::nullopt;
  return PixelFromNormalisedT<double>(ToIntrinsics(), p_cam.x() / p_cam.z(), p_cam.y() / p_cam.z());
}

Eigen::Matrix3d CameraModel::RotationTurretFromCamera() const {
  return geo::RotationTurretFromCameraT(mount_yaw_rad, mount_pitch_rad, mount_roll_rad);
}

Eigen::Vector3d CameraModel::RayEnu(const Eigen::Vector2d& px, double az_rad, double el_rad) const {
  return RayEnuT<double>(ToIntrinsics(), px.x(), px.y(), Sight(az_rad, el_rad));
}

Eigen::Vector3d CameraModel::RayEnu(const Eigen::Vector2d& px, double az_rad, double el_rad,
                                    const geo::PointingTerms& pointing) const {
  return RayEnuT<double>(ToIntrinsics(), px.x(), px.y(), Sight(az_rad, el_rad, pointing));
}

std::optional<Eigen::Vector2d> CameraModel::ProjectEnu(const Eigen::Vector3d& dir_enu, double az_rad,
                                                       double el_rad) const {
  Eigen::Vector2d px;
  if (!ProjectEnuT<double>(ToIntrinsics(), dir_enu, Sight(az_rad, el_rad), &px)) return std::nullopt;
  return px;
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

namespace {

double SigmaNumber(const io::Json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || j.at(key).is_null()) return 0.0;
  const double v = io::RequireNumber(j, key, where);
  if (!std::isfinite(v) || v < 0.0) throw DataError(where, 0, 0, std::string(key) + " must be finite and >= 0");
  return v;
}

}  // namespace

CalibrationSigma CameraCalibrationSigma(const CameraModel& camera, const std::string& where) {
  CalibrationSigma s;
  if (!camera.calibration.is_object() || !camera.calibration.contains("sigma")) return s;
  const io::Json& sig = camera.calibration.at("sigma");
  const std::string w = where + ": calibration.sigma";
  if (sig.is_null()) return s;
  if (!sig.is_object()) throw DataError(where, 0, 0, "calibration.sigma must be an object");
  if (sig.contains("mount_deg") && !sig.at("mount_deg").is_null()) {
    const io::Json& m = sig.at("mount_deg");
    if (!m.is_object()) throw DataError(where, 0, 0, "calibration.sigma.mount_deg must be an object");
    const char* keys[] = {"yaw", "pitch", "roll"};
    for (int i = 0; i < 3; ++i) s.mount_rad[i] = geo::DegToRad(SigmaNumber(m, keys[i], w + ".mount_deg"));
  }
  s.focal_mm = SigmaNumber(sig, "focal_length_mm", w);
  s.time_offset_s = SigmaNumber(sig, "time_offset_s", w);
  return s;
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

// Pinhole camera with OpenCV (k1, k2, p1, p2, k3) distortion, mounted on a turret
// (SPEC.md §3).
//
// Pixels: x right, y down, (0, 0) is the centre of the top-left pixel.
// Camera frame: x right, y down, z along the optical axis. Normalised image
// point m = (xn, yn, 1); distorted pixel = (fx * xd + cx, fy * yd + cy) with
//   xd = xn (1 + k1 r² + k2 r⁴ + k3 r⁶) + 2 p1 xn yn + p2 (r² + 2 xn²)
//   yd = yn (1 + k1 r² + k2 r⁴ + k3 r⁶) + p1 (r² + 2 yn²) + 2 p2 xn yn,  r² = xn² + yn².
//
// Mount (optional "mount_deg": {"yaw", "pitch", "roll"}): the camera's small
// misalignment to the turret boresight frame (x right, y down, z boresight):
//   R_turret_cam = Ry(yaw) · Rx(pitch) · Rz(roll)
// yaw > 0 turns the optical axis to the right of the boresight, pitch > 0 turns
// it up, roll > 0 turns the image x axis towards image down (clockwise seen
// from behind the camera). The optical axis in the turret frame is
// (sin yaw cos pitch, -sin pitch, cos yaw cos pitch). Zero mount = identity.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "camera/projection.h"
#include "geo/pointing.h"
#include "io/json_util.h"

namespace rk::camera {

struct CameraModel {
  int width_px = 2448;
  int height_px = 2048;
  std::array<double, 2> pixel_size_mm = {0.00345, 0.00345};
  double focal_length_mm = 50.0;
  Eigen::Vector2d principal_point_px{1223.5, 1023.5};
  std::array<double, 5> distortion = {0, 0, 0, 0, 0};  // k1, k2, p1, p2, k3
  double mount_yaw_rad = 0.0;
  double mount_pitch_rad = 0.0;
  double mount_roll_rad = 0.0;
  // Camera latency (SPEC.md §3): a frame's mid-exposure time is its frames.csv t_s + time_offset_s; the
  // turret and range logs' times are true. Optional "time_offset_s" in the file, default 0.
  double time_offset_s = 0.0;
  // rk-calibrate's "calibration" object (method, date, residual RMS, "sigma" of every estimated
  // parameter), kept as read so that a camera written back keeps it; null when absent.
  io::Json calibration;

  double fx() const { return focal_length_mm / pixel_size_mm[0]; }
  double fy() const { return focal_length_mm / pixel_size_mm[1]; }
  bool HasDistortion() const;
  // The lens as numbers and the line-of-sight parameters at boresight az/el (radians) under `pointing`, with this
  // camera's mount, for camera/projection.h: every method below is a call of it.
  Intrinsics ToIntrinsics() const;
  SightParams<double> Sight(double az_rad, double el_rad, const geo::PointingTerms& pointing = {}) const;

  // Pixel → undistorted normalised ray m = (xn, yn, 1) in the camera frame.
  // The distortion is inverted by Newton iteration to ~1e-15 (camera::Undistort; not OpenCV's
  // fixed 5 iterations, which leave ~0.01 px at the corners of strong lenses).
  Eigen::Vector3d NormalisedRay(const Eigen::Vector2d& px) const;
  // Jacobian d(xn, yn)/d(x_px, y_px) of NormalisedRay (inverse of the distortion Jacobian, scaled by
  // 1/fx, 1/fy): for error propagation and automatic differentiation through the undistortion.
  Eigen::Matrix2d NormalisedRayJacobian(const Eigen::Vector2d& px) const;
  // Camera-frame point (z > 0) → distorted pixel. nullopt behind the camera.
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& p_cam) const;

  Eigen::Matrix3d RotationTurretFromCamera() const;
  // Unit line of sight in ENU through pixel `px` for boresight az/el (radians).
  Eigen::Vector3d RayEnu(const Eigen::Vector2d& px, double az_rad, double el_rad) const;
  // The same through the turret's pointing model (SPEC.md §3.1); az/el are the logged angles.
  Eigen::Vector3d RayEnu(const Eigen::Vector2d& px, double az_rad, double el_rad,
                         const geo::PointingTerms& pointing) const;
  // ENU direction → pixel for boresight az/el; nullopt if behind the camera.
  std::optional<Eigen::Vector2d> ProjectEnu(const Eigen::Vector3d& dir_enu, double az_rad, double el_rad) const;
};

// The 1σ of the calibrated mount, focal length and latency, from the file's "calibration": {"sigma":
// {"mount_deg": {"yaw", "pitch", "roll"}, "focal_length_mm", "time_offset_s"}} (rk-calibrate; absent = 0).
// DataError naming `where` for a malformed or negative one. Radians, mm, seconds.
struct CalibrationSigma {
  std::array<double, 3> mount_rad{};  // yaw, pitch, roll
  double focal_mm = 0.0;
  double time_offset_s = 0.0;
};
CalibrationSigma CameraCalibrationSigma(const CameraModel& camera, const std::string& where);

// The default station camera of seed 001: 2448×2048, 3.45 µm, 50 mm.
CameraModel DefaultCamera();
// Reads and validates camera JSON (SPEC.md §3); errors name the file and field.
CameraModel LoadCameraModel(const std::string& path);
CameraModel CameraModelFromJson(const io::Json& j, const std::string& where);
io::Json CameraModelToJson(const CameraModel& cam);

}  // namespace rk::camera

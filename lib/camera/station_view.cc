// Pointing model as an equivalent boresight and mount; see station_view.h.
#include "camera/station_view.h"

#include <algorithm>
#include <cmath>

#include "geo/angles.h"

namespace rk::camera {

StationView ApplyPointing(const CameraModel& camera, const geo::AzEl& logged, const geo::PointingTerms& terms) {
  StationView v;
  if (terms.IsZero()) {
    v.boresight = logged;
    v.mount_yaw_rad = camera.mount_yaw_rad;
    v.mount_pitch_rad = camera.mount_pitch_rad;
    v.mount_roll_rad = camera.mount_roll_rad;
    return v;
  }
  const Eigen::Matrix3d R_pm = geo::RotationEnuFromTurret(logged.az_rad, logged.el_rad, terms);
  v.boresight = geo::AzElFromEnu(R_pm.col(2));
  const Eigen::Matrix3d R0 = geo::RotationEnuFromTurret(v.boresight.az_rad, v.boresight.el_rad);
  const Eigen::Matrix3d R = R0.transpose() * R_pm * camera.RotationTurretFromCamera();
  // R = Ry(yaw)·Rx(pitch)·Rz(roll): third column (sin yaw cos pitch, −sin pitch, cos yaw cos pitch),
  // second row (cos pitch sin roll, cos pitch cos roll, −sin pitch).
  v.mount_pitch_rad = std::asin(std::clamp(-R(1, 2), -1.0, 1.0));
  v.mount_yaw_rad = std::atan2(R(0, 2), R(2, 2));
  v.mount_roll_rad = std::atan2(R(1, 0), R(1, 1));
  return v;
}

CameraModel CameraInView(CameraModel camera, const StationView& view) {
  camera.mount_yaw_rad = view.mount_yaw_rad;
  camera.mount_pitch_rad = view.mount_pitch_rad;
  camera.mount_roll_rad = view.mount_roll_rad;
  return camera;
}

}  // namespace rk::camera

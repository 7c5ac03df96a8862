// The camera the rk-locate tests share: the default camera with every distortion term and a mount
// misalignment on all three axes, so that no term of SPEC §3's model can be dropped unnoticed.
#pragma once

#include "camera/camera_model.h"
#include "geo/angles.h"

namespace rk::locate::test_data {

inline camera::CameraModel DistortedMisalignedCamera() {
  camera::CameraModel cam = camera::DefaultCamera();
  cam.distortion = {-0.08, 0.02, 2e-4, -1e-4, 0.001};
  cam.mount_yaw_rad = geo::DegToRad(0.4);
  cam.mount_pitch_rad = geo::DegToRad(-0.25);
  cam.mount_roll_rad = geo::DegToRad(0.6);
  return cam;
}

}  // namespace rk::locate::test_data

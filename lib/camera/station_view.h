// The turret pointing model of SPEC.md §3.1 in the tools that turn pixels and turret angles into directions
// (rk-locate, rk-attitude oi, rk-attitude cylinder), without rewriting their §3 geometry:
//
// Under the pointing model the camera-to-ENU rotation is R_pm · R_turret_cam with
// R_pm = geo::RotationEnuFromTurretT(A, E, az_offset, tilt_north, tilt_east, el_axis_tilt). Let b' = R_pm·(0,0,1)
// be the true boresight, (A', E') its azimuth and elevation and R0 = geo::RotationEnuFromTurret(A', E') the §3
// turret frame there. Then Q = R0ᵀ·R_pm fixes the boresight axis (a roll about it) and, exactly,
//   R_pm · R_turret_cam = R0(A', E') · R'_turret_cam,   R'_turret_cam = Q · R_turret_cam.
// R'_turret_cam is written back as mount angles Ry(yaw')·Rx(pitch')·Rz(roll') (|pitch'| < 90°: a mount is a small
// misalignment). So every §3 routine (RayEnu, ProjectEnu, the budgets, the pose's R_enu_cam) gives §3.1's result
// when called with (A', E') and the camera with that mount — exact, no small-angle approximation.
// With every term zero the logged angles and the camera are returned unchanged (bit-identical results).
#pragma once

#include "camera/camera_model.h"
#include "geo/line_of_sight.h"
#include "geo/pointing.h"

namespace rk::camera {

struct StationView {
  geo::AzEl boresight;        // (A', E'): the true boresight direction (radians)
  double mount_yaw_rad = 0;   // the camera's mount in the turret frame at (A', E')
  double mount_pitch_rad = 0;
  double mount_roll_rad = 0;
};

// The §3 boresight and camera mount equivalent to logged angles `logged` under `terms` (see above).
StationView ApplyPointing(const CameraModel& camera, const geo::AzEl& logged, const geo::PointingTerms& terms);

// `camera` with the mount of `view`.
CameraModel CameraInView(CameraModel camera, const StationView& view);

}  // namespace rk::camera

// Budget model "locate" (rk-locate's computation, seed 001 / SPEC.md §3 and §3.1): one pixel, the logged turret
// angles, the turret's pointing model, the camera's mount and a range → line-of-sight azimuth and elevation and
// the ENU position of the target.
//   inputs  boresight_az, boresight_el (rad), x, y (px), range (m),
//           az_offset, tilt_north, tilt_east, el_axis_tilt (rad; the pointing model, SPEC.md §3.1),
//           mount_yaw, mount_pitch, mount_roll (rad; the camera's mount)
//   outputs az (wraps), el (rad), e, n, u (m)
//   groups  "boresight" = both angles, "pixels" = x and y, "pointing" = the four terms, "mount" = the three angles
// y = g(x): ray = camera::RayEnuT (camera/projection.h, the line of sight rk-locate uses);
// az = atan2(e, n), el = atan2(u, hypot(e, n)); p = range · ray.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "analysis/budget.h"
#include "camera/camera_model.h"
#include "camera/pointing_model.h"

namespace rk::analysis {

// `nominal`: {"boresight_az_deg", "boresight_el_deg", "x_px", "y_px", "range_m"}; the pointing terms' nominal
// values are `pointing`'s, the mount's the camera's. Errors name `where`.
std::unique_ptr<BudgetModel> MakeLocateBudgetModel(const io::Json& nominal, const camera::CameraModel& camera,
                                                   const camera::PointingModel& pointing, const std::string& where);

// The calibrated σ the files already carry, as sources of a "locate" budget: each pointing term with a "sigma"
// in pointing.json (`pointing_file` names it in the source), each mount angle with a σ in the camera's
// "calibration" (camera::CameraCalibrationSigma). A σ of 0 or none gives no source.
std::vector<BudgetSource> LocateCalibrationSources(const BudgetModel& model, const camera::CameraModel& camera,
                                                   const camera::PointingModel& pointing,
                                                   const std::string& pointing_file, const std::string& where);

}  // namespace rk::analysis

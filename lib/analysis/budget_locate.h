// Budget model "locate" (rk-locate's computation, seed 001 / SPEC.md §3): one pixel, the boresight angles and
// a range → line-of-sight azimuth and elevation and the ENU position of the target.
//   inputs  boresight_az, boresight_el (rad), x, y (px), range (m)
//   outputs az (wraps), el (rad), e, n, u (m)
//   groups  "boresight" = both angles, "pixels" = x and y
// y = g(x): ray = camera.RayEnu(px, A, E); az = atan2(e, n), el = atan2(u, hypot(e, n)); p = range · ray.
#pragma once

#include <memory>
#include <string>

#include "analysis/budget.h"
#include "camera/camera_model.h"

namespace rk::analysis {

// `nominal`: {"boresight_az_deg", "boresight_el_deg", "x_px", "y_px", "range_m"}; errors name `where`.
std::unique_ptr<BudgetModel> MakeLocateBudgetModel(const io::Json& nominal, const camera::CameraModel& camera,
                                                   const std::string& where);

}  // namespace rk::analysis

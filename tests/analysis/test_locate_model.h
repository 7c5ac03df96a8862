// Shared by the budget tests: the Jacobian tolerance, and the "locate" budget model (analysis/budget_locate.h)
// on a camera with lens distortion and a tilted mount, at a given boresight and pixel, 850 m away.
#pragma once

#include <memory>

#include "analysis/budget.h"
#include "analysis/budget_locate.h"
#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "geo/angles.h"
#include "io/json_util.h"

namespace rk::analysis {

// Central differences with steps 1e-7 rad / 1e-4 px / 1e-6 m have truncation + rounding ~1e-8 relative.
inline constexpr double kJacobianRel = 1e-6;

inline camera::CameraModel DistortedCamera() {
  camera::CameraModel c = camera::DefaultCamera();
  c.distortion = {-0.08, 0.02, 0.001, -0.0005, 0.0};
  c.mount_yaw_rad = geo::DegToRad(0.3);
  c.mount_pitch_rad = geo::DegToRad(-0.2);
  c.mount_roll_rad = geo::DegToRad(0.5);
  return c;
}

// A turret pointing model of a few arcminutes per term, with the σ rk-calibrate pointing would give it.
inline camera::PointingModel TiltedTurret() {
  camera::PointingModel p;
  p.terms = {geo::DegToRad(0.05), geo::DegToRad(-0.03), geo::DegToRad(0.02), geo::DegToRad(0.04)};
  p.sigma_rad = {geo::DegToRad(10.0 / 3600), geo::DegToRad(4.0 / 3600), geo::DegToRad(4.0 / 3600), std::nullopt};
  return p;
}

inline std::unique_ptr<BudgetModel> Locate(double az_deg, double el_deg, double x, double y,
                                           const camera::PointingModel& pointing = TiltedTurret()) {
  const io::Json nominal = {{"boresight_az_deg", az_deg}, {"boresight_el_deg", el_deg}, {"x_px", x}, {"y_px", y},
                            {"range_m", 850.0}};
  return MakeLocateBudgetModel(nominal, DistortedCamera(), pointing, "budget.json");
}

}  // namespace rk::analysis

#include "sim/trajectory.h"

#include <cmath>

#include "geo/angles.h"
#include "geo/line_of_sight.h"

namespace rk::sim {
namespace {

constexpr double kDefaultHalfLengthM = 13.0;  // L of the default back-and-forth line
constexpr double kDefaultBobM = 1.5;          // vertical bob amplitude of the default trajectory

}  // namespace

bool ParseTrajectoryKind(const std::string& name, TrajectoryKind* kind) {
  if (name == "default") *kind = TrajectoryKind::kDefault;
  else if (name == "straight") *kind = TrajectoryKind::kStraight;
  else if (name == "turning") *kind = TrajectoryKind::kTurning;
  else if (name == "overhead") *kind = TrajectoryKind::kOverhead;
  else if (name == "static") *kind = TrajectoryKind::kStatic;
  else return false;
  return true;
}

std::string TrajectoryKindName(TrajectoryKind kind) {
  switch (kind) {
    case TrajectoryKind::kDefault: return "default";
    case TrajectoryKind::kStraight: return "straight";
    case TrajectoryKind::kTurning: return "turning";
    case TrajectoryKind::kOverhead: return "overhead";
    case TrajectoryKind::kStatic: return "static";
  }
  return "?";
}

const io::OptionTable<TrajectoryOptions>& TrajectoryOptions::Table() {
  static const io::OptionTable<TrajectoryOptions> table = io::OptionTable<TrajectoryOptions>().Real(
      "--max-el-deg", &TrajectoryOptions::max_elevation_deg, "deg", io::Bounds::LeftOpen(0.0, 85.0),
      "overhead: elevation at closest approach (deg)");
  return table;
}

bool TrajectoryOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!(range_m >= 20.0 && range_m <= 10000.0)) return fail("range must be in [20, 10000] m");
  if (!(speed_mps >= 0.0 && speed_mps <= 1000.0)) return fail("speed must be in [0, 1000] m/s");
  if (kind == TrajectoryKind::kDefault && !(speed_mps > 0.0)) return fail("the default trajectory needs a speed > 0");
  if (!std::isfinite(azimuth_rad)) return fail("azimuth must be finite");
  if (!(elevation_rad >= geo::DegToRad(-10.0) && elevation_rad <= geo::DegToRad(80.0))) {
    return fail("elevation must be in [-10, 80] deg");
  }
  if (!std::isfinite(t_mid_s)) return fail("t_mid must be finite");
  if (kind == TrajectoryKind::kTurning) {
    if (!(turn_rate_rad_s > 0.0 && turn_rate_rad_s <= 2.0)) return fail("turn rate must be in (0, 2] rad/s");
    if (speed_mps / turn_rate_rad_s > 0.8 * range_m * std::cos(elevation_rad)) {
      return fail("turn radius speed/turn-rate must be at most 0.8 x the horizontal range");
    }
  }
  return true;
}

Trajectory::Trajectory(const TrajectoryOptions& opt) : opt_(opt) {
  const double a = opt.azimuth_rad;
  right_enu_ = Eigen::Vector3d(std::cos(a), -std::sin(a), 0.0);
  const Eigen::Vector3d los_h(std::sin(a), std::cos(a), 0.0);
  along_enu_ = (los_h + right_enu_).normalized();  // 45° to the line of sight
  if (opt.kind == TrajectoryKind::kOverhead) {
    const double h = opt.range_m * std::sin(opt.max_elevation_rad());
    const double d = opt.range_m * std::cos(opt.max_elevation_rad());
    centre_enu_ = d * los_h + Eigen::Vector3d(0, 0, h);
  } else {
    centre_enu_ = opt.range_m * geo::DirectionFromAzEl(a, opt.elevation_rad);
  }
  if (opt.kind == TrajectoryKind::kTurning) {
    radius_m_ = opt.speed_mps / opt.turn_rate_rad_s;
    phase0_rad_ = std::atan2(-centre_enu_.y(), -centre_enu_.x());
  }
}

Eigen::Vector3d Trajectory::PositionEnu(double t_s) const {
  const double dt = t_s - opt_.t_mid_s;
  switch (opt_.kind) {
    case TrajectoryKind::kStatic:
      return centre_enu_;
    case TrajectoryKind::kDefault: {
      const double w = opt_.speed_mps / kDefaultHalfLengthM;
      const double s = kDefaultHalfLengthM * std::sin(w * dt);
      const double bob = kDefaultBobM * std::sin(0.37 * w * dt);
      return centre_enu_ + s * along_enu_ + Eigen::Vector3d(0, 0, bob);
    }
    case TrajectoryKind::kStraight:
    case TrajectoryKind::kOverhead:
      return centre_enu_ + opt_.speed_mps * dt * right_enu_;
    case TrajectoryKind::kTurning: {
      const double phi = phase0_rad_ + opt_.turn_rate_rad_s * dt;
      return centre_enu_ + radius_m_ * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0);
    }
  }
  return centre_enu_;
}

Eigen::Vector3d Trajectory::VelocityEnu(double t_s) const {
  constexpr double h = 1e-4;
  return (PositionEnu(t_s + h) - PositionEnu(t_s - h)) / (2 * h);
}

}  // namespace rk::sim

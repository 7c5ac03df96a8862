// Target trajectories in the station ENU frame (x east, y north, z up, metres,
// origin at the turret rotation centre) for the synthetic trials of rk-sim.
//
// Each trajectory is a closed-form position p_enu(t) of the target's body
// reference point, smooth in t (so that the servo model and range
// interpolation see realistic, differentiable motion). The geometry is fixed
// by a "nominal" direction (azimuth A0 clockwise from north, elevation E0) and
// a nominal range R:
//   static   p(t) = R · dir(A0, E0)
//   default  seed 001's field trial: back-and-forth along a horizontal line
//            oblique to the line of sight (45° to it), with a slow vertical bob:
//            p(t) = c + s(t)·h + w(t)·z,  c = R·dir(A0, E0),
//            s(t) = L sin(ω (t − t_mid)),  ω = v / L,  L = 13 m (so peak speed = v),
//            w(t) = 1.5 m · sin(0.37 ω (t − t_mid)); speed and range change all the time.
//   straight constant-velocity level pass, closest approach R at t_mid at
//            (A0, E0), velocity horizontal and perpendicular to the line of sight:
//            p(t) = c + v (t − t_mid) · h⊥.
//   turning  coordinated (constant-speed, constant-rate) level turn: a circle of
//            radius ρ = v / ω centred at R·dir(A0, E0), p(t) = c + ρ (cos φ, sin φ, 0),
//            φ = φ0 + ω (t − t_mid), φ0 chosen so that the target is nearest
//            the station at t_mid.
//   overhead level straight pass whose closest point has slant range R and
//            elevation Emax (default 80°): height H = R sin Emax, horizontal miss
//            distance D = R cos Emax; p(t) = D·(sin A0, cos A0, 0) + H·z + v (t − t_mid)·h⊥.
// where h⊥ = (cos A0, −sin A0, 0) is the horizontal direction to the right of the
// line of sight. Paper: Guan et al. 2014 (seed 001) for the default trial.
#pragma once

#include <Eigen/Core>
#include <string>

#include "geo/angles.h"
#include "io/options.h"

namespace rk::sim {

enum class TrajectoryKind { kDefault, kStraight, kTurning, kOverhead, kStatic };

// "default" | "straight" | "turning" | "overhead" | "static"; false if unknown.
bool ParseTrajectoryKind(const std::string& name, TrajectoryKind* kind);
std::string TrajectoryKindName(TrajectoryKind kind);

struct TrajectoryOptions {
  TrajectoryKind kind = TrajectoryKind::kDefault;
  double range_m = 80.0;               // nominal / closest-approach range (m), [20, 10000]
  double speed_mps = 2.7;              // peak (default) or constant speed (m/s), [0, 1000]
  double azimuth_rad = 0.5235987755982988;   // nominal azimuth A0 (rad), clockwise from north
  double elevation_rad = 0.0872664625997165;  // nominal elevation E0 (rad), [-0.2, 1.4]; unused by overhead
  double max_elevation_deg = 80.0;     // overhead: elevation at closest approach (deg), (0, 85]
  double turn_rate_rad_s = 0.1;        // turning: ω (rad/s), > 0
  double t_mid_s = 6.0;                // time of closest approach / centre of the motion (s)

  double max_elevation_rad() const { return geo::DegToRad(max_elevation_deg); }

  // The options a command line sets (--max-el-deg); the kind and the nominal geometry come from
  // DefaultTrajectoryOptions (rk-sim beacon's --trajectory, --range-m, ... are optional values).
  static const io::OptionTable<TrajectoryOptions>& Table();
  // Table().Check, then the rules between options (speed, turn radius).
  bool Check(std::string* why) const;
};

class Trajectory {
 public:
  explicit Trajectory(const TrajectoryOptions& opt);
  // Body reference point in station ENU (m) at time t (s).
  Eigen::Vector3d PositionEnu(double t_s) const;
  // Velocity (m/s), by central difference of PositionEnu (exact enough for
  // the smooth closed forms above: error ~1e-9 m/s).
  Eigen::Vector3d VelocityEnu(double t_s) const;
  const TrajectoryOptions& options() const { return opt_; }

 private:
  TrajectoryOptions opt_;
  Eigen::Vector3d centre_enu_;
  Eigen::Vector3d right_enu_;  // h⊥
  Eigen::Vector3d along_enu_;  // default: line direction
  double phase0_rad_ = 0.0;    // turning
  double radius_m_ = 0.0;      // turning
};

}  // namespace rk::sim

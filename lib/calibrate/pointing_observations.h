// The inputs of rk-calibrate pointing (SPEC.md §1.1, §3.1) turned into what the solver fits: for each
// image point of a known target, the logged turret angles at the frame's true time, the target's
// direction in station ENU at that time, and which errors it shares with other observations.
//
//   observations  frame,t_s,id,x_px,y_px[,sigma_x_px,sigma_y_px]   (SPEC.md §2.1 image points)
//   true time     t_s + time_offset_s (camera latency, SPEC.md §3); the turret log's times are true
//   turret        track::BoresightSource (linear interpolation, no extrapolation) at the true time
//   target        landmark: constant ENU direction; star: observed place at epoch_utc + true time
//
// Shared errors. A stepper turret holding still logs one encoder value for every frame of a dwell: its
// quantisation error (uniform, σ = step/√12 per axis) is one draw per dwell. Observations are grouped
// into clusters: consecutive observations with bit-identical logged angles share one: a dwell, or the
// targets seen in one frame during a slew; an observation during a slew alone in its frame has its own.
// During a slew an axis's reading is interpolated between two log samples: where the axis moves at least
// 3 encoder steps per log interval their errors are independent and the interpolated reading's σ is
// step/√12 · √((1 − w)² + w²), w the image point's position between the two samples (a camera at a fixed
// phase to the log has the same w in every frame); where it moves slower (the S-curve ends, where most
// image points of a slew are taken) the samples' errors are correlated and the reading keeps
// σ = step/√12. The log reads the dwell's value from the moment the turret enters the dwell's encoder
// cell, but the turret still creeps inside that cell until it stops (and starts creeping before it
// leaves): an image point within the creep window of either end of a still stretch gets its own reading
// error (σ = step/√12) instead of the dwell's. The window is 2.5 × the time the turret took to cross the
// previous cell (the last two transitions of the log), plus one log interval: for an approach at constant
// deceleration the creep after the last transition lasts at most (1 + √2) × that time.
// A landmark with `sigma_m` contributes one shared direction error per landmark (σ = sigma_m / range per
// axis).
// Turret rate. τ moves the turret angle by its rate × Δτ. Where the turret is slow the slope of the log
// between two samples is mostly quantisation (0, or one step per interval); the rate is therefore taken
// over ±50 ms of the log, which averages the steps. (With the local slope, image points at the slow ends
// of the slews, whose reading error is then about (w − ½) × the step, the same for every frame at a fixed
// phase w between log samples, made the time offset's σ optimistic: mean NEES 1.5 in a Monte Carlo.)
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "io/csv.h"
#include "formats/image_points.h"
#include "target/calibration_targets.h"
#include "track/boresight.h"

namespace rk::calibrate {

// One row of the observations file.
struct ImagePoint {
  std::int64_t frame = 0;
  double t_s = 0.0;
  std::string id;
  Eigen::Vector2d px = Eigen::Vector2d::Zero();
  std::optional<Eigen::Vector2d> sigma_px;  // from sigma_x_px,sigma_y_px when both are given
  std::size_t line = 0;                     // file line
  int id_column = 0;                        // 1-based character column of the id cell (messages)
};
struct ImagePoints {
  std::string source;
  std::vector<ImagePoint> rows;      // the measured points (formats::ImagePoint::measured)
  std::size_t unmeasured_rows = 0;   // rows without a position to fit (lost, invalid, predicted, empty)
};
// The observations: an image-points file (formats::ReadImagePoints: its checks and messages).
ImagePoints ReadImagePoints(const io::CsvTable& table);
// The cells ReadImagePoints needs of every row (--bad-rows skip).
inline io::CsvRowRule ImagePointsRowRule() { return formats::ImagePointsRowRule(); }

// The targets the observations may name, with where they came from (messages).
struct TargetCatalogue {
  std::vector<target::Landmark> landmarks;
  std::string landmarks_source;
  std::vector<target::Star> stars;
  std::string stars_source;
  target::Geodetic station;
  std::optional<target::UtcJd> epoch_utc;  // required when stars are given
  double dut1_s = 0.0;
  target::Atmosphere atmosphere;
};

// One observation ready for the solver: everything at the linearisation time offset tau0_s.
struct PointingObservation {
  std::size_t row = 0;  // index into ImagePoints::rows
  Eigen::Vector2d px = Eigen::Vector2d::Zero();
  Eigen::Vector2d sigma_px = Eigen::Vector2d::Ones();
  double t_turret_s = 0.0;                      // t_s + tau0_s: the turret-log time of the observation
  double az_log_rad = 0.0, el_log_rad = 0.0;    // logged boresight at t_s + tau0_s (unwrapped az)
  double az_rate_rps = 0.0, el_rate_rps = 0.0;  // turret rates (rad/s) there, over ± kTurretRateHalfWindowS
  bool log_moving = false;                       // the logged angles change within ± kRateStepS
  double sample_weight = 0.5;                    // position between the two log samples interpolated (0..1)
  Eigen::Vector3d dir_enu = Eigen::Vector3d::UnitY();  // unit target direction at t_s + tau0_s
  Eigen::Vector3d dir_rate_enu = Eigen::Vector3d::Zero();  // its time derivative (stars move; 1/s)
  int target = 0;         // index into PointingObservations::target_ids
  int cluster = 0;        // shared turret-reading error (index into cluster_sigma_rad)
  bool is_star = false;
};
struct PointingObservations {
  double tau0_s = 0.0;  // time offset the turret and targets were evaluated at
  std::vector<PointingObservation> obs;
  std::vector<std::string> target_ids;
  std::vector<double> target_sigma_rad;         // shared direction error per target (0 = exact)
  std::vector<Eigen::Vector2d> cluster_sigma_rad;  // per cluster: σ of the az and el readings
  std::vector<int> cluster_size;
  std::size_t dwells = 0;  // clusters of a still turret with more than one observation
};

// Builds the observations at time offset tau0_s. Throws DataError at the observation's file:line:col for
// an id that is neither a landmark nor a star, a star without an epoch, a target below the horizon, a
// frame time the turret log does not cover. Rows without sigma_x_px,sigma_y_px get default_sigma_px.
PointingObservations BuildObservations(const ImagePoints& points, const TargetCatalogue& targets,
                                       const track::BoresightSource& turret, double encoder_step_rad,
                                       double default_sigma_px, double tau0_s);

}  // namespace rk::calibrate

// Synthetic 6-DOF pose tracks with truth at sample and mid-times (rk-sim posetrack;
// seed 000, Sun & Zhang 2015: adaptive-UKF fixed-lead prediction of helmet pose).
//
// Pose. p(t) = (x, y, z, yaw, pitch, roll): position of the target (helmet / turntable
// target) origin in the measuring camera's frame (m) and its Z-Y-X attitude angles
// (SPEC.md §3 conventions; rad inside, deg in the files). Every component follows a
// closed form with exact analytic first and second derivatives:
//   p_c(t) = c_c + s_c (t − t0) + Σ_i a_ci sin(2π f_ci (t − t0) + φ_ci)
// Scenarios:
//   turntable  seed 000's experiment (§4.2): yaw = yaw0 + ω (t − t0) with ω = 10°/s,
//              position and the other two angles constant (x, y, z) = (0.05, −0.02,
//              0.80) m, pitch 10°, roll −5°; 20 fps, 0–9 s.
//   head       maneuvering head motion: each component is a sum of 3 sines with
//              frequencies uniform in [0.1, 2] Hz and phases uniform in [0, 2π); the
//              component's total amplitude A is uniform in [0.1, 0.3] m (position) or
//              [10°, 40°] (angles) and is split among its sines with weights ∝ u_i / f_i
//              (u_i uniform in [0.5, 1]: slower motions are larger, as in head motion),
//              so |p_c − c_c| ≤ A. Accelerations change continuously. Centres: position
//              (0, 0, 0.8) m, pitch and roll 0; the yaw centre is chosen so that the yaw
//              over the sample and mid-times spans [−h, +h] (h = half its range): the
//              yaw crosses north (0/360) at least once.
// Sample times t_k = t0 + k / fps, k = 0 … K with K = ⌊duration·fps⌋ (both ends of
// [t0, t0 + duration] included: 0–9 s at 20 fps = 181 samples); mid-times
// t_{k+1/2} = t0 + (k + 1/2) / fps, k = 0 … K − 1.
// Measurements at t_k: truth + independent Gaussian noise N(0, σ²) per component
// (σ_angle for the three angles, σ_pos for x, y, z); with probability `dropout` a whole
// row is missing (all six values empty), and each remaining value is missing with
// probability `dropout_value`.
// Determinism: std::mt19937_64 streams seeded with seed_seq{seed, stream}: stream 1 =
// head-profile parameters, 2 = measurement noise, 3 = dropout, so the noise does not
// change when the dropout options do.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geo/angles.h"
#include "io/json_util.h"
#include "io/options.h"

namespace rk::sim {

enum class PoseScenario { kTurntable, kHead };

// "turntable" | "head"; false if unknown.
bool ParsePoseScenario(const std::string& name, PoseScenario* scenario);
std::string PoseScenarioName(PoseScenario scenario);

// Pose components in file order and their CSV names (SPEC.md §2 units in names):
// values x_m … roll_deg, rates <base>_rate_<unit>_s, accelerations <base>_accel_<unit>_s2.
inline constexpr int kPoseDof = 6;
inline constexpr int kPoseYaw = 3;  // index of yaw (wrapped to [0, 360) in files)
const std::array<std::string, kPoseDof>& PoseColumns();       // x_m,y_m,z_m,yaw_deg,pitch_deg,roll_deg
const std::array<std::string, kPoseDof>& PoseRateColumns();   // x_rate_m_s … roll_rate_deg_s
const std::array<std::string, kPoseDof>& PoseAccelColumns();  // x_accel_m_s2 … roll_accel_deg_s2
bool PoseIsAngle(int component);                               // components 3, 4, 5

using PoseVector = Eigen::Matrix<double, kPoseDof, 1>;  // (m, m, m, rad, rad, rad)

struct PoseTrackOptions {
  PoseScenario scenario = PoseScenario::kTurntable;
  double duration_s = 9.0;   // trial length (s), (0, 3600]; samples cover [t0, t0 + duration]
  double fps = 20.0;         // sample rate (Hz), (0, 1000]; at least 3 samples in all
  double t0_s = 0.0;         // time of sample 0 since the trial epoch (s), finite, >= 0
  double noise_deg = 0.0724;                        // angle noise std (deg), [0, 10]; seed 000 Table 1
  double noise_position_m = 0.5e-3;                 // position noise std (m), [0, 1]
  double rate_rad_s = geo::DegToRad(10.0);         // turntable yaw rate ω (rad/s), |ω| <= 1000°/s
  double yaw0_rad = geo::DegToRad(20.0);           // turntable yaw at t0 (rad), [0, 2π)
  double dropout = 0.0;                             // probability of a missing row, [0, 1)
  double dropout_value = 0.0;                       // probability of a missing value, [0, 1)
  std::uint64_t seed = 1;

  double noise_angle_rad() const { return geo::DegToRad(noise_deg); }
  // Every number and choice option; not in it: the scenario-dependent optional values --duration,
  // --rate-deg-s, --yaw0-deg (registered by the app; DefaultPoseTrackOptions gives their defaults).
  static const io::OptionTable<PoseTrackOptions>& Table();
  // Table().Check, then the optional values and the sample count.
  bool Check(std::string* why) const;
  // The run report's "options": Table().ToJson plus the duration (and the turntable's rate and yaw0).
  io::Json ToJson() const;
};
// Defaults of a scenario: turntable 9 s, head 20 s; everything else as above.
PoseTrackOptions DefaultPoseTrackOptions(PoseScenario scenario);
io::Json PoseTrackOptionsToJson(const PoseTrackOptions& opt);

// One sinusoid of a component's motion.
struct PoseSine {
  double amplitude = 0.0;  // m or rad
  double freq_hz = 0.0;
  double phase_rad = 0.0;
};
// Closed-form motion of one component: c + s (t − t0) + Σ a sin(2π f (t − t0) + φ).
struct PoseComponentMotion {
  double centre = 0.0;  // m or rad
  double slope = 0.0;   // m/s or rad/s
  std::vector<PoseSine> sines;
};

// Truth at one time: values (yaw unwrapped, i.e. continuous), rates and accelerations.
struct PoseTruth {
  double t_s = 0.0;
  PoseVector value = PoseVector::Zero();
  PoseVector rate = PoseVector::Zero();   // m/s, rad/s
  PoseVector accel = PoseVector::Zero();  // m/s², rad/s²
};

struct PoseMeasurement {
  double t_s = 0.0;
  PoseVector value = PoseVector::Zero();  // truth + noise, yaw unwrapped; NaN = missing
  bool row_missing = false;               // the whole row dropped
};

class PoseTrackSimulator {
 public:
  // Throws UsageError if the options fail Check().
  explicit PoseTrackSimulator(PoseTrackOptions opt);

  const PoseTrackOptions& options() const { return opt_; }
  const std::array<PoseComponentMotion, kPoseDof>& motion() const { return motion_; }
  // Exact truth at any time.
  PoseTruth TruthAt(double t_s) const;

  std::size_t sample_count() const { return sample_t_s_.size(); }
  const std::vector<double>& sample_times() const { return sample_t_s_; }  // t_k
  const std::vector<double>& mid_times() const { return mid_t_s_; }        // t_{k+1/2}
  const std::vector<PoseMeasurement>& measurements() const { return meas_; }

 private:
  PoseTrackOptions opt_;
  std::array<PoseComponentMotion, kPoseDof> motion_;
  std::vector<double> sample_t_s_, mid_t_s_;
  std::vector<PoseMeasurement> meas_;
};

struct PoseTrackWriteOptions {
  std::string out_dir;  // folder to create
  bool force = false;   // replace an existing non-empty out_dir
  static const io::OptionTable<PoseTrackWriteOptions>& Table();  // --force (--out is registered by the app)
  bool Check(std::string* why) const;
};

struct PoseTrackSummary {
  std::int64_t samples = 0;
  std::int64_t mid_times = 0;
  std::int64_t missing_rows = 0;
  std::int64_t missing_values = 0;  // values missing in rows that are not missing as a whole
  std::int64_t yaw_wraps = 0;       // crossings of north (0/360) by the true yaw over the sample and mid-times
  double max_abs_rate_deg_s = 0.0;  // largest |true angular rate| of the three angles
  double max_abs_accel_deg_s2 = 0.0;
  double max_abs_speed_mps = 0.0;   // largest |true rate| of x, y, z
  io::Json ToJson() const;
};

// Writes measurements.csv, truth.csv, truth_sample.csv, truth_mid.csv and scenario.json
// (docs/rk-sim.md) into a new folder, atomically: a temporary sibling folder
// "<parent>/.<name>.XXXXXX" is filled and renamed onto the output at the end. An
// existing non-empty output is refused (UsageError) unless `force`, which replaces it
// as a whole. Throws IoError if it cannot write.
PoseTrackSummary WritePoseTrack(const PoseTrackSimulator& sim, const PoseTrackWriteOptions& opt);

}  // namespace rk::sim

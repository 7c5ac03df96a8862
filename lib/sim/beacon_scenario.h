// Synthetic beacon-tracking trial with ground truth (rk-sim beacon; seed 001,
// Guan et al. 2014: beacon camera on a pan/tilt turret plus a 5 Hz laser
// rangefinder).
//
// Scene. A target body reference point p_enu(t) moves on a Trajectory
// (sim/trajectory.h). It carries a cooperative lamp cluster: N >= 5 point lamps
// in a plane facing the station (perpendicular to the line of sight):
//   lamp_i = p + (S/2) (a_i r + b_i u),  r = unit(los × z), u = r × los,
// with lamp 0 at the reference point (a, b) = (0, 0) and lamps 1..N−1 on the
// unit circle at angles 0.3 + 2π(i−1)/(N−1) rad; S = cluster span (m). Lamp i
// has relative intensity w_i = 1 − 0.3·frac(0.618034·i) ∈ (0.7, 1] (lamp 0 = 1).
// Images. A turret (sim/turret_servo.h) follows the direction of p with lag and
// jitter; during a servo hold [t0 + START, t0 + START + DURATION) the turret's
// command stays at the target direction of the hold's start (the turret stops)
// and afterwards it catches up through its lag, so the image motion reverses
// (docs/rk-sim.md "Servo hold"); the true boresight (A, E) at frame time t_k = t0 + k / fps drives the
// exact camera projection (camera::CameraModel::ProjectEnu, with the model's
// distortion and mount). Lamp i is a pixel-integrated Gaussian spot of std
// σ_psf (px) and fixed amplitude peak_dn · w_i (DN above background, 8-bit
// scale: exposure is set for the beacon, so the peak does not change with
// range). Distractors are single bright glints (amplitude 0.5–1.5 × peak_dn,
// σ 1.0 px) drifting slowly (or fixed) in the image, never closer to the
// cluster centre than the cluster radius + 30 px. Occlusion intervals hide
// every lamp. Frames are digitised by sim::Digitise (background, shot noise,
// read noise, quantisation); for 16-bit output every DN quantity is ×256.
// Truth (docs/rk-sim.md):
//   centre_px   = FluxWeightedCentre(lamp spots) — the expected grey-weighted centroid;
//   az/el       = AzElFromEnu(camera.RayEnu(centre_px, A, E)) at the TRUE boresight;
//   range_m     = |p|, p_enu = p (body reference point).
// Determinism: everything random is drawn from std::mt19937_64 streams seeded
// with seed_seq{seed, stream}; frame k's noise uses stream (1000, k), so any
// frame renders the same on its own or in sequence.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "camera/camera_model.h"
#include "geo/pointing.h"
#include "geo/angles.h"
#include "io/json_util.h"
#include "io/options.h"
#include "sim/render.h"
#include "sim/trajectory.h"
#include "sim/turret_servo.h"

namespace rk::sim {

// Camera presets: "default" (2448×2048, 3.45 µm, 50 mm, principal point at the
// centre) and "small" (640×512, same pixel pitch and focal length). False if unknown.
bool CameraPreset(const std::string& name, camera::CameraModel* cam);

// Default nominal range, speed, direction per trajectory kind (docs/rk-sim.md).
TrajectoryOptions DefaultTrajectoryOptions(TrajectoryKind kind);
// The same for a given nominal range: the default speed scales with the range
// so that the angular rate stays that of the default geometry (capped at
// 300 m/s; the default trajectory only slows down below 80 m).
TrajectoryOptions DefaultTrajectoryOptions(TrajectoryKind kind, double range_m);

struct OcclusionInterval {
  double start_s = 0.0;     // seconds after the first frame (t - t0)
  double duration_s = 0.5;  // > 0
};
// "START:DURATION" with DURATION a number of seconds, "short" (0.5 s) or "long" (5 s).
bool ParseOcclusion(const std::string& text, OcclusionInterval* occ, std::string* why);

struct BeaconSimOptions {
  camera::CameraModel camera;          // default: DefaultCamera()
  std::string camera_preset = "default";  // name recorded in the manifest
  TrajectoryOptions trajectory;        // t_mid_s is set to t0 + duration / 2 by the simulator
  double duration_s = 10.0;            // trial length (s), (0, 3600]
  double fps = 20.0;                   // frame rate (Hz), (0, 1000]
  double t0_s = 1.0;                   // time of frame 0 since the trial epoch (s)

  int lamps = 5;                       // lamps in the cluster, [5, 64]
  double cluster_span_m = 0.03;        // S: cluster diameter (m), [0.001, 10]; 3 cm = a five-LED beacon head
  double psf_sigma_px = 1.2;           // lamp PSF std (px), [0.3, 10]
  double peak_dn = 160.0;              // brightest lamp amplitude above background (8-bit DN), (0, 255];
                                       // 160: the overlapping lamps of the 3 cm head peak at ≈ 200 DN at 80 m
  SensorOptions sensor;                // background 10 DN, read noise 2 DN, gain 40 e-/DN, 8 bit

  int distractors = 0;                 // number of glints, [0, 50]
  double distractor_margin_px = 120.0; // glints start at least this far from the cluster centre (px)
  std::vector<OcclusionInterval> occlusions;
  std::vector<OcclusionInterval> servo_holds;  // turret stops, then catches up (same START:DURATION form)

  TurretServoOptions servo;
  double turret_rate_hz = 50.0;        // turret log rate (Hz), (0, 10000]
  double turret_offset_s = 0.0037;     // turret log time offset from the frame grid (s)
  double turret_resolution_deg = 0.003;  // encoder quantisation step (deg), PTU-D48E; 0 = none
  double turret_noise_deg = 0.0;       // extra Gaussian encoder noise std (deg)

  double range_rate_hz = 5.0;          // rangefinder rate (Hz), (0, 1000]
  double range_offset_s = 0.071;       // range log time offset from the frame grid (s)
  double range_noise_mm = 0.35;        // Gaussian range noise std (mm), [0, 10000]
  double range_error_rate = 0.01;      // probability of a device-error row, [0, 1)

  std::uint64_t seed = 1;

  // Station errors (docs/rk-sim.md "Station errors"; not in the table, and in the JSON only when set, so
  // trials without them are written as before): the turret's true pointing model (SPEC.md §3.1). The turret
  // still follows the target (the physical boresight is the servo's); its encoder reads the angles that
  // give that boresight under these terms, and those are logged. The camera's latency is
  // camera.time_offset_s: frames.csv stamps are the mid-exposure times minus it.
  geo::PointingTerms station_pointing;
  // The target's body reference point in the station ENU frame (m) at t (s), replacing `trajectory` when set
  // (not in the table or the JSON): rk-sim multistation gives each station the one target seen from it.
  std::function<Eigen::Vector3d(double)> target_enu;

  double turret_resolution_rad() const { return geo::DegToRad(turret_resolution_deg); }
  double turret_noise_rad() const { return geo::DegToRad(turret_noise_deg); }
  double range_noise_m() const { return range_noise_mm * 1e-3; }

  // Every number option, with the trajectory, sensor and servo tables. Not in it: the camera, the
  // occlusions and servo holds (lists), and the trajectory's kind and geometry (rk-sim beacon's
  // --trajectory selects DefaultTrajectoryOptions; --range-m ... are optional values).
  static const io::OptionTable<BeaconSimOptions>& Table();
  // Table().Check, then the camera size, the trajectory and servo rules, the frame count, the intervals.
  bool Check(std::string* why) const;
  // The run report's "options": Table().ToJson plus the camera, the resolved trajectory and the intervals.
  io::Json ToJson() const;
};
io::Json BeaconSimOptionsToJson(const BeaconSimOptions& opt);

struct FrameTruth {
  std::int64_t frame = 0;
  double t_s = 0.0;
  double boresight_az_rad = 0.0;  // true boresight (lag + jitter), [0, 2π)
  double boresight_el_rad = 0.0;
  std::vector<Spot> lamps;        // image spots of the visible lamps (empty when occluded)
  bool visible = false;           // lamps not occluded
  Eigen::Vector2d centre_px{0, 0};  // flux-weighted centre of all lamps (also computed when occluded)
  double az_rad = 0.0;            // ray through centre_px at the true boresight, [0, 2π)
  double el_rad = 0.0;
  double range_m = 0.0;           // |p_enu|
  Eigen::Vector3d p_enu{0, 0, 0}; // body reference point (m)
  std::vector<Spot> distractors;  // glints in this frame
  double distractor_min_dist_px = -1.0;  // nearest glint to centre_px (px); < 0 when there are none
  double cluster_radius_px = 0.0; // largest lamp distance from centre_px (px)
};

struct TurretSample {
  double t_s = 0.0;
  double true_az_rad = 0.0, true_el_rad = 0.0;  // true encoder angles (the true boresight when the station is perfect)
  double az_rad = 0.0, el_rad = 0.0;            // recorded (quantised, noisy); az in [0, 2π)
};

struct RangeSample {
  double t_s = 0.0;
  double true_range_m = 0.0;
  double range_m = 0.0;  // measured; NaN on a device error
  int status = 0;        // 0 ok, 255 device error
};

class BeaconSimulator {
 public:
  // Throws UsageError if the options fail Check() or if the target leaves the
  // image (too fast for the turret lag) at some frame.
  explicit BeaconSimulator(BeaconSimOptions opt);

  const BeaconSimOptions& options() const { return opt_; }
  std::size_t frame_count() const { return frames_.size(); }
  const FrameTruth& frame(std::size_t k) const { return frames_.at(k); }
  const std::vector<FrameTruth>& frames() const { return frames_; }

  // Renders frame k (CV_8UC1 or CV_16UC1) with the frame's own seeded noise.
  cv::Mat RenderFrame(std::size_t k) const;
  // Renders frame k drawing the noise from `rng`.
  cv::Mat RenderFrame(std::size_t k, std::mt19937_64& rng) const;
  // Noise-free signal of frame k (CV_32FC1, DN above background, 8-bit scale).
  cv::Mat RenderSignal(std::size_t k) const;

  // True boresight at any t in [t0 − 1, t_last + 1] s.
  geo::AzEl TrueBoresight(double t_s) const { return servo_.Boresight(t_s); }
  // The encoder angles (A, E) whose §3.1 boresight under options().station_pointing is `boresight`
  // (Newton; = `boresight` for a perfect station).
  geo::AzEl EncoderAngles(const geo::AzEl& boresight) const;
  Eigen::Vector3d TargetEnu(double t_s) const {
    return opt_.target_enu ? opt_.target_enu(t_s) : trajectory_.PositionEnu(t_s);
  }
  bool Occluded(double t_s) const;
  // Time whose target direction the turret is commanded to at t_s: the start of
  // the servo hold containing t_s, else t_s.
  double CommandTime(double t_s) const;

  // Turret log over [t0 − 0.5, t_last + 0.5] s at turret_rate_hz, and range log likewise.
  std::vector<TurretSample> TurretLog() const;
  std::vector<RangeSample> RangeLog() const;

 private:
  void PlaceDistractors();

  BeaconSimOptions opt_;
  Trajectory trajectory_;
  TurretServo servo_;
  std::vector<Eigen::Vector2d> lamp_unit_;  // (a_i, b_i)
  std::vector<double> lamp_weight_;         // w_i
  std::vector<FrameTruth> frames_;
  struct Glint {
    Eigen::Vector2d p0_px, v_pxps;
    double amplitude_dn = 0, sigma_px = 1.0;
  };
  std::vector<Glint> glints_;
};

}  // namespace rk::sim

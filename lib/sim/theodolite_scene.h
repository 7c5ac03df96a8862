// Synthetic single-station theodolite trial of a cylindrical target with ground truth (rk-sim theodolite;
// seed 004, Tang et al. 2004 §4: cine-theodolite with f = 1500 mm, 0.011 mm pixels, 16.9 mm sensor).
//
// Target: target::CylinderShape and target::CylinderPose (target/cylinder.h: the solid, its pose and the
// silhouette points of SPEC.md §3).
//
// Motion. The target's mid-point c = s0 + (l/2) a is at range R, azimuth A0, elevation E0 from the station at
// the reference time t_ref = t0 + duration/2; it moves along the reference axis at speed v:
//   c(t) = c_ref + v (t − t_ref) a_ref,   ψ(t) = ψ0 + ψ' (t − t_ref),   θ(t) = θ0 + θ' (t − t_ref).
// Theodolite. The true boresight points at c(t) plus a tracking error: the image of c is offset from the
// principal point by (track_px · sin(2π 0.37 t + φx), track_px · cos(2π 0.23 t + φy)) pixels (φ from the
// seed). The log (`t_s,az_deg,el_deg`) is sampled at theodolite_rate_hz with a time offset from the frame
// grid; recorded angles = true + bias (one draw per trial, N(0, angle_bias²) per axis: the static errors of
// the paper's budget) + noise (N(0, angle_noise²) per sample), then quantised to the encoder step. Image
// points. Exact SPEC.md §3 projection of P1..P3 at the true boresight (camera::CameraModel::ProjectEnu, with
// the model's distortion and mount), then optionally Gaussian noise (point_noise_px) and rounding to whole
// pixels (quantise: the paper's "1-pixel" reading error, pixel centres at integers). Determinism:
// std::mt19937_64 streams from seed_seq{seed, stream[, index]}: 1 = trial constants (biases, phases), 2 =
// theodolite noise, 3 = point noise, (1000, k) = image noise of frame k.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "camera/camera_model.h"
#include "io/json_util.h"
#include "io/options.h"
#include "target/cylinder.h"

namespace rk::sim {

// Seed 004 §4: f = 1500 mm, 0.011 mm pixels, 16.9 mm sensor (1536 × 1536 px), principal point at the
// centre, no distortion.
camera::CameraModel Seed004Camera();

struct TheodoliteSimOptions {
  camera::CameraModel camera = Seed004Camera();
  target::CylinderShape shape;      // Check() below also requires 0 < nose_length_m < length_m
  double range_m = 1132.0;          // to the target mid-point at t_ref, [10, 1e6]
  double az_deg = 326.2;            // station → target azimuth at t_ref (see docs/rk-sim.md: seed 004's set-up)
  double el_deg = 16.274;           // elevation at t_ref, [-10, 89]
  double yaw_deg = 76.211;          // seed 004's true axis attitude
  double pitch_deg = 31.257;
  double speed_mps = 0.0;           // along the axis
  double yaw_rate_deg_s = 0.0, pitch_rate_deg_s = 0.0;
  double duration_s = 1.0;          // [0, 3600]
  double fps = 20.0;                // (0, 1000]
  double t0_s = 1.0;                // time of frame 0 since the epoch
  double track_error_px = 20.0;     // tracking error amplitude (px), [0, 1e4]
  double theodolite_rate_hz = 50.0; // (0, 10000]
  double theodolite_offset_s = 0.003;
  double angle_bias_arcsec = 0.0;   // std of the per-trial bias of each axis (arcsec)
  double angle_noise_arcsec = 0.0;  // std of the per-sample noise (arcsec)
  double encoder_step_arcsec = 0.0; // quantisation of the recorded angles; 0 = none
  double point_noise_px = 0.0;      // Gaussian noise of the written image points (px)
  bool quantise = false;            // round the written image points to whole pixels
  std::uint64_t seed = 1;

  // Every number option and --quantise (the target shape's too); not in it: the camera (--camera,
  // --sensor-px) and --angle-budget (sets the angle bias and noise), registered by the app.
  static const io::OptionTable<TheodoliteSimOptions>& Table();
  // Table().Check, then finite values, the nose inside the target.
  bool Check(std::string* why) const;
};
io::Json TheodoliteSimOptionsToJson(const TheodoliteSimOptions& opt);

struct TheodoliteFrameTruth {
  std::int64_t frame = 0;
  double t_s = 0.0;
  target::CylinderPose pose;
  target::SilhouettePoints3d points;
  double boresight_az_rad = 0.0, boresight_el_rad = 0.0;  // true
  Eigen::Vector2d nose_px{0, 0}, tail1_px{0, 0}, tail2_px{0, 0};  // exact projections
  std::array<Eigen::Vector2d, 3> measured_px;               // written points (noise, quantisation)
  double view_angle_rad = 0.0;  // ViewAngle(pose)
  double image_length_px = 0.0; // |nose_px − (tail1_px + tail2_px)/2|
  bool in_image = true;         // every point of the silhouette inside the image
  // The other exact solution of the isosceles P3P on the exact rays (mirror attitude), if any.
  std::optional<double> alt_yaw_rad, alt_pitch_rad;
};

struct TheodoliteSample {
  double t_s = 0.0;
  double true_az_rad = 0.0, true_el_rad = 0.0;
  double az_rad = 0.0, el_rad = 0.0;  // recorded
};

class TheodoliteSimulator {
 public:
  // Throws UsageError if the options fail Check() or a point leaves the image or passes behind the camera.
  explicit TheodoliteSimulator(TheodoliteSimOptions opt);

  const TheodoliteSimOptions& options() const { return opt_; }
  const std::vector<TheodoliteFrameTruth>& frames() const { return frames_; }
  target::CylinderPose PoseAtTime(double t_s) const;
  // True boresight at any time (tracks the target with the tracking error).
  void TrueBoresight(double t_s, double* az_rad, double* el_rad) const;
  // Theodolite log over [t0 − 0.5, t_last + 0.5] s.
  std::vector<TheodoliteSample> TheodoliteLog() const;
  double bias_az_rad() const { return bias_az_; }
  double bias_el_rad() const { return bias_el_; }

 private:
  TheodoliteSimOptions opt_;
  double t_ref_ = 0.0;
  target::CylinderPose pose_ref_;
  double phase_x_ = 0.0, phase_y_ = 0.0;
  double bias_az_ = 0.0, bias_el_ = 0.0;
  std::vector<TheodoliteFrameTruth> frames_;
};

}  // namespace rk::sim

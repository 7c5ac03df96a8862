// Synthetic attitude-camera trial with ground truth (rk-sim attitude; seed 001, Guan et al.
// 2014, §3.3 "attitude experiment": a target with feature points on a six-degree-of-freedom
// gantry, seen by the 100 mm attitude camera on the tracking turret).
//
// Target. Markers (spheres of radius marker_radius_m) at body points p_i (body frame x nose,
// y right, z down, m). The body origin moves in the station ENU frame like the gantry of seed
// 001's dynamic test: starting at range R0 in direction (A0, E0), it approaches the station by
// approach_m along a horizontal line at path_angle to the line of sight, then goes back by
// return_m along the same line:
//   p(t) = p0 + ĥ (approach_m · u1(t) − return_m · u2(t)),  p0 = R0 · dir(A0, E0),
//   ĥ = horizontal unit vector toward the station, turned by path_angle (clockwise seen from above),
// with smooth ramps u1 (0 → 1 over the leg_in_s after the first frame) and u2 (0 → 1 over the
// following leg_out_s), u(τ) = (1 − cos πτ)/2, so speed is zero at the ends and at the turn
// (defaults 12 s and 10 s: 6 m in, 5 m out at ≤ 0.8 m/s; the default duration, 22 s, covers
// both legs; a shorter run covers the start of the approach). The attitude
// follows the paper's "yaw ≈ 10°, pitch ≈ 7°, roll ≈ 5° on the way in, back to the start on the
// way out": (yaw, pitch, roll)(t) = (yaw0, pitch0, roll0) + (Δyaw, Δpitch, Δroll)·(u1 − u2),
// R_ned_body = Rz(yaw)·Ry(pitch)·Rx(roll) (geo/body_attitude.h). Yaw and roll are wrapped, so
// yaw0 = 355° crosses north and roll0 = 177° crosses ±180°.
// Turret. sim::TurretServo follows the direction of the body origin (first-order lag +
// jitter); the camera rides on it (camera::CameraModel::ProjectEnu at the TRUE boresight of
// each frame, with the model's mount and distortion). The turret log is the true boresight at
// turret_rate_hz, quantised to the encoder step (as rk-sim beacon).
// Image. Markers are discs (sim/attitude_render.h) of radius f·r/d at the projection of their
// centre, amplitude marker_dn; the body, when body_dn > 0, is a uniform convex outline around
// the markers (their hull grown by 3 disc radii + 10 px, so each marker sits on uniform
// body paint), digitised by sim::Digitise (background, shot and read noise). Markers may be
// hidden for a while (hide intervals: occlusion tests).
// Truth: the body pose, the boresight, and every marker's projected centre (pixel).
// Determinism: std::mt19937_64 streams from seed_seq{seed, stream}; frame k's noise uses
// stream (1000, k), so any frame renders the same alone or in sequence.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "camera/camera_model.h"
#include "geo/angles.h"
#include "geo/body_attitude.h"
#include "geo/line_of_sight.h"
#include "io/json_util.h"
#include "io/options.h"
#include "sim/render.h"
#include "sim/turret_servo.h"

namespace rk::sim {

// The attitude camera of seed 001: 2448×2048, 3.45 µm pixels, 100 mm lens, centred.
camera::CameraModel AttitudeCamera();

// The default target: 8 markers on an asymmetric airframe-like layout 0.80 × 0.69 × 0.40 m
// (docs/rk-sim.md lists the coordinates).
void DefaultAttitudeMarkers(std::vector<std::string>* ids, std::vector<Eigen::Vector3d>* p_body);

struct MarkerHide {
  std::string id;
  double start_s = 0.0;     // seconds after the first frame
  double duration_s = 0.5;  // > 0
};
// "ID:START:DURATION" (seconds). False with a reason if malformed.
bool ParseMarkerHide(const std::string& text, MarkerHide* hide, std::string* why);

struct AttitudeSimOptions {
  camera::CameraModel camera = AttitudeCamera();
  std::vector<std::string> marker_ids;           // empty: DefaultAttitudeMarkers
  std::vector<Eigen::Vector3d> markers_body;     // body metres, same order
  double marker_radius_m = 0.012;                // sphere radius (m), (0, 1]
  double marker_dn = 150.0;                      // marker level above background (8-bit DN), (0, 255]
  double psf_sigma_px = 0.8;                     // [0.3, 10]
  double body_dn = 25.0;                         // body level above background (8-bit DN), [0, 255]; 0 = no body
  SensorOptions sensor{20.0, 2.0, 40.0, 8};      // background 20 DN, read 2 DN, 40 e-/DN, 8 bit

  double duration_s = 22.0;                      // (0, 3600]
  double fps = 20.0;                             // (0, 1000]
  double t0_s = 1.0;                             // time of frame 0 since the epoch (s)

  double range_m = 22.0;                         // R0 (m), [2, 10000]
  double azimuth_deg = 30.0;                     // A0
  double elevation_deg = 3.0;                    // E0, [-0.2, 1.4] rad
  double approach_m = 6.0;                       // [0, 0.9 R0]
  double leg_in_s = 12.0;                        // duration of the approach (s), > 0
  double leg_out_s = 10.0;                       // duration of the return (s), > 0
  double return_m = 5.0;                         // [0, approach_m + 0.5 R0]
  double path_angle_deg = 30.0;                  // [−1.5, 1.5] rad
  double yaw0_deg = 300.0;                       // side-on (the station sees the left side)
  double pitch0_deg = 5.0;
  double roll0_deg = 0.0;
  double dyaw_deg = 10.0;
  double dpitch_deg = 7.0;
  double droll_deg = 5.0;

  TurretServoOptions servo{0.10};                // lag 0.1 s, 5″ jitter
  double turret_rate_hz = 50.0;
  double turret_offset_s = 0.0037;
  double turret_resolution_deg = 0.003;          // encoder step; 0 = exact
  double turret_noise_deg = 0.0;

  std::vector<MarkerHide> hides;
  std::uint64_t seed = 1;

  double azimuth_rad() const { return geo::DegToRad(azimuth_deg); }
  double elevation_rad() const { return geo::DegToRad(elevation_deg); }
  double path_angle_rad() const { return geo::DegToRad(path_angle_deg); }
  double yaw0_rad() const { return geo::DegToRad(yaw0_deg); }
  double pitch0_rad() const { return geo::DegToRad(pitch0_deg); }
  double roll0_rad() const { return geo::DegToRad(roll0_deg); }
  double dyaw_rad() const { return geo::DegToRad(dyaw_deg); }
  double dpitch_rad() const { return geo::DegToRad(dpitch_deg); }
  double droll_rad() const { return geo::DegToRad(droll_deg); }
  double turret_resolution_rad() const { return geo::DegToRad(turret_resolution_deg); }
  double turret_noise_rad() const { return geo::DegToRad(turret_noise_deg); }

  // Every number option, with the sensor and servo tables; not in it: the camera, the target model,
  // the marker hides, registered by the app.
  static const io::OptionTable<AttitudeSimOptions>& Table();
  // Table().Check, then the markers, finite values and the rules between options.
  bool Check(std::string* why) const;
  // The run report's "options": Table().ToJson plus the camera, the markers and the hides.
  io::Json ToJson() const;
};
io::Json AttitudeSimOptionsToJson(const AttitudeSimOptions& opt);

struct AttitudeFrameTruth {
  std::int64_t frame = 0;
  double t_s = 0.0;
  Eigen::Vector3d p_enu{0, 0, 0};                      // body origin (m)
  geo::EulerZyx attitude;
  Eigen::Matrix3d R_enu_body = Eigen::Matrix3d::Identity();
  geo::AzEl boresight;                                 // true (lag + jitter)
  std::vector<Eigen::Vector2d> marker_px;              // projected centre of each marker
  std::vector<double> marker_radius_px;
  std::vector<bool> visible;                           // not hidden
  double min_separation_px = 0.0;                      // closest pair of visible marker centres
};

struct AttitudeTurretSample {
  double t_s = 0.0;
  double true_az_rad = 0.0, true_el_rad = 0.0;
  double az_rad = 0.0, el_rad = 0.0;  // recorded (quantised); az in [0, 2π)
};

class AttitudeSimulator {
 public:
  // Throws UsageError if the options fail Check(), or if a marker disc leaves the image (or a
  // marker goes behind the camera) in some frame: the message names the frame.
  explicit AttitudeSimulator(AttitudeSimOptions opt);

  const AttitudeSimOptions& options() const { return opt_; }
  const std::vector<std::string>& marker_ids() const { return opt_.marker_ids; }
  std::size_t frame_count() const { return frames_.size(); }
  const AttitudeFrameTruth& frame(std::size_t k) const { return frames_.at(k); }
  const std::vector<AttitudeFrameTruth>& frames() const { return frames_; }

  // Body pose at any time (s).
  Eigen::Vector3d PositionEnu(double t_s) const;
  geo::EulerZyx Attitude(double t_s) const;

  cv::Mat RenderFrame(std::size_t k) const;        // CV_8UC1 / CV_16UC1, the frame's own noise
  cv::Mat RenderSignal(std::size_t k) const;       // noise-free CV_32FC1, DN above background (8-bit scale)
  std::vector<AttitudeTurretSample> TurretLog() const;

 private:
  double Progress(double t_s) const;  // u1 − u2 (attitude); position uses the two separately
  void Ramps(double t_s, double* u1, double* u2) const;

  AttitudeSimOptions opt_;
  Eigen::Vector3d p0_enu_{0, 0, 0}, dir_enu_{0, 0, 0};
  std::optional<TurretServo> servo_;
  std::vector<AttitudeFrameTruth> frames_;
};

}  // namespace rk::sim

// Synthetic station-calibration session with truth (rk-sim pointing; issue 17): a station whose turret has
// a known pointing model (SPEC.md §3.1), a camera with a known mount, focal-length error and latency;
// landmarks near the horizon and stars higher up; a turret that slews from target to target and dwells on
// each; the image points of every target in view in every frame.
//
// Targets. Landmarks at random azimuths, elevations [landmark_min_el, landmark_max_el], ranges
// 500–3000 m (station ENU, also written WGS-84 by the writer). Stars at random azimuths, elevations
// [star_min_el, star_max_el] at the epoch: their ICRS catalogue places are made by ERFA's inverse
// (target::StarFromObservedPlace) so they stand there; they then move with the sky.
// Turret. Visits the targets in azimuth order. Slew: both axes at slew_rate (deg/s) from the previous
// commanded angles (the longer axis sets the time, the shorter one moves proportionally), then a dwell of
// dwell_s on the command that puts the target at a random offset (≤ 40 % of the half field) from the
// image centre. Commanded encoder angles A(t), E(t) are continuous; the log (turret_rate_hz) holds them
// quantised to encoder_step_deg: a still turret logs one value for the whole dwell.
// Frames. At frame_rate_hz with stamps t_k; the mid-exposure time is t_k + time_offset_s (SPEC.md §3).
// Each target whose truth projection (SPEC.md §3.1 model, camera mount, focal × (1 + focal_error),
// distortion) is inside the image (10 px margin) gives an observation with Gaussian centroid noise.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "camera/camera_model.h"
#include "geo/pointing.h"
#include "io/options.h"
#include "target/calibration_targets.h"

namespace rk::sim {

struct PointingSimOptions {
  std::uint64_t seed = 1;
  int landmarks = 12;
  int stars = 24;
  double landmark_min_el_deg = 0.0, landmark_max_el_deg = 8.0;
  double star_min_el_deg = 12.0, star_max_el_deg = 75.0;
  double focal_length_mm = 100.0;     // nominal lens (the camera file handed to the calibration)
  double pixel_size_mm = 0.00345;
  int width_px = 2448, height_px = 2048;
  double encoder_step_deg = 0.003;
  double centroid_sigma_px = 0.05;
  double dwell_s = 2.0;
  double slew_rate_deg_s = 2.0;
  double frame_rate_hz = 10.0;
  double turret_rate_hz = 50.0;
  // Truth.
  double az_offset_deg = 137.25, tilt_north_deg = 0.021, tilt_east_deg = -0.013, el_axis_tilt_deg = 0.009;
  double mount_yaw_deg = 0.05, mount_pitch_deg = -0.03, mount_roll_deg = 0.12;
  double focal_error = 0.002;         // true focal = nominal × (1 + focal_error)
  double time_offset_s = 0.012;       // camera latency
  double lat_deg = 32.5, lon_deg = -106.6, h_m = 1300.0;
  std::string epoch_utc = "2026-03-20T03:00:00Z";
  double validation_s = 20.0;         // length of the tracked validation target (s); 0 = none

  static const io::OptionTable<PointingSimOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const;
};

struct PointingObservationRow {
  std::int64_t frame = 0;
  double t_s = 0.0;
  std::string id;
  Eigen::Vector2d px = Eigen::Vector2d::Zero();
  Eigen::Vector2d truth_px = Eigen::Vector2d::Zero();
};

// A tracked validation target after the session (same station, same errors): a target flying a straight
// line 3 km out, the turret following it, a beacon track with the same centroid noise. rk-locate
// --pointing on it must give the truth's az/el; without the pointing model it is off by the station errors.
struct ValidationTrack {
  std::vector<double> frame_t_s;
  std::vector<Eigen::Vector2d> px;                               // observed beacon pixel per frame
  std::vector<double> turret_t_s, turret_az_deg, turret_el_deg;  // logged turret
  std::vector<Eigen::Vector3d> p_enu;                            // true target position per frame (m)
  std::vector<double> true_t_s;  // mid-exposure time of each frame (stamp + the camera's time offset): p_enu's
};

struct PointingSession {
  target::Geodetic station;
  target::UtcJd epoch;
  camera::CameraModel camera_nominal;  // what the calibration starts from (no mount, nominal focal, τ 0)
  camera::CameraModel camera_truth;    // true mount, focal and time offset
  geo::PointingTerms truth;
  std::vector<target::Landmark> landmarks;
  std::vector<target::Star> stars;
  std::vector<double> turret_t_s, turret_az_deg, turret_el_deg;  // logged (quantised) turret
  std::vector<PointingObservationRow> observations;
  std::size_t frames = 0, dwells = 0;
  double duration_s = 0.0;
  ValidationTrack validation;
};

// Throws UsageError for options that fail Check().
PointingSession SimulatePointingSession(const PointingSimOptions& options);

}  // namespace rk::sim

// `rk-attitude oi` as a library call: target position and attitude in the station frame, per
// video frame, from image points of known target features, the attitude camera's model and
// the turret angles (seed 001 §2.3, Guan et al. 2014, with the exact geometry of SPEC.md §3).
//
// Per frame (one output row per frame of the points file, never dropped):
//   1. Usable points (x, y given; status ok/reacquired), at least min_points (≥ 4) of them,
//      else status `lost` (note few_points).
//   2. Boresight (A, E) at the frame time (track/boresight.h); none → `invalid` (note turret).
//   3. Pixels → undistorted normalised rays m = (x, y, 1) (camera::CameraModel::NormalisedRay,
//      the OpenCV distortion inverted exactly), pose R_cam_body, t_cam by pose::PnpSolver
//      (weak-perspective or homography start → orthogonal iteration → LM polish of the
//      reprojection error → second start for near-planar targets). Each point is weighted by
//      its sigma_px (points file) or the default sigma_px.
//   4. Checks, never trusting a solver flag: every point in front of the camera (else
//      `invalid`, behind_camera); RMS reprojection error through the full camera model
//      (distorted pixels) ≤ max_rms_px, else one point may be rejected (leave-one-out, with
//      ≥ min_points left, the fit with the smallest RMS) and the row keeps it in rejected_id;
//      still too large → `invalid` (reprojection). Degenerate geometry (collinear points,
//      singular information matrix) → `invalid` (degenerate).
//   5. Station frame. The camera rides on the turret (its centre at the rotation centre,
//      docs/conventions.md):  R_enu_cam = R_enu_turret(A, E) · R_turret_cam (mount),
//        p_enu = R_enu_cam · t_cam,   R_enu_body = R_enu_cam · R_cam_body,
//        R_ned_body = R_ned_enu · R_enu_body → yaw, pitch, roll (geo/body_attitude.h).
//   6. Two minima that the data cannot separate (pose/pnp.h: Δχ² < ambiguity_chi2) → the row is
//      flagged `ambiguous`; the primary is the minimum continuous with the previous row's
//      attitude (within continuity_s), else the lower χ²; the other goes in alt_*.
//   7. 1σ of e, n, u, yaw, pitch, roll: first-order propagation of the pose covariance
//      (JᵀWJ)⁻¹ of the LM polish (W = 1/σ² per point) and of the turret angle noise
//      (turret_sigma_deg on A and E) through step 5, by central differences. It does not
//      include camera calibration or target model errors.
// A frame is `reacquired` when it has a pose and the previous frame had none.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "camera/camera_model.h"
#include "geo/body_attitude.h"
#include "geo/line_of_sight.h"
#include "io/csv.h"
#include "io/row_status.h"
#include "io/run_summary.h"
#include "track/boresight.h"
#include "pose/image_points.h"
#include "geo/pointing.h"
#include "pose/pnp.h"

namespace rk::pose {

struct AttitudeOiOptions {
  PnpOptions pnp;
  // Boresight from the turret log (the caller builds the track::BoresightSource with these).
  track::InterpMethod turret_method = track::InterpMethod::kCubic;  // linear or cubic
  double turret_max_gap_s = 0.1;    // longest turret-log interval interpolated across (s), > 0
  double turret_sigma_deg = 0.003 / std::sqrt(12.0);  // 1σ of A and E (deg): 0.003° encoder step / √12, ≥ 0
  double sigma_px = 0.1;            // 1σ pixel noise of points without sigma_px (px), > 0
  int min_points = 4;               // fewest usable points for a pose, [4, 1000]
  double max_rms_px = 1.0;          // largest accepted RMS reprojection error (px), > 0
  bool no_reject = false;           // never leave one point out when the RMS is too large
  double continuity_s = 1.0;        // ambiguous frames follow the previous pose if within this time (s), ≥ 0
  bool pure_oi = false;             // orthogonal iteration only: pnp.polish is turned off
  // Not in the table: the turret pointing model of SPEC.md §3.1 (rk-attitude oi --pointing), applied
  // exactly through camera::ApplyPointing (camera/station_view.h); all zero = a perfect turret.
  geo::PointingTerms pointing;

  // The command-line options of rk-attitude oi, the solver's among them (io/options.h).
  static const io::OptionTable<AttitudeOiOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
};

enum class PoseNote { kNone, kFewPoints, kTurret, kDegenerate, kBehindCamera, kReprojection };
const char* PoseNoteName(PoseNote note);  // "", few_points, turret, degenerate, behind_camera, reprojection

struct PoseRow {
  std::optional<std::int64_t> frame;
  double t_s = 0.0;
  RowStatus status = RowStatus::kLost;
  PoseNote note = PoseNote::kNone;
  int points_used = 0;
  bool has_pose = false;
  Eigen::Vector3d p_enu_m = Eigen::Vector3d::Zero();  // body origin, station ENU (m)
  geo::EulerZyx attitude;
  Eigen::Matrix3d R_enu_body = Eigen::Matrix3d::Identity();
  double rms_px = 0.0, max_px = 0.0;                   // reprojection residuals (distorted pixels)
  double chi2 = 0.0;                                   // σ-weighted
  int dof = 0;                                         // 2n − 6
  bool ambiguous = false;
  bool has_alt = false;                                // alt_attitude valid (ambiguous rows)
  geo::EulerZyx alt_attitude;
  std::optional<std::string> rejected_id;
  Eigen::Matrix<double, 6, 1> sigma = Eigen::Matrix<double, 6, 1>::Zero();  // e,n,u (m), yaw,pitch,roll (rad)
  std::optional<geo::AzEl> boresight;
  int oi_iterations = 0;
};

struct AttitudeOiResult {
  std::vector<PoseRow> rows;
  bool has_frame = false;
  std::array<std::size_t, 5> rows_by_status{};  // indexed by RowStatus
  std::size_t few_points = 0, turret_not_covered = 0, degenerate = 0, behind_camera = 0, reprojection = 0;
  std::size_t outliers_rejected = 0, ambiguous = 0, second_starts = 0, turret_duplicate_times = 0;
  double chi2_sum = 0.0;   // over rows with a pose
  double dof_sum = 0.0;
  // Mean χ²/dof over the rows with a pose (≈ 1 when sigma_px is right; NaN if none).
  double MeanChi2PerDof() const;
  // The report's "summary" (docs/rk-attitude.md "Report"): the headline figures rk-run copies.
  nlohmann::json SummaryJson() const;
  // The run's summary (io/run_summary.h): rows by status, the warnings rk-attitude oi prints (turret log not
  // covering frame times, unless the boresight is fixed; ambiguous poses; chi-square per dof above 4), outliers
  // rejected (report only), poses as headline, and the report keys counts, mean_chi2_per_dof and summary.
  io::RunSummary Summary(const std::string& turret_source, bool boresight_fixed, std::size_t unusable_point_rows) const;
};

// Throws DataError naming file:line:col for a pixel outside the camera's image, and naming the
// turret log if it covers no frame time; ProcessingError if no frame gets a pose; UsageError
// for bad options.
AttitudeOiResult RunAttitudeOi(const ImagePoints& points, const target::FeatureModel& model,
                               const camera::CameraModel& camera, const track::BoresightSource& boresight,
                               const AttitudeOiOptions& options);

// Pose CSV (SPEC.md §2.1 `t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,status` + reproj_rms_px)
// with extra columns: frame (first, if the points had it), reproj_max_px, points_used,
// ambiguous (0/1), alt_yaw_deg, alt_pitch_deg, alt_roll_deg, sigma_e_m, sigma_n_m, sigma_u_m,
// sigma_yaw_deg, sigma_pitch_deg, sigma_roll_deg, rejected_id, note, boresight_az_deg,
// boresight_el_deg.
io::CsvWriter PoseCsv(const AttitudeOiResult& result);

// The station-frame pose of a camera-frame pose for boresight (A, E): p_enu and R_enu_body.
void StationPose(const camera::CameraModel& camera, const geo::AzEl& boresight, const Eigen::Matrix3d& R_cam_body,
                 const Eigen::Vector3d& t_cam, Eigen::Vector3d* p_enu, Eigen::Matrix3d* R_enu_body);

}  // namespace rk::pose

// `rk-attitude cylinder` as a library call: image points (nose, tail1, tail2 per frame) + theodolite log +
// camera model + cylinder model → axis attitude per frame (SPEC.md §1.1, §2.1, §3; seed 004).
//
// Per frame:
//   1. The three points of the frame (image points file `frame,t_s,id,x_px,y_px`, long format; rows of a
//      frame together; ids nose, tail1, tail2 only). A missing point, an empty coordinate or a point row
//      whose `status` is lost/invalid → row status `lost`, solution `missing_points`.
//   2. Theodolite boresight A, E at the frame time: the log interpolated (cubic, azimuth on its unwrapped
//      sequence, wrap-safe), no extrapolation, no interpolation across a gap longer than
//      theodolite_max_gap_s → `invalid`, solution `no_theodolite`. (Same reader and interpolation as
//      rk-locate.)
//   3. Lines of sight by SPEC.md §3's exact geometry (camera::CameraModel::RayEnu: undistortion, mount,
//      R_enu_turret(A, E)); never the paper's small-angle eq. 3.
//   4. Checks: a point outside the image → `outside_image`; tail1 = tail2 → `degenerate`; the nose image
//      inside the tail-rim image (angle nose–tail centre ≤ half the angle tail1–tail2: the axis within
//      atan(d/2l) of the line of sight, the nose hidden behind the tail) → `tail_chase`, attitude = the line
//      of sight to the tail centre (seed 004 §3: "the attitude is the theodolite pointing"); the nose not
//      equidistant from the tail points (|∠(nose,tail1) − ∠(nose,tail2)| · f above both max_asymmetry_px and a
//      quarter of the tail diameter's image; zero for a true cylinder) → `inconsistent` (mislabelled or bad
//      points).
//   5. All admissible solutions (cylinder_solve.h). None → `no_solution`; only a near miss → `near_miss`.
//   6. Primary (SPEC.md §3): the solution continuous with the previous rows — nearest to the axis predicted
//      by a straight-line least-squares fit of the axis over the last (up to five) accepted rows not older
//      than continuity_gap_s (the last row itself when there is only one) —
//      and, with no such history, the nose-nearer one. Solution status: `unique` (one solution),
//      `continuity` (two, chosen by history), `ambiguous` (two more than ambiguity_deg apart that history
//      cannot tell apart: none, or both within ambiguity_deg of the prediction — primary by the SPEC rule,
//      the other in alt_*), `side_on` (two within ambiguity_deg of each other: the view is nearly
//      perpendicular to the axis, the double root of the problem, where precision is poorest).
//   5b. Optional image fit (with the frames: rk-attitude cylinder --video): the solutions are refined by
//      fitting the projected target to the frame itself (cylinder_image_fit.h) before step 6 chooses between
//      them (near the side-on double root the frame has two minima of equal cost close to the two three-point
//      solutions: the image cannot tell them apart either). Both are fitted only when history cannot tell them
//      apart (step 6 would say ambiguous or side_on) or they are within fit_both_within_deg of each other; else
//      only the one continuity chooses, and alt_* keep the other's three-point values. After the first converged fit each fit starts from the
//      previous one's nuisance parameters and noise model (CylinderImageFitStart), and a fit of the solution
//      continuity chose starts from the axis the history predicts (within 2° of its three-point axis). With fit_time_limit_s,
//      rows after that much fitting time are not fitted. yaw, pitch, alt_*, the ranges and
//      the σ columns are then the fit's (σ from its covariance); `fit` says converged / not_converged /
//      failed (failed: that solution keeps its three-point values).
//   8. Quality: σ of yaw and pitch from pixel_sigma_px on each coordinate and angle_sigma_arcsec on A and E,
//      by the autodiff Jacobian (cylinder_budget.h); empty at a double root (infinite). Also the angle
//      between the two solutions (separation_deg), the asymmetry (px) and the edge tilt of the primary.
// Row status (SPEC.md §2): `ok` with values for unique/continuity/ambiguous/side_on/near_miss/tail_chase
// (`reacquired`/`predicted` carried from the points file); `lost` for missing_points; `invalid` with empty
// values for the other failures. Rows are never dropped: one output row per frame.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "attitude/cylinder_geometry.h"
#include "attitude/cylinder_image_fit.h"
#include "attitude/cylinder_solve.h"
#include "camera/camera_model.h"
#include "geo/pointing.h"
#include "io/csv.h"
#include "io/json_util.h"
#include "io/row_status.h"
#include "formats/turret_log.h"
#include "io/run_summary.h"
#include "track/interp.h"

namespace rk::attitude {

enum class CylinderSolutionStatus {
  kUnique,
  kContinuity,
  kAmbiguous,
  kSideOn,
  kNearMiss,
  kTailChase,
  kMissingPoints,
  kOutsideImage,
  kNoTheodolite,
  kDegenerate,
  kInconsistent,
  kNoSolution,
};
inline constexpr int kCylinderSolutionStatusCount = 12;
const char* CylinderSolutionStatusName(CylinderSolutionStatus s);

// The three silhouette points of one frame (pixels), from the image points file.
struct CylinderFramePoints {
  std::optional<std::int64_t> frame;
  double t_s = 0.0;
  std::size_t line = 0;                              // first line of the frame in the file
  std::array<std::optional<Eigen::Vector2d>, 3> px;  // nose, tail1, tail2
  RowStatus status = RowStatus::kOk;                 // worst status of the point rows (predicted, reacquired)
};

struct CylinderPointsFile {
  std::string source;
  bool has_frame = false;
  std::vector<CylinderFramePoints> frames;
};

// Reads `frame,t_s,id,x_px,y_px[,status]` (long format). Rows are grouped by `frame` (or, without the column,
// by equal consecutive t_s). DataError (file:line:col) for: an id other than nose/tail1/tail2, an id twice in
// a frame, a frame whose rows are not together or disagree on t_s, time going backwards, bad numbers.
CylinderPointsFile ReadCylinderPoints(const io::CsvTable& table);
// The cells ReadCylinderPoints needs of every row (for io::CsvReadOptions::rule, --bad-rows skip).
io::CsvRowRule CylinderPointsRowRule();

struct CylinderRunOptions {
  CylinderSolveOptions solve;
  double max_miss_px = 1.0;                 // near-miss acceptance (px), >= 0 (0 = exact roots only)
  track::InterpMethod theodolite_method = track::InterpMethod::kCubic;
  double theodolite_max_gap_s = 0.2;        // > 0
  double continuity_gap_s = 1.0;            // history older than this is not used, > 0
  double ambiguity_deg = 1.0;               // > 0
  double max_asymmetry_px = 3.0;            // > 0; the limit is max(this, diameter image / 4)
  double pixel_sigma_px = 0.3;              // for the σ columns, >= 0
  double angle_sigma_arcsec = 0.0;          // for the σ columns, >= 0
  CylinderImageFitOptions image_fit;        // used when frames are given
  // Image fit: total fitting time (s) after which the remaining rows keep their three-point solution (fit
  // column empty, counted in the summary); 0 = no limit, >= 0. Depends on the machine's speed.
  double fit_time_limit_s = 0.0;
  // Image fit: both solutions are fitted when they are closer than this (deg; near side-on the frame's two
  // minima are a few degrees apart and a start from one solution can lie in the other's basin), as when history
  // cannot choose; otherwise only the one continuity chooses. > 0.
  double fit_both_within_deg = 10.0;
  // Not in the table: the theodolite/turret pointing model of SPEC.md §3.1 (rk-attitude cylinder --pointing),
  // applied exactly through camera::ApplyPointing (camera/station_view.h); all zero = a perfect instrument.
  geo::PointingTerms pointing;
  // The command-line options of rk-attitude cylinder, solve's and image_fit's among them (io/options.h).
  static const io::OptionTable<CylinderRunOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
};

struct CylinderRow {
  std::optional<std::int64_t> frame;
  double t_s = 0.0;
  RowStatus status = RowStatus::kLost;
  CylinderSolutionStatus solution = CylinderSolutionStatus::kMissingPoints;
  std::optional<double> yaw_rad, pitch_rad, alt_yaw_rad, alt_pitch_rad;
  std::optional<Eigen::Vector3d> range_m;  // nose, tail1, tail2
  std::optional<double> sigma_yaw_rad, sigma_pitch_rad;
  std::optional<double> separation_rad, asymmetry_px, edge_tilt_rad;
  std::optional<double> boresight_az_rad, boresight_el_rad;
  std::optional<Eigen::Vector3d> axis_enu;  // primary axis (for continuity)
  // Image fit (when frames are given and the row has a three-point solution).
  std::optional<CylinderImageFitStatus> fit;
  std::optional<double> fit_rms_dn, fit_psf_px, fit_cone_m;
  std::optional<int> fit_iterations;
};

struct CylinderRunResult {
  std::vector<CylinderRow> rows;
  bool has_frame = false;
  std::array<std::size_t, 5> rows_by_status{};                                   // by RowStatus
  std::array<std::size_t, kCylinderSolutionStatusCount> rows_by_solution{};      // by CylinderSolutionStatus
  std::size_t theodolite_duplicate_times = 0;
  long solver_evaluations = 0;
  bool image_fit = false;
  std::array<std::size_t, 3> rows_by_fit{};  // by CylinderImageFitStatus
  std::size_t rows_fit_time_limit = 0;       // rows not fitted: fit_time_limit_s was spent
  std::size_t fits = 0, fits_warm = 0;       // fits run, of which from the previous frame's start
  long fit_evaluations = 0;
  double fit_seconds = 0.0;
  io::Json SummaryJson() const;
  // The run's summary (io/run_summary.h): rows by status, the warnings rk-attitude cylinder prints (ambiguous,
  // invalid frames by cause), termination "time limit" when the image fit ran out of fit_time_limit_s, the
  // fraction of rows ok, and the report's "summary".
  io::RunSummary Summary() const;
};

// The frame numbered `frame` (SPEC.md: counting from 0 across video segments) for the image fit, CV_8UC1 or
// CV_16UC1 of the camera's size; throws DataError naming the video if it cannot supply it.
using CylinderFrameReader = std::function<const cv::Mat&(std::int64_t frame)>;

// Throws DataError naming the theodolite log if it covers no frame time, ProcessingError if no frame has
// the three points, UsageError if the options fail Check() or frames are given for a points file without
// the `frame` column.
CylinderRunResult RunCylinder(const CylinderPointsFile& points, formats::TurretLog theodolite,
                              const camera::CameraModel& camera, const target::CylinderShape& target,
                              const CylinderRunOptions& options, const CylinderFrameReader* frames = nullptr);

// Axis attitude CSV (SPEC.md §2.1 + extras):
//   [frame,]t_s,yaw_deg,pitch_deg,status,alt_yaw_deg,alt_pitch_deg,solution,range_nose_m,range_tail1_m,
//   range_tail2_m,sigma_yaw_deg,sigma_pitch_deg,separation_deg,asymmetry_px,edge_tilt_deg,
//   boresight_az_deg,boresight_el_deg[,fit,fit_rms_dn,fit_psf_px,fit_cone_m,fit_iterations (image fit)]
io::CsvWriter CylinderCsv(const CylinderRunResult& result);

}  // namespace rk::attitude

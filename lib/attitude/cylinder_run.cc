// rk-attitude cylinder pipeline; method in cylinder_run.h.
#include "attitude/cylinder_run.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "attitude/cylinder_budget.h"
#include "formats/image_points.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"
#include "track/boresight.h"
#include "camera/station_view.h"

namespace rk::attitude {

const char* CylinderSolutionStatusName(CylinderSolutionStatus s) {
  switch (s) {
    case CylinderSolutionStatus::kUnique:
      return "unique";
    case CylinderSolutionStatus::kContinuity:
      return "continuity";
    case CylinderSolutionStatus::kAmbiguous:
      return "ambiguous";
    case CylinderSolutionStatus::kSideOn:
      return "side_on";
    case CylinderSolutionStatus::kNearMiss:
      return "near_miss";
    case CylinderSolutionStatus::kTailChase:
      return "tail_chase";
    case CylinderSolutionStatus::kMissingPoints:
      return "missing_points";
    case CylinderSolutionStatus::kOutsideImage:
      return "outside_image";
    case CylinderSolutionStatus::kNoTheodolite:
      return "no_theodolite";
    case CylinderSolutionStatus::kDegenerate:
      return "degenerate";
    case CylinderSolutionStatus::kInconsistent:
      return "inconsistent";
    case CylinderSolutionStatus::kNoSolution:
      return "no_solution";
  }
  return "?";
}

const io::OptionTable<CylinderRunOptions>& CylinderRunOptions::Table() {
  using B = io::Bounds;
  using O = CylinderRunOptions;
  using track::InterpMethod;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Sub(&O::solve, CylinderSolveOptions::Table())
          .Choice("--theodolite-interp", &O::theodolite_method, {InterpMethod::kLinear, InterpMethod::kCubic},
                  track::InterpMethodName, "Theodolite interpolation: linear or cubic")
          .Real("--theodolite-max-gap", &O::theodolite_max_gap_s, "s", B::Positive(),
                "Longest theodolite-log interval (s) interpolated across; frames in longer gaps are invalid")
          .Real("--continuity-gap", &O::continuity_gap_s, "s", B::Positive(),
                "History older than this (s) is not used to choose between the two solutions")
          .Real("--ambiguity-deg", &O::ambiguity_deg, "deg", B::Positive().Finite(),
                "Solutions (or their distances to the predicted axis) closer than this are not told apart (deg)")
          .Real("--max-asymmetry-px", &O::max_asymmetry_px, "px", B::Positive(),
                "Largest difference of the nose's distances to tail1 and tail2 (px; at least a quarter of the tail "
                "diameter's image) before a frame is inconsistent")
          .Real("--max-miss-px", &O::max_miss_px, "px", B::AtLeast(0).Finite(),
                "Where noise removes the exact solutions, accept the closest approach if it misses by at most this "
                "(px); 0 = never")
          .Real("--max-edge-tilt-deg", [](O& o) -> double& { return o.solve.max_edge_tilt_deg; }, "deg",
                B::LeftOpen(0, 90),
                "Solutions tilting the tail diameter further out of the image plane are not admissible (deg)")
          .Sub(&O::image_fit, CylinderImageFitOptions::Table())
          .Real("--fit-both-within-deg", &O::fit_both_within_deg, "deg", B::Positive().Finite(),
                "Image fit: both solutions are fitted when history cannot choose or they are closer than this "
                "(deg; near side-on one start can lie in the other's basin); else only the chosen one")
          .Real("--fit-time-limit", &O::fit_time_limit_s, "s", B::AtLeast(0).Finite(),
                "Image fit: after this much fitting time (s) in all, the remaining frames keep the three-point "
                "solution (fit column empty); 0 = no limit")
          .Real("--pixel-sigma", &O::pixel_sigma_px, "px", B::AtLeast(0).Finite(),
                "Point error assumed for the sigma columns (px, each coordinate)")
          .Real("--angle-sigma-arcsec", &O::angle_sigma_arcsec, "arcsec", B::AtLeast(0).Finite(),
                "Theodolite angle error assumed for the sigma columns (arcsec, each axis)");
  return table;
}

bool CylinderRunOptions::Check(std::string* why) const {
  return Table().Check(*this, why) && solve.Check(why) && image_fit.Check(why);
}

namespace {

int PointIndex(std::string_view id) {
  if (id == "nose") return 0;
  if (id == "tail1") return 1;
  if (id == "tail2") return 2;
  return -1;
}

}  // namespace

CylinderPointsFile ReadCylinderPoints(const io::CsvTable& table) {
  const formats::ImagePoints file = formats::ReadImagePoints(table);
  CylinderPointsFile out;
  out.source = file.source;
  out.has_frame = file.has_frame;
  out.frames.reserve(file.frames.size());
  for (const formats::ImagePointFrame& in : file.frames) {
    CylinderFramePoints f;
    f.frame = in.frame;
    f.t_s = in.t_s;
    f.line = in.line;
    for (const formats::ImagePoint& p : in.points) {
      const int k = PointIndex(p.id);
      if (k < 0) {
        throw DataError(file.source, p.line, p.col_id,
                        "unknown point id '" + p.id + "': the cylinder model has the points nose, tail1, tail2");
      }
      // A predicted point is used, and the row says so (image_points.h); lost and invalid rows have none.
      const bool usable = p.measured() || (p.px && p.status == RowStatus::kPredicted);
      if (!usable) continue;
      f.px[static_cast<std::size_t>(k)] = *p.px;
      if (p.status == RowStatus::kPredicted || (p.status == RowStatus::kReacquired && f.status == RowStatus::kOk)) {
        f.status = p.status;
      }
    }
    out.frames.push_back(std::move(f));
  }
  return out;
}

io::RunSummary CylinderRunResult::Summary() const {
  io::RunSummary out;
  for (std::size_t s = 0; s < rows_by_status.size(); ++s) out.CountRows(static_cast<RowStatus>(s), rows_by_status[s]);
  using S = CylinderSolutionStatus;
  const auto n = [&](S s) { return std::to_string(rows_by_solution[static_cast<std::size_t>(s)]); };
  if (rows_by_solution[static_cast<std::size_t>(S::kAmbiguous)] > 0) {
    out.Warn("ambiguous", n(S::kAmbiguous) +
                              " frame(s) ambiguous: two solutions that no history separates; primary = nose-nearer "
                              "(SPEC.md 3), the other in alt_yaw_deg/alt_pitch_deg");
  }
  const std::size_t invalid = rows_by_status[static_cast<std::size_t>(RowStatus::kInvalid)];
  if (invalid > 0) {
    out.Warn("rows_invalid", std::to_string(invalid) + " frame(s) invalid (no_theodolite " + n(S::kNoTheodolite) +
                                 ", outside_image " + n(S::kOutsideImage) + ", inconsistent " + n(S::kInconsistent) +
                                 ", degenerate " + n(S::kDegenerate) + ", no_solution " + n(S::kNoSolution) + ")");
  }
  if (rows_fit_time_limit > 0) out.termination = "time limit";
  if (!rows.empty()) {
    const std::size_t ok = rows_by_status[static_cast<std::size_t>(RowStatus::kOk)];
    out.AddFigure("attitude ok", static_cast<double>(ok) / static_cast<double>(rows.size()), "fraction",
                  std::to_string(rows.size()) + " rows");
  }
  out.details["summary"] = SummaryJson();
  return out;
}

io::Json CylinderRunResult::SummaryJson() const {
  io::Json by_status = io::Json::object();
  for (int s = 0; s < 5; ++s)
    by_status[RowStatusName(static_cast<RowStatus>(s))] = rows_by_status[static_cast<std::size_t>(s)];
  io::Json by_solution = io::Json::object();
  for (int s = 0; s < kCylinderSolutionStatusCount; ++s)
    by_solution[CylinderSolutionStatusName(static_cast<CylinderSolutionStatus>(s))] =
        rows_by_solution[static_cast<std::size_t>(s)];
  io::Json j = {{"rows", rows.size()},
                {"status_counts", by_status},
                {"solution_counts", by_solution},
                {"theodolite_duplicate_times", theodolite_duplicate_times},
                {"solver_evaluations", solver_evaluations}};
  if (image_fit) {
    io::Json by_fit = io::Json::object();
    for (int s = 0; s < 3; ++s)
      by_fit[CylinderImageFitStatusName(static_cast<CylinderImageFitStatus>(s))] = rows_by_fit[static_cast<std::size_t>(s)];
    j["image_fit"] = {{"fit_counts", by_fit},
                      {"rows_not_fitted_time_limit", rows_fit_time_limit},
                      {"fits", fits},
                      {"fits_warm_start", fits_warm},
                      {"model_evaluations", fit_evaluations},
                      {"seconds", fit_seconds}};
  }
  return j;
}

namespace {

// The axes of the last accepted rows and the axis they predict for the next row (continuity).
class AxisHistory {
 public:
  void Add(double t_s, const Eigen::Vector3d& axis) {
    entries_.push_back({t_s, axis});
    if (entries_.size() > kHistory) entries_.erase(entries_.begin());
  }

  // The axis predicted at t_s from the rows within `gap_s` of the last one (older history is
  // forgotten): none without history, the last axis after one row, else a straight-line fit.
  std::optional<Eigen::Vector3d> Predict(double t_s, double gap_s) {
    while (!entries_.empty() && t_s - entries_.back().t_s > gap_s) entries_.clear();
    if (entries_.size() == 1) return entries_.back().axis;
    if (entries_.size() < 2) return std::nullopt;
    // Straight-line least-squares fit of the axis components over the history (up to kHistory rows), so
    // that one noisy row does not throw the prediction (two-point extrapolation doubles the noise).
    const double t_ref = entries_.back().t_s;
    double sw = 0, st = 0, stt = 0;
    Eigen::Vector3d sa = Eigen::Vector3d::Zero(), sta = Eigen::Vector3d::Zero();
    for (const Entry& h : entries_) {
      const double t = h.t_s - t_ref;
      sw += 1;
      st += t;
      stt += t * t;
      sa += h.axis;
      sta += t * h.axis;
    }
    const double det = sw * stt - st * st;
    if (det > 1e-12 * std::max(1.0, stt * sw)) {
      const Eigen::Vector3d slope = (sw * sta - st * sa) / det;
      const Eigen::Vector3d icept = (sa - slope * st) / sw;
      return (icept + slope * (t_s - t_ref)).normalized();
    }
    return (sa / sw).normalized();
  }

 private:
  static constexpr std::size_t kHistory = 5;  // accepted rows kept
  struct Entry {
    double t_s;
    Eigen::Vector3d axis;
  };
  std::vector<Entry> entries_;
};

// What became of a row.
struct RowOutcome {
  RowStatus status;
  CylinderSolutionStatus solution;
};

// True when a point lies outside the image.
bool OutsideImage(const CylinderFramePoints& f, const camera::CameraModel& cam) {
  bool outside = false;
  for (const auto& p : f.px) {
    outside = outside || p->x() < -0.5 || p->y() < -0.5 || p->x() > cam.width_px - 0.5 || p->y() > cam.height_px - 0.5;
  }
  return outside;
}

// The image fit of the solution continuity chose starts from the predicted axis when that is within this of
// the solution's three-point axis (the same branch; the three points' error is ≲ 0.5° at ≥ 100 px).
constexpr double kStartFromHistoryRad = geo::DegToRad(2.0);

// Solves the rows of one run in time order (the choice between two solutions uses the rows before).
class CylinderRowSolver {
 public:
  CylinderRowSolver(const camera::CameraModel& cam, const target::CylinderShape& target, const CylinderRunOptions& options,
                    const CylinderFrameReader* frames, CylinderRunResult* result)
      : cam_(cam), target_(target), options_(options), frames_(frames), result_(result), solve_(options.solve) {
    solve_.max_miss_rad = options.max_miss_px / cam.fx();
    tau_ = geo::DegToRad(options.ambiguity_deg);
    px_var_ = options.pixel_sigma_px * options.pixel_sigma_px;
    const double ang = options.angle_sigma_arcsec / geo::kArcsecPerRad;
    ang_var_ = ang * ang;
  }

  // The camera's mount in the current row's view (pointing model, camera/station_view.h).
  void SetView(const camera::StationView& view) {
    cam_.mount_yaw_rad = view.mount_yaw_rad;
    cam_.mount_pitch_rad = view.mount_pitch_rad;
    cam_.mount_roll_rad = view.mount_roll_rad;
  }

  // A row with its three points in the image and a theodolite boresight (of the row's view).
  RowOutcome Solve(const CylinderFramePoints& f, const geo::AzEl& boresight, CylinderRow* row) {
    const RowStatus ok_status = f.status;  // ok, or predicted / reacquired from the points file
    CylinderInputs x;
    x << boresight.az_rad, boresight.el_rad, f.px[0]->x(), f.px[0]->y(), f.px[1]->x(), f.px[1]->y(), f.px[2]->x(), f.px[2]->y(),
        target_.length_m, target_.diameter_m;
    const CylinderRays rays = RaysFromInputs(cam_, x);
    const double bc = AxisAngle(rays.tail1, rays.tail2);
    if (!(bc > 0.0) || (*f.px[1] - *f.px[2]).norm() < 1e-9) return {RowStatus::kInvalid, CylinderSolutionStatus::kDegenerate};
    const Eigen::Vector3d mid = (rays.tail1 + rays.tail2).normalized();
    if (AxisAngle(rays.nose, mid) <= 0.5 * bc) {
      TailChase(row->t_s, mid, row);
      return {ok_status, CylinderSolutionStatus::kTailChase};
    }
    row->asymmetry_px = std::abs(AxisAngle(rays.nose, rays.tail1) - AxisAngle(rays.nose, rays.tail2)) * cam_.fx();
    // Inconsistent: beyond the absolute limit and beyond a quarter of the tail diameter's image (a mislabelled
    // or foreign point is off by about the diameter or more; reading noise by much less).
    if (*row->asymmetry_px > std::max(options_.max_asymmetry_px, 0.25 * bc * cam_.fx())) {
      return {RowStatus::kInvalid, CylinderSolutionStatus::kInconsistent};
    }
    std::vector<CylinderSolution> sols = Candidates(rays);
    if (sols.empty()) return {RowStatus::kInvalid, CylinderSolutionStatus::kNoSolution};
    const std::vector<std::optional<CylinderImageFitResult>> fits = FitImage(f, boresight, &sols);
    std::size_t primary = 0;
    CylinderSolutionStatus sol_status = Choose(sols, history_.Predict(row->t_s, options_.continuity_gap_s), row, &primary);
    const CylinderSolution& p = sols[primary];
    if (!p.exact) sol_status = CylinderSolutionStatus::kNearMiss;
    row->yaw_rad = p.yaw_rad;
    row->pitch_rad = p.pitch_rad;
    row->range_m = p.range_m;
    row->edge_tilt_rad = p.edge_tilt_rad;
    row->axis_enu = p.axis_enu;
    SetSigmaAndFit(x, p, fits[primary], row);
    if (row->fit) ++result_->rows_by_fit[static_cast<std::size_t>(*row->fit)];
    history_.Add(row->t_s, *row->axis_enu);
    return {ok_status, sol_status};
  }

 private:
  // Tail chase: the nose image lies within the tail rim's; the axis is along the line of sight.
  void TailChase(double t_s, const Eigen::Vector3d& mid, CylinderRow* row) {
    const geo::AzEl los = geo::AzElFromEnu(mid);
    row->yaw_rad = los.az_rad;
    row->pitch_rad = los.el_rad;
    row->axis_enu = mid;
    const double bound = std::atan2(0.5 * target_.diameter_m, target_.length_m);
    row->sigma_yaw_rad = bound / std::max(std::cos(los.el_rad), 1e-9);
    row->sigma_pitch_rad = bound;
    history_.Add(t_s, mid);
  }

  // The three-point solutions, at most two: the two most nearly edge-on, in nose-range order.
  std::vector<CylinderSolution> Candidates(const CylinderRays& rays) {
    const CylinderSolveResult sr = SolveCylinder(rays, target_, solve_);
    result_->solver_evaluations += sr.function_evaluations;
    std::vector<CylinderSolution> sols = sr.solutions;
    if (sols.size() > 2) {
      std::sort(sols.begin(), sols.end(),
                [](const CylinderSolution& p, const CylinderSolution& q) { return p.edge_tilt_rad < q.edge_tilt_rad; });
      sols.resize(2);
      std::sort(sols.begin(), sols.end(),
                [](const CylinderSolution& p, const CylinderSolution& q) { return p.range_m(0) < q.range_m(0); });
    }
    return sols;
  }

  // Image fit of each solution (near the side-on double root the frame has two minima close to the two
  // three-point solutions, of equal cost: each is refined, and continuity chooses as without the fit).
  // A fit that did not fail replaces its solution.
  std::vector<std::optional<CylinderImageFitResult>> FitImage(const CylinderFramePoints& f, const geo::AzEl& boresight,
                                                              std::vector<CylinderSolution>* sols) {
    std::vector<std::optional<CylinderImageFitResult>> fits(sols->size());
    if (!frames_ || !f.frame) return fits;
    if (options_.fit_time_limit_s > 0.0 && result_->fit_seconds >= options_.fit_time_limit_s) {
      ++result_->rows_fit_time_limit;
      return fits;
    }
    const cv::Mat& image = (*frames_)(*f.frame);
    const std::optional<std::size_t> only = ClearChoice(*sols, f.t_s);
    for (std::size_t k = 0; k < sols->size(); ++k) {
      if (only && k != *only) continue;
      CylinderSolution& c = (*sols)[k];
      // The chosen solution's fit starts from the axis the fitted history predicts (closer than the three
      // points' by their noise), the position from the three points.
      geo::AzEl start{c.yaw_rad, c.pitch_rad};
      const std::optional<Eigen::Vector3d> predicted = history_.Predict(f.t_s, options_.continuity_gap_s);
      if (only && predicted && AxisAngle(*predicted, c.axis_enu) < kStartFromHistoryRad) {
        start = geo::AzElFromEnu(*predicted);
      }
      const auto t0 = std::chrono::steady_clock::now();
      const CylinderImageFitResult g =
          FitCylinderImage(image, cam_, boresight.az_rad, boresight.el_rad, target_, c.tail_centre_enu, start.az_rad,
                           start.el_rad, options_.image_fit, warm_ ? &*warm_ : nullptr);
      result_->fit_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      result_->fit_evaluations += g.evaluations;
      ++result_->fits;
      if (warm_) ++result_->fits_warm;
      fits[k] = g;
      // The next fit starts from this one when it converged; a fit that did not starts the next one cold.
      warm_.reset();
      if (g.status == CylinderImageFitStatus::kConverged) warm_ = g.NextStart();
      if (g.status == CylinderImageFitStatus::kFailed) continue;
      c.yaw_rad = g.yaw_rad;
      c.pitch_rad = g.pitch_rad;
      c.axis_enu = g.axis_enu;
      c.tail_centre_enu = g.tail_centre_enu;
      c.nose_enu = g.tail_centre_enu + target_.length_m * g.axis_enu;
      const Eigen::Vector3d n = g.axis_enu.cross(g.tail_centre_enu).normalized();
      c.range_m = Eigen::Vector3d(c.nose_enu.norm(), (g.tail_centre_enu + 0.5 * target_.diameter_m * n).norm(),
                                  (g.tail_centre_enu - 0.5 * target_.diameter_m * n).norm());
    }
    return fits;
  }

  // The solution continuity chooses without doubt (two solutions further apart than fit_both_within_deg and
  // ambiguity_deg, their distances to the predicted axis further apart than ambiguity_deg): then only it is
  // fitted. None when history cannot choose (no
  // history, ambiguous, side-on) or there is one solution (fitted anyway).
  std::optional<std::size_t> ClearChoice(const std::vector<CylinderSolution>& sols, double t_s) {
    if (sols.size() != 2) return std::nullopt;
    const std::optional<Eigen::Vector3d> predicted = history_.Predict(t_s, options_.continuity_gap_s);
    const double both_within = std::max(tau_, geo::DegToRad(options_.fit_both_within_deg));
    if (!predicted || AxisAngle(sols[0].axis_enu, sols[1].axis_enu) < both_within) return std::nullopt;
    const double d0 = AxisAngle(sols[0].axis_enu, *predicted), d1 = AxisAngle(sols[1].axis_enu, *predicted);
    if (std::abs(d0 - d1) < tau_) return std::nullopt;
    return d1 < d0 ? std::size_t{1} : std::size_t{0};
  }

  // The primary of one or two solutions, by continuity with the predicted axis (SPEC.md §3), and the
  // alternative's angles in the row.
  CylinderSolutionStatus Choose(const std::vector<CylinderSolution>& sols, const std::optional<Eigen::Vector3d>& predicted,
                                CylinderRow* row, std::size_t* primary) const {
    *primary = 0;
    if (sols.size() != 2) return CylinderSolutionStatus::kUnique;
    CylinderSolutionStatus sol_status;
    const double sep = AxisAngle(sols[0].axis_enu, sols[1].axis_enu);
    row->separation_rad = sep;
    if (predicted) {
      const double d0 = AxisAngle(sols[0].axis_enu, *predicted), d1 = AxisAngle(sols[1].axis_enu, *predicted);
      *primary = d1 < d0 ? 1 : 0;
      if (sep < tau_) {
        sol_status = CylinderSolutionStatus::kSideOn;
      } else if (std::abs(d0 - d1) < tau_) {
        sol_status = CylinderSolutionStatus::kAmbiguous;
      } else {
        sol_status = CylinderSolutionStatus::kContinuity;
      }
    } else {
      *primary = 0;  // SPEC.md §3: no history → the nose-nearer
      sol_status = sep < tau_ ? CylinderSolutionStatus::kSideOn : CylinderSolutionStatus::kAmbiguous;
    }
    const CylinderSolution& alt = sols[1 - *primary];
    row->alt_yaw_rad = alt.yaw_rad;
    row->alt_pitch_rad = alt.pitch_rad;
    return sol_status;
  }

  // σ: the image fit's covariance when it succeeded, else the three-point Jacobian's propagation; and the
  // fit's figures.
  void SetSigmaAndFit(const CylinderInputs& x, const CylinderSolution& p, const std::optional<CylinderImageFitResult>& fit,
                      CylinderRow* row) const {
    const bool fitted = fit && fit->status != CylinderImageFitStatus::kFailed;
    CylinderJacobianMatrix J;
    if (!fitted && CylinderJacobian(cam_, x, p.range_m, &J)) {
      auto sigma = [&](int k) {
        double v = 0.0;
        for (int i = 2; i < 8; ++i) v += J(k, i) * J(k, i) * px_var_;
        v += (J(k, 0) * J(k, 0) + J(k, 1) * J(k, 1)) * ang_var_;
        return std::sqrt(v);
      };
      row->sigma_yaw_rad = sigma(0);
      row->sigma_pitch_rad = sigma(1);
    }
    if (fit) {
      const CylinderImageFitResult& g = *fit;
      row->fit = g.status;
      if (fitted) {
        row->sigma_yaw_rad = g.sigma_yaw_rad;
        row->sigma_pitch_rad = g.sigma_pitch_rad;
        row->fit_rms_dn = g.rms_dn;
        row->fit_psf_px = g.psf_sigma_px;
        row->fit_cone_m = g.nose_cone_length_m;
        row->fit_iterations = g.iterations;
      }
    }
  }

  camera::CameraModel cam_;  // the run's camera, with the mount of the row's StationView
  const target::CylinderShape& target_;
  const CylinderRunOptions& options_;
  const CylinderFrameReader* frames_;
  CylinderRunResult* result_;
  CylinderSolveOptions solve_;
  double tau_ = 0.0, px_var_ = 0.0, ang_var_ = 0.0;
  AxisHistory history_;
  std::optional<CylinderImageFitStart> warm_;  // the last converged fit's start for the next
};

}  // namespace

CylinderRunResult RunCylinder(const CylinderPointsFile& points, formats::TurretLog theodolite,
                              const camera::CameraModel& cam, const target::CylinderShape& target,
                              const CylinderRunOptions& options, const CylinderFrameReader* frames) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  if (!target.Check(&why)) throw UsageError(why);
  if (frames && !points.has_frame)
    throw UsageError(points.source + " has no `frame` column: the image fit (--video) needs it to find each row's frame");
  CylinderRunResult result;
  result.has_frame = points.has_frame;
  result.image_fit = frames != nullptr;

  // Theodolite: merge repeated times, azimuth on its unwrapped sequence (track/boresight.h, as rk-locate).
  const track::BoresightSource theo =
      track::BoresightSource::FromLog(std::move(theodolite), options.theodolite_method, options.theodolite_max_gap_s);
  result.theodolite_duplicate_times = theo.duplicate_times();

  CylinderRowSolver solver(cam, target, options, frames, &result);
  std::size_t complete_frames = 0, covered_frames = 0;
  result.rows.reserve(points.frames.size());
  for (const CylinderFramePoints& f : points.frames) {
    CylinderRow row;
    row.frame = f.frame;
    row.t_s = f.t_s + cam.time_offset_s;  // mid-exposure time (SPEC.md §3), the theodolite log's clock
    const bool complete = f.px[0] && f.px[1] && f.px[2];
    const std::optional<geo::AzEl> boresight = theo.At(row.t_s);
    const bool covered = boresight.has_value();
    if (covered) {
      row.boresight_az_rad = boresight->az_rad;
      row.boresight_el_rad = boresight->el_rad;
    }
    RowOutcome out{RowStatus::kLost, CylinderSolutionStatus::kMissingPoints};
    if (complete) {
      ++complete_frames;
      if (OutsideImage(f, cam)) {
        out = {RowStatus::kInvalid, CylinderSolutionStatus::kOutsideImage};
      } else if (!covered) {
        out = {RowStatus::kInvalid, CylinderSolutionStatus::kNoTheodolite};
      } else {
        ++covered_frames;
        const camera::StationView view = camera::ApplyPointing(cam, *boresight, options.pointing);
        solver.SetView(view);
        out = solver.Solve(f, view.boresight, &row);
      }
    }
    row.status = out.status;
    row.solution = out.solution;
    ++result.rows_by_status[static_cast<std::size_t>(row.status)];
    ++result.rows_by_solution[static_cast<std::size_t>(row.solution)];
    result.rows.push_back(row);
  }

  if (complete_frames == 0) {
    throw ProcessingError("no frame of " + points.source + " has all three points nose, tail1, tail2");
  }
  if (covered_frames == 0 && result.rows_by_solution[static_cast<std::size_t>(CylinderSolutionStatus::kNoTheodolite)] > 0) {
    theo.ThrowNoFrameCovered("theodolite", points.source, points.frames.front().t_s + cam.time_offset_s,
                             points.frames.back().t_s + cam.time_offset_s, "--theodolite-max-gap");
  }
  return result;
}

io::CsvWriter CylinderCsv(const CylinderRunResult& result) {
  std::vector<std::string> cols;
  if (result.has_frame) cols.push_back("frame");
  for (const char* c : {"t_s", "yaw_deg", "pitch_deg", "status", "alt_yaw_deg", "alt_pitch_deg", "solution",
                        "range_nose_m", "range_tail1_m", "range_tail2_m", "sigma_yaw_deg", "sigma_pitch_deg",
                        "separation_deg", "asymmetry_px", "edge_tilt_deg", "boresight_az_deg", "boresight_el_deg"}) {
    cols.push_back(c);
  }
  if (result.image_fit)
    for (const char* c : {"fit", "fit_rms_dn", "fit_psf_px", "fit_cone_m", "fit_iterations"}) cols.push_back(c);
  io::CsvWriter w(cols);
  constexpr int kAngleDecimals = 9;
  constexpr int kLengthDecimals = 6;
  auto deg = [](const std::optional<double>& rad) {
    return rad ? std::optional<double>(geo::RadToDeg(*rad)) : std::nullopt;
  };
  for (const CylinderRow& row : result.rows) {
    const bool values = row.status != RowStatus::kLost && row.status != RowStatus::kInvalid;
    auto val = [&](const std::optional<double>& v) { return values ? v : std::nullopt; };
    if (result.has_frame) {
      if (row.frame) {
        w.Add(*row.frame);
      } else {
        w.AddEmpty();
      }
    }
    w.Add(row.t_s, 9);
    w.Add(deg(val(row.yaw_rad)), kAngleDecimals);
    w.Add(deg(val(row.pitch_rad)), kAngleDecimals);
    w.Add(RowStatusName(row.status));
    w.Add(deg(val(row.alt_yaw_rad)), kAngleDecimals);
    w.Add(deg(val(row.alt_pitch_rad)), kAngleDecimals);
    w.Add(CylinderSolutionStatusName(row.solution));
    for (int i = 0; i < 3; ++i)
      w.Add(values && row.range_m ? std::optional<double>((*row.range_m)(i)) : std::nullopt, kLengthDecimals);
    w.Add(deg(val(row.sigma_yaw_rad)), kAngleDecimals);
    w.Add(deg(val(row.sigma_pitch_rad)), kAngleDecimals);
    w.Add(deg(val(row.separation_rad)), 6);
    w.Add(row.asymmetry_px, 6);  // a data-quality figure: also written for `inconsistent` rows
    w.Add(deg(val(row.edge_tilt_rad)), 6);
    w.Add(deg(row.boresight_az_rad), kAngleDecimals);
    w.Add(deg(row.boresight_el_rad), kAngleDecimals);
    if (result.image_fit) {
      if (row.fit) {
        w.Add(CylinderImageFitStatusName(*row.fit));
      } else {
        w.AddEmpty();
      }
      w.Add(row.fit_rms_dn, 3);
      w.Add(row.fit_psf_px, 4);
      w.Add(row.fit_cone_m, 4);
      if (row.fit_iterations) {
        w.Add(*row.fit_iterations);
      } else {
        w.AddEmpty();
      }
    }
    w.EndRow();
  }
  return w;
}

io::CsvRowRule CylinderPointsRowRule() { return formats::ImagePointsRowRule(); }

}  // namespace rk::attitude

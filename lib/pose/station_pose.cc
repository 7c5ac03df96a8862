// rk-attitude oi pipeline; method in station_pose.h.
#include "pose/station_pose.h"

#include <Eigen/Dense>
#include <cmath>
#include <utility>

#include "geo/angles.h"
#include "io/error.h"
#include "io/json_util.h"
#include "io/number_text.h"
#include "camera/station_view.h"
#include "pose/reproj_refine.h"

namespace rk::pose {
namespace {

// Station-frame outputs (e, n, u, yaw, pitch, roll) of a perturbed pose, for the covariance.
Eigen::Matrix<double, 6, 1> Outputs(const camera::CameraModel& cam, const geo::AzEl& b, const Eigen::Matrix3d& R,
                                    const Eigen::Vector3d& t, const Eigen::Matrix<double, 8, 1>& d) {
  geo::AzEl bb = b;
  bb.az_rad += d(6);
  bb.el_rad += d(7);
  Eigen::Vector3d p;
  Eigen::Matrix3d Reb;
  StationPose(cam, bb, ExpSo3(d.head<3>()) * R, t + d.segment<3>(3), &p, &Reb);
  const geo::EulerZyx e = geo::EulerFromRotationEnuBody(Reb);
  Eigen::Matrix<double, 6, 1> y;
  y << p, e.yaw_rad, e.pitch_rad, e.roll_rad;
  return y;
}

}  // namespace

const io::OptionTable<AttitudeOiOptions>& AttitudeOiOptions::Table() {
  using B = io::Bounds;
  using O = AttitudeOiOptions;
  using track::InterpMethod;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Choice("--turret-interp", &O::turret_method, {InterpMethod::kLinear, InterpMethod::kCubic},
                  track::InterpMethodName, "Turret angle interpolation to frame times: linear or cubic")
          .Real("--turret-max-gap", &O::turret_max_gap_s, "s", B::Positive(),
                "Longest turret-log interval (s) interpolated across; frames in longer gaps are invalid")
          .Real("--turret-sigma-deg", &O::turret_sigma_deg, "deg", B::AtLeast(0).Finite(),
                "1-sigma turret angle noise (deg) in the sigma_* columns (default: 0.003 deg step / sqrt 12)")
          .Real("--sigma-px", &O::sigma_px, "px", B::Positive().Finite(),
                "1-sigma pixel noise of points without a sigma_px column (px)")
          .Integer("--min-points", &O::min_points, "", B::Closed(4, 1000), "Fewest usable points for a pose (>= 4)")
          .Real("--max-rms-px", &O::max_rms_px, "px", B::Positive(),
                "Largest accepted RMS reprojection error (px); larger rows are invalid (after trying to reject one "
                "point)")
          .Flag("--no-reject", &O::no_reject, "Never leave a point out to bring the RMS under --max-rms-px")
          .Sub(&O::pnp, PnpOptions::Table())
          .Real("--continuity", &O::continuity_s, "s", B::AtLeast(0),
                "Ambiguous frames take the pose nearest the previous row's if it is at most this old (s)")
          .Flag("--pure-oi", &O::pure_oi,
                "Orthogonal iteration only, without the reprojection polish (object-space optimum; for comparison)");
  return table;
}

bool AttitudeOiOptions::Check(std::string* why) const { return Table().Check(*this, why) && pnp.Check(why); }

const char* PoseNoteName(PoseNote note) {
  switch (note) {
    case PoseNote::kNone:
      return "";
    case PoseNote::kFewPoints:
      return "few_points";
    case PoseNote::kTurret:
      return "turret";
    case PoseNote::kDegenerate:
      return "degenerate";
    case PoseNote::kBehindCamera:
      return "behind_camera";
    case PoseNote::kReprojection:
      return "reprojection";
  }
  return "?";
}

double AttitudeOiResult::MeanChi2PerDof() const { return dof_sum > 0 ? chi2_sum / dof_sum : std::nan(""); }

io::RunSummary AttitudeOiResult::Summary(const std::string& turret_source, bool boresight_fixed,
                                         std::size_t unusable_point_rows) const {
  io::RunSummary out;
  io::Json status = io::Json::object();
  for (std::size_t s = 0; s < rows_by_status.size(); ++s) {
    out.CountRows(static_cast<RowStatus>(s), rows_by_status[s]);
    status[RowStatusName(static_cast<RowStatus>(s))] = rows_by_status[s];
  }
  const std::string n = std::to_string(rows.size());
  if (turret_not_covered > 0 && !boresight_fixed) {
    out.Warn("turret_not_covered", std::to_string(turret_not_covered) + " of " + n +
                                       " frame times are not covered by " + turret_source +
                                       " (rows with enough points written as invalid)");
  }
  if (ambiguous > 0) {
    out.Warn("ambiguous", std::to_string(ambiguous) + " of " + n +
                              " frames have two poses that fit equally well (column ambiguous; the other is in alt_*)");
  }
  const double c2 = MeanChi2PerDof();
  if (std::isfinite(c2) && c2 > 4.0) {
    out.Warn("noise_above_sigma", "mean chi-square per degree of freedom is " + std::to_string(c2) +
                                      ": the pixel noise is larger than --sigma-px / sigma_px says, so the sigma_* "
                                      "columns are too small");
  }
  if (outliers_rejected > 0) {
    out.Flag("outliers_rejected", std::to_string(outliers_rejected) + " outlier point(s) rejected");
  }
  const std::size_t poses = rows_by_status[static_cast<std::size_t>(RowStatus::kOk)];
  if (!rows.empty()) {
    out.AddFigure("poses", static_cast<double>(poses) / static_cast<double>(rows.size()), "fraction",
                  std::to_string(poses) + " of " + n + " frames");
  }
  out.details["counts"] = {{"frames", rows.size()},
                           {"status", status},
                           {"few_points", few_points},
                           {"turret_not_covered", turret_not_covered},
                           {"degenerate", degenerate},
                           {"behind_camera", behind_camera},
                           {"reprojection", reprojection},
                           {"outliers_rejected", outliers_rejected},
                           {"ambiguous", ambiguous},
                           {"second_starts", second_starts},
                           {"turret_duplicate_times", turret_duplicate_times},
                           {"unusable_point_rows", unusable_point_rows}};
  out.details["mean_chi2_per_dof"] = std::isfinite(c2) ? io::Json(c2) : io::Json(nullptr);
  out.details["summary"] = SummaryJson();
  return out;
}

nlohmann::json AttitudeOiResult::SummaryJson() const {
  const double c2 = MeanChi2PerDof();
  return {{"frames", rows.size()},
          {"mean_chi2_per_dof", std::isfinite(c2) ? io::Json(c2) : io::Json(nullptr)},
          {"poses", rows_by_status[static_cast<std::size_t>(RowStatus::kOk)]},
          {"outliers_rejected", outliers_rejected}};
}

void StationPose(const camera::CameraModel& camera, const geo::AzEl& boresight, const Eigen::Matrix3d& R_cam_body,
                 const Eigen::Vector3d& t_cam, Eigen::Vector3d* p_enu, Eigen::Matrix3d* R_enu_body) {
  const Eigen::Matrix3d R_enu_cam =
      geo::RotationEnuFromTurret(boresight.az_rad, boresight.el_rad) * camera.RotationTurretFromCamera();
  *p_enu = R_enu_cam * t_cam;
  *R_enu_body = R_enu_cam * R_cam_body;
}

namespace {

// Pixels outside the sensor cannot be measurements: most likely the wrong camera model.
void CheckPointsInImage(const ImagePoints& points, const camera::CameraModel& camera) {
  for (const auto& f : points.frames) {
    for (const auto& p : f.points) {
      const bool inside = p.px.x() >= -0.5 && p.px.x() <= camera.width_px - 0.5 && p.px.y() >= -0.5 &&
                          p.px.y() <= camera.height_px - 0.5;
      if (!inside) {
        throw DataError(points.source, p.line, p.col_x,
                        "point (" + io::NumberText(p.px.x()) + ", " + io::NumberText(p.px.y()) + ") px is outside the " +
                            std::to_string(camera.width_px) + "x" + std::to_string(camera.height_px) +
                            " image of the camera model");
      }
    }
  }
}

PnpOptions SolverOptions(const AttitudeOiOptions& options) {
  PnpOptions pnp = options.pnp;
  if (options.pure_oi) pnp.polish = false;
  return pnp;
}

// The stages of RunAttitudeOi (station_pose.h steps 1–7), one frame at a time; the buffers are reused
// across frames.
class OiRun {
 public:
  OiRun(const ImagePoints& points, const target::FeatureModel& model, const camera::CameraModel& camera,
        const track::BoresightSource& boresight, const AttitudeOiOptions& options)
      : points_(points), model_(model), camera_(camera), boresight_(boresight), options_(options),
        solver_(SolverOptions(options)), cam_view_(camera) {
    res_.has_frame = points.has_frame;
    res_.turret_duplicate_times = boresight.duplicate_times();
    res_.rows.reserve(points.frames.size());
  }

  // Steps 1–7 for one frame: appends its row.
  void Frame(const PointFrame& f) {
    PoseRow row;
    row.frame = f.frame;
    row.t_s = f.t_s + camera_.time_offset_s;  // mid-exposure time (SPEC.md §3), the turret log's clock
    row.points_used = static_cast<int>(f.points.size());
    track::InterpStatus bs = track::InterpStatus::kOk;
    row.boresight = boresight_.At(row.t_s, &bs);
    if (!row.boresight) ++res_.turret_not_covered;
    if (row.boresight) {
      // The pointing model as the equivalent §3 boresight and mount (camera/station_view.h).
      const camera::StationView view = camera::ApplyPointing(camera_, *row.boresight, options_.pointing);
      b_view_ = view.boresight;
      cam_view_.mount_yaw_rad = view.mount_yaw_rad;
      cam_view_.mount_pitch_rad = view.mount_pitch_rad;
      cam_view_.mount_roll_rad = view.mount_roll_rad;
    }
    if (row.points_used < options_.min_points) {
      ++res_.few_points;
      return Finish(&row, RowStatus::kLost, PoseNote::kFewPoints);
    }
    if (!row.boresight) return Finish(&row, RowStatus::kInvalid, PoseNote::kTurret);
    Fit fit;
    const PoseNote note = FitFrame(f, &row, &fit);
    if (note != PoseNote::kNone) return Finish(&row, RowStatus::kInvalid, note);

    PnpSolution primary = fit.r.best;
    Eigen::Vector3d p_enu;
    Eigen::Matrix3d R_enu_body;
    ChoosePrimary(fit.r, &row, &primary, &p_enu, &R_enu_body);
    if (!PropagateSigma(b_view_, primary, &row.sigma)) {
      ++res_.degenerate;
      return Finish(&row, RowStatus::kInvalid, PoseNote::kDegenerate);
    }
    row.has_pose = true;
    row.p_enu_m = p_enu;
    row.R_enu_body = R_enu_body;
    row.attitude = geo::EulerFromRotationEnuBody(R_enu_body);
    row.rms_px = fit.rms;
    row.max_px = fit.max;
    row.chi2 = primary.chi2;
    row.dof = 2 * row.points_used - 6;
    row.oi_iterations = primary.oi_iterations;
    res_.chi2_sum += row.chi2;
    res_.dof_sum += std::max(row.dof, 0);
    const bool back = !res_.rows.empty() && !res_.rows.back().has_pose;
    Finish(&row, back ? RowStatus::kReacquired : RowStatus::kOk, PoseNote::kNone);
    prev_pose_ = res_.rows.size() - 1;
  }

  // The run's own checks: the turret log covers some frame, some frame has a pose.
  AttitudeOiResult Result() && {
    if (!boresight_.fixed() && !res_.rows.empty() && res_.turret_not_covered == res_.rows.size()) {
      const double t0 = boresight_.first_time(), t1 = boresight_.last_time();
      throw DataError(boresight_.source(), 0, 0,
                      (std::isnan(t0) ? std::string("has no usable sample")
                                      : "covers t_s " + io::NumberText(t0) + " .. " + io::NumberText(t1)) +
                          " but no frame time of " + points_.source + " (t_s " + io::NumberText(res_.rows.front().t_s) +
                          " .. " + io::NumberText(res_.rows.back().t_s) + ") is covered within the --turret-max-gap limit");
    }
    const std::size_t with_pose = res_.rows_by_status[static_cast<std::size_t>(RowStatus::kOk)] +
                                  res_.rows_by_status[static_cast<std::size_t>(RowStatus::kReacquired)];
    if (with_pose == 0) {
      throw ProcessingError("no pose in any of the " + std::to_string(res_.rows.size()) + " frames of " +
                            points_.source + " (" + std::to_string(res_.few_points) + " with fewer than " +
                            std::to_string(options_.min_points) + " usable points, " +
                            std::to_string(res_.rows.size() - res_.few_points) + " failed a check)");
    }
    return std::move(res_);
  }

 private:
  // A subset's pose and its residuals in distorted pixels.
  struct Fit {
    PnpResult r;
    double rms = 0, max = 0;
    bool front = false;
  };

  void Finish(PoseRow* row, RowStatus st, PoseNote note) {
    row->status = st;
    row->note = note;
    ++res_.rows_by_status[static_cast<std::size_t>(st)];
    res_.rows.push_back(*row);
  }

  // Steps 3–4: the pose of all points, else of all but the one whose omission fits best when the RMS is
  // too large. kNone when the fit passes the checks, else the note of the invalid row.
  PoseNote FitFrame(const PointFrame& f, PoseRow* row, Fit* fit) {
    xn_.clear();
    pb_.clear();
    sg_.clear();
    px_.clear();
    for (const auto& p : f.points) {
      const Eigen::Vector3d m = camera_.NormalisedRay(p.px);
      xn_.emplace_back(m.x(), m.y());
      pb_.push_back(model_.p_body[static_cast<std::size_t>(p.model_index)]);
      sg_.push_back(p.sigma_px.value_or(options_.sigma_px));
      px_.push_back(p.px);
    }
    *fit = Solve(-1);
    if (!fit->r.ok) {
      const bool behind = fit->r.failure.find("front") != std::string::npos;
      ++(behind ? res_.behind_camera : res_.degenerate);
      return behind ? PoseNote::kBehindCamera : PoseNote::kDegenerate;
    }
    if (fit->r.second_start_run) ++res_.second_starts;
    if (fit->rms > options_.max_rms_px && !options_.no_reject &&
        static_cast<int>(xn_.size()) - 1 >= options_.min_points) {
      Fit best;
      int best_skip = -1;
      for (int j = 0; j < static_cast<int>(xn_.size()); ++j) {
        Fit cand = Solve(j);
        if (cand.r.ok && cand.front && (best_skip < 0 || cand.rms < best.rms)) {
          best = cand;
          best_skip = j;
        }
      }
      if (best_skip >= 0 && best.rms <= options_.max_rms_px) {
        *fit = best;
        row->rejected_id =
            model_.ids[static_cast<std::size_t>(f.points[static_cast<std::size_t>(best_skip)].model_index)];
        row->points_used -= 1;
        ++res_.outliers_rejected;
      }
    }
    if (!fit->front) {
      ++res_.behind_camera;
      return PoseNote::kBehindCamera;
    }
    if (fit->rms > options_.max_rms_px) {
      ++res_.reprojection;
      row->rms_px = fit->rms;
      row->max_px = fit->max;
      return PoseNote::kReprojection;
    }
    return PoseNote::kNone;
  }

  // Solves the frame's points but `skip` (an index, or -1) and measures them in distorted pixels.
  Fit Solve(int skip) {
    xn_sub_.clear();
    pb_sub_.clear();
    sg_sub_.clear();
    for (std::size_t i = 0; i < xn_.size(); ++i) {
      if (static_cast<int>(i) == skip) continue;
      xn_sub_.push_back(xn_[i]);
      pb_sub_.push_back(pb_[i]);
      sg_sub_.push_back(sg_[i]);
    }
    Fit fit;
    fit.r = solver_.Solve(xn_sub_, pb_sub_, sg_sub_, camera_.fx(), camera_.fy());
    if (!fit.r.ok) return fit;
    double sse = 0;
    int n = 0;
    fit.front = true;
    for (std::size_t i = 0; i < xn_.size(); ++i) {
      if (static_cast<int>(i) == skip) continue;
      const auto uv = camera_.Project(fit.r.best.R_cam_body * pb_[i] + fit.r.best.t_cam);
      if (!uv) {
        fit.front = false;
        continue;
      }
      const double e2 = (*uv - px_[i]).squaredNorm();
      sse += e2;
      fit.max = std::max(fit.max, std::sqrt(e2));
      ++n;
    }
    fit.rms = n > 0 ? std::sqrt(sse / n) : 0.0;
    return fit;
  }

  // Steps 5–6: primary and alternative minima in the station frame; of two ambiguous minima the one
  // continuous with the previous pose is the primary, the other goes in alt_*.
  void ChoosePrimary(const PnpResult& r, PoseRow* row, PnpSolution* primary,
                     Eigen::Vector3d* p_enu, Eigen::Matrix3d* R_enu_body) {
    const geo::AzEl& b = b_view_;
    PnpSolution other = r.alt;
    Eigen::Vector3d p_alt;
    Eigen::Matrix3d R_alt;
    StationPose(cam_view_, b, primary->R_cam_body, primary->t_cam, p_enu, R_enu_body);
    if (!r.ambiguous) return;
    StationPose(cam_view_, b, other.R_cam_body, other.t_cam, &p_alt, &R_alt);
    const PoseRow* prev = prev_pose_ ? &res_.rows[*prev_pose_] : nullptr;
    if (prev && row->t_s - prev->t_s <= options_.continuity_s &&
        RotationAngle(R_alt, prev->R_enu_body) < RotationAngle(*R_enu_body, prev->R_enu_body)) {
      std::swap(*primary, other);
      std::swap(*p_enu, p_alt);
      std::swap(*R_enu_body, R_alt);
    }
    row->ambiguous = true;
    row->has_alt = true;
    row->alt_attitude = geo::EulerFromRotationEnuBody(R_alt);
    ++res_.ambiguous;
  }

  // Step 7: 1σ of e, n, u, yaw, pitch, roll from the covariance of (δθ_cam, δt_cam) of the polish plus
  // the turret noise on A and E. False when the information matrix is degenerate.
  bool PropagateSigma(const geo::AzEl& b, const PnpSolution& primary, Eigen::Matrix<double, 6, 1>* sigma) const {
    Eigen::Matrix<double, 8, 8> cov_in = Eigen::Matrix<double, 8, 8>::Zero();
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(primary.information);
    const Eigen::Matrix<double, 6, 6> cov6 = ldlt.solve(Eigen::Matrix<double, 6, 6>::Identity());
    const Eigen::Vector<double, 6> dinfo = primary.information.diagonal();
    if (ldlt.info() != Eigen::Success || !cov6.allFinite() || !(dinfo.minCoeff() > 0.0) || ldlt.rcond() < 1e-14) {
      return false;
    }
    cov_in.topLeftCorner<6, 6>() = cov6;
    const double turret_sigma_rad = geo::DegToRad(options_.turret_sigma_deg);
    cov_in(6, 6) = cov_in(7, 7) = turret_sigma_rad * turret_sigma_rad;
    Eigen::Matrix<double, 6, 8> J;
    for (int k = 0; k < 8; ++k) {
      const double h = 1e-6;
      Eigen::Matrix<double, 8, 1> d = Eigen::Matrix<double, 8, 1>::Zero();
      d(k) = h;
      Eigen::Matrix<double, 6, 1> yp = Outputs(cam_view_, b, primary.R_cam_body, primary.t_cam, d);
      Eigen::Matrix<double, 6, 1> ym = Outputs(cam_view_, b, primary.R_cam_body, primary.t_cam, -d);
      Eigen::Matrix<double, 6, 1> dy = yp - ym;
      for (int a = 3; a < 6; ++a) dy(a) = geo::WrapPi(yp(a) - ym(a));
      J.col(k) = dy / (2 * h);
    }
    const Eigen::Matrix<double, 6, 6> cov_out = J * cov_in * J.transpose();
    *sigma = cov_out.diagonal().cwiseMax(0.0).cwiseSqrt();
    return true;
  }

  const ImagePoints& points_;
  const target::FeatureModel& model_;
  const camera::CameraModel& camera_;
  const track::BoresightSource& boresight_;
  const AttitudeOiOptions& options_;
  PnpSolver solver_;
  AttitudeOiResult res_;
  std::optional<std::size_t> prev_pose_;  // index of the last row with a pose
  std::vector<Eigen::Vector2d> xn_, xn_sub_, px_;
  std::vector<Eigen::Vector3d> pb_, pb_sub_;
  std::vector<double> sg_, sg_sub_;
  // The frame's boresight and camera under the pointing model (the logged ones without one).
  camera::CameraModel cam_view_;
  geo::AzEl b_view_;
};

}  // namespace

AttitudeOiResult RunAttitudeOi(const ImagePoints& points, const target::FeatureModel& model,
                               const camera::CameraModel& camera, const track::BoresightSource& boresight,
                               const AttitudeOiOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  CheckPointsInImage(points, camera);
  OiRun run(points, model, camera, boresight, options);
  for (const PointFrame& f : points.frames) run.Frame(f);
  return std::move(run).Result();
}

io::CsvWriter PoseCsv(const AttitudeOiResult& result) {
  std::vector<std::string> cols;
  if (result.has_frame) cols.push_back("frame");
  for (const char* c :
       {"t_s", "e_m", "n_m", "u_m", "yaw_deg", "pitch_deg", "roll_deg", "status", "reproj_rms_px", "reproj_max_px",
        "points_used", "ambiguous", "alt_yaw_deg", "alt_pitch_deg", "alt_roll_deg", "sigma_e_m", "sigma_n_m",
        "sigma_u_m", "sigma_yaw_deg", "sigma_pitch_deg", "sigma_roll_deg", "rejected_id", "note", "boresight_az_deg",
        "boresight_el_deg"}) {
    cols.push_back(c);
  }
  io::CsvWriter w(cols);
  constexpr int kM = 6, kDeg = 6, kPx = 4, kSigDeg = 6;
  using geo::RadToDeg;
  for (const PoseRow& r : result.rows) {
    if (result.has_frame) {
      if (r.frame) {
        w.Add(*r.frame);
      } else {
        w.AddEmpty();
      }
    }
    w.Add(r.t_s, 9);
    if (r.has_pose) {
      w.Add(r.p_enu_m.x(), kM).Add(r.p_enu_m.y(), kM).Add(r.p_enu_m.z(), kM);
      w.Add(RadToDeg(r.attitude.yaw_rad), kDeg).Add(RadToDeg(r.attitude.pitch_rad), kDeg);
      w.Add(RadToDeg(r.attitude.roll_rad), kDeg);
    } else {
      for (int k = 0; k < 6; ++k) w.AddEmpty();
    }
    w.Add(RowStatusName(r.status));
    if (r.has_pose || r.note == PoseNote::kReprojection) {
      w.Add(r.rms_px, kPx).Add(r.max_px, kPx);
    } else {
      w.AddEmpty().AddEmpty();
    }
    w.Add(r.points_used);
    if (r.has_pose) {
      w.Add(r.ambiguous ? 1 : 0);
    } else {
      w.AddEmpty();
    }
    if (r.has_alt) {
      w.Add(RadToDeg(r.alt_attitude.yaw_rad), kDeg).Add(RadToDeg(r.alt_attitude.pitch_rad), kDeg);
      w.Add(RadToDeg(r.alt_attitude.roll_rad), kDeg);
    } else {
      w.AddEmpty().AddEmpty().AddEmpty();
    }
    if (r.has_pose) {
      for (int k = 0; k < 3; ++k) w.Add(r.sigma(k), kM);
      for (int k = 3; k < 6; ++k) w.Add(RadToDeg(r.sigma(k)), kSigDeg);
    } else {
      for (int k = 0; k < 6; ++k) w.AddEmpty();
    }
    w.Add(r.rejected_id ? std::string_view(*r.rejected_id) : std::string_view());
    w.Add(PoseNoteName(r.note));
    if (r.boresight) {
      w.Add(RadToDeg(r.boresight->az_rad), 9).Add(RadToDeg(r.boresight->el_rad), 9);
    } else {
      w.AddEmpty().AddEmpty();
    }
    w.EndRow();
  }
  return w;
}

}  // namespace rk::pose

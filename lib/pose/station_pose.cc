// rk-attitude oi pipeline; method in station_pose.h.
#include "pose/station_pose.h"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "geo/angles.h"
#include "io/error.h"
#include "io/json_util.h"
#include "pose/reproj_refine.h"

namespace rk::pose {
namespace {

std::string Num(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

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

bool AttitudeOiOptions::Check(std::string* why) const {
  if (!pnp.Check(why)) return false;
  if (min_points < 4 || min_points > 1000) {
    *why = "--min-points must be in [4, 1000] (a pose needs 4 points)";
    return false;
  }
  if (!(sigma_px > 0.0) || !std::isfinite(sigma_px)) {
    *why = "--sigma-px must be > 0";
    return false;
  }
  if (!(turret_sigma_rad >= 0.0) || !std::isfinite(turret_sigma_rad)) {
    *why = "--turret-sigma-deg must be >= 0";
    return false;
  }
  if (!(max_rms_px > 0.0)) {
    *why = "--max-rms-px must be > 0";
    return false;
  }
  if (!(continuity_s >= 0.0)) {
    *why = "--continuity must be >= 0 s";
    return false;
  }
  return true;
}

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

AttitudeOiResult RunAttitudeOi(const ImagePoints& points, const target::FeatureModel& model,
                               const camera::CameraModel& camera, const locate::BoresightSource& boresight,
                               const AttitudeOiOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  AttitudeOiResult res;
  res.has_frame = points.has_frame;
  res.turret_duplicate_times = boresight.duplicate_times();
  PnpSolver solver(options.pnp);
  const double fx = camera.fx(), fy = camera.fy();

  // Pixels outside the sensor cannot be measurements: most likely the wrong camera model.
  for (const auto& f : points.frames) {
    for (const auto& p : f.points) {
      const bool inside = p.px.x() >= -0.5 && p.px.x() <= camera.width_px - 0.5 && p.px.y() >= -0.5 &&
                          p.px.y() <= camera.height_px - 0.5;
      if (!inside) {
        throw DataError(points.source, p.line, p.col_x,
                        "point (" + Num(p.px.x()) + ", " + Num(p.px.y()) + ") px is outside the " +
                            std::to_string(camera.width_px) + "x" + std::to_string(camera.height_px) +
                            " image of the camera model");
      }
    }
  }

  std::vector<Eigen::Vector2d> xn, xn_sub;
  std::vector<Eigen::Vector3d> pb, pb_sub;
  std::vector<double> sg, sg_sub;
  std::vector<Eigen::Vector2d> px;
  std::optional<std::size_t> prev_pose;  // index of the last row with a pose
  res.rows.reserve(points.frames.size());
  for (const PointFrame& f : points.frames) {
    PoseRow row;
    row.frame = f.frame;
    row.t_s = f.t_s;
    row.points_used = static_cast<int>(f.points.size());
    track::InterpStatus bs = track::InterpStatus::kOk;
    row.boresight = boresight.At(f.t_s, &bs);
    auto finish = [&](RowStatus st, PoseNote note) {
      row.status = st;
      row.note = note;
      ++res.rows_by_status[static_cast<std::size_t>(st)];
      res.rows.push_back(row);
    };
    if (!row.boresight) ++res.turret_not_covered;
    if (row.points_used < options.min_points) {
      ++res.few_points;
      finish(RowStatus::kLost, PoseNote::kFewPoints);
      continue;
    }
    if (!row.boresight) {
      finish(RowStatus::kInvalid, PoseNote::kTurret);
      continue;
    }
    xn.clear();
    pb.clear();
    sg.clear();
    px.clear();
    for (const auto& p : f.points) {
      const Eigen::Vector3d m = camera.NormalisedRay(p.px);
      xn.emplace_back(m.x(), m.y());
      pb.push_back(model.p_body[static_cast<std::size_t>(p.model_index)]);
      sg.push_back(p.sigma_px.value_or(options.sigma_px));
      px.push_back(p.px);
    }
    // Solves a subset (skip = index left out, or -1) and measures it in distorted pixels.
    struct Fit {
      PnpResult r;
      double rms = 0, max = 0;
      bool front = false;
    };
    auto solve = [&](int skip) {
      xn_sub.clear();
      pb_sub.clear();
      sg_sub.clear();
      for (std::size_t i = 0; i < xn.size(); ++i) {
        if (static_cast<int>(i) == skip) continue;
        xn_sub.push_back(xn[i]);
        pb_sub.push_back(pb[i]);
        sg_sub.push_back(sg[i]);
      }
      Fit fit;
      fit.r = solver.Solve(xn_sub, pb_sub, sg_sub, fx, fy);
      if (!fit.r.ok) return fit;
      double sse = 0;
      int n = 0;
      fit.front = true;
      for (std::size_t i = 0; i < xn.size(); ++i) {
        if (static_cast<int>(i) == skip) continue;
        const auto uv = camera.Project(fit.r.best.R_cam_body * pb[i] + fit.r.best.t_cam);
        if (!uv) {
          fit.front = false;
          continue;
        }
        const double e2 = (*uv - px[i]).squaredNorm();
        sse += e2;
        fit.max = std::max(fit.max, std::sqrt(e2));
        ++n;
      }
      fit.rms = n > 0 ? std::sqrt(sse / n) : 0.0;
      return fit;
    };
    Fit fit = solve(-1);
    if (!fit.r.ok) {
      const bool behind = fit.r.failure.find("front") != std::string::npos;
      ++(behind ? res.behind_camera : res.degenerate);
      finish(RowStatus::kInvalid, behind ? PoseNote::kBehindCamera : PoseNote::kDegenerate);
      continue;
    }
    if (fit.r.second_start_run) ++res.second_starts;
    if (fit.rms > options.max_rms_px && options.reject_outlier &&
        static_cast<int>(xn.size()) - 1 >= options.min_points) {
      Fit best;
      int best_skip = -1;
      for (int j = 0; j < static_cast<int>(xn.size()); ++j) {
        Fit cand = solve(j);
        if (cand.r.ok && cand.front && (best_skip < 0 || cand.rms < best.rms)) {
          best = cand;
          best_skip = j;
        }
      }
      if (best_skip >= 0 && best.rms <= options.max_rms_px) {
        fit = best;
        row.rejected_id = model.ids[static_cast<std::size_t>(f.points[static_cast<std::size_t>(best_skip)].model_index)];
        row.points_used -= 1;
        ++res.outliers_rejected;
      }
    }
    if (!fit.front) {
      ++res.behind_camera;
      finish(RowStatus::kInvalid, PoseNote::kBehindCamera);
      continue;
    }
    if (fit.rms > options.max_rms_px) {
      ++res.reprojection;
      row.rms_px = fit.rms;
      row.max_px = fit.max;
      finish(RowStatus::kInvalid, PoseNote::kReprojection);
      continue;
    }

    // Primary and alternative minima in the station frame.
    const geo::AzEl& b = *row.boresight;
    PnpSolution primary = fit.r.best;
    PnpSolution other = fit.r.alt;
    Eigen::Vector3d p_enu, p_alt;
    Eigen::Matrix3d R_enu_body, R_alt;
    StationPose(camera, b, primary.R_cam_body, primary.t_cam, &p_enu, &R_enu_body);
    if (fit.r.ambiguous) {
      StationPose(camera, b, other.R_cam_body, other.t_cam, &p_alt, &R_alt);
      const PoseRow* prev = prev_pose ? &res.rows[*prev_pose] : nullptr;
      if (prev && f.t_s - prev->t_s <= options.continuity_s &&
          RotationAngle(R_alt, prev->R_enu_body) < RotationAngle(R_enu_body, prev->R_enu_body)) {
        std::swap(primary, other);
        std::swap(p_enu, p_alt);
        std::swap(R_enu_body, R_alt);
      }
      row.ambiguous = true;
      row.has_alt = true;
      row.alt_attitude = geo::EulerFromRotationEnuBody(R_alt);
      ++res.ambiguous;
    }
    // Covariance of (δθ_cam, δt_cam) from the polish, plus turret noise on A and E.
    Eigen::Matrix<double, 8, 8> cov_in = Eigen::Matrix<double, 8, 8>::Zero();
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(primary.information);
    const Eigen::Matrix<double, 6, 6> cov6 = ldlt.solve(Eigen::Matrix<double, 6, 6>::Identity());
    const Eigen::Vector<double, 6> dinfo = primary.information.diagonal();
    if (ldlt.info() != Eigen::Success || !cov6.allFinite() || !(dinfo.minCoeff() > 0.0) ||
        ldlt.rcond() < 1e-14) {
      ++res.degenerate;
      finish(RowStatus::kInvalid, PoseNote::kDegenerate);
      continue;
    }
    cov_in.topLeftCorner<6, 6>() = cov6;
    cov_in(6, 6) = cov_in(7, 7) = options.turret_sigma_rad * options.turret_sigma_rad;
    Eigen::Matrix<double, 6, 8> J;
    for (int k = 0; k < 8; ++k) {
      const double h = 1e-6;
      Eigen::Matrix<double, 8, 1> d = Eigen::Matrix<double, 8, 1>::Zero();
      d(k) = h;
      Eigen::Matrix<double, 6, 1> yp = Outputs(camera, b, primary.R_cam_body, primary.t_cam, d);
      Eigen::Matrix<double, 6, 1> ym = Outputs(camera, b, primary.R_cam_body, primary.t_cam, -d);
      Eigen::Matrix<double, 6, 1> dy = yp - ym;
      for (int a = 3; a < 6; ++a) dy(a) = geo::WrapPi(yp(a) - ym(a));
      J.col(k) = dy / (2 * h);
    }
    const Eigen::Matrix<double, 6, 6> cov_out = J * cov_in * J.transpose();
    row.sigma = cov_out.diagonal().cwiseMax(0.0).cwiseSqrt();

    row.has_pose = true;
    row.p_enu_m = p_enu;
    row.R_enu_body = R_enu_body;
    row.attitude = geo::EulerFromRotationEnuBody(R_enu_body);
    row.rms_px = fit.rms;
    row.max_px = fit.max;
    row.chi2 = primary.chi2;
    row.dof = 2 * row.points_used - 6;
    row.oi_iterations = primary.oi_iterations;
    res.chi2_sum += row.chi2;
    res.dof_sum += std::max(row.dof, 0);
    const bool back = !res.rows.empty() && !res.rows.back().has_pose;
    finish(back ? RowStatus::kReacquired : RowStatus::kOk, PoseNote::kNone);
    prev_pose = res.rows.size() - 1;
  }

  if (!boresight.fixed() && !res.rows.empty() && res.turret_not_covered == res.rows.size()) {
    const double t0 = boresight.first_time(), t1 = boresight.last_time();
    throw DataError(boresight.source(), 0, 0,
                    (std::isnan(t0) ? std::string("has no usable sample")
                                    : "covers t_s " + Num(t0) + " .. " + Num(t1)) +
                        " but no frame time of " + points.source + " (t_s " + Num(res.rows.front().t_s) + " .. " +
                        Num(res.rows.back().t_s) + ") is covered within the --turret-max-gap limit");
  }
  const std::size_t with_pose = res.rows_by_status[static_cast<std::size_t>(RowStatus::kOk)] +
                                res.rows_by_status[static_cast<std::size_t>(RowStatus::kReacquired)];
  if (with_pose == 0) {
    throw ProcessingError("no pose in any of the " + std::to_string(res.rows.size()) + " frames of " + points.source +
                          " (" + std::to_string(res.few_points) + " with fewer than " +
                          std::to_string(options.min_points) + " usable points, " +
                          std::to_string(res.rows.size() - res.few_points) + " failed a check)");
  }
  return res;
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

// PnP pipeline (weak-perspective start → OI → LM polish → second start); see pnp.h.
#include "pose/pnp.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "geo/angles.h"
#include "pose/pose_init.h"

namespace rk::pose {

std::string SecondStartName(SecondStart s) {
  switch (s) {
    case SecondStart::kAuto:
      return "auto";
    case SecondStart::kAlways:
      return "always";
    case SecondStart::kNever:
      return "never";
  }
  return "?";
}

const io::OptionTable<PnpOptions>& PnpOptions::Table() {
  using B = io::Bounds;
  using O = PnpOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Choice("--second-start", &O::second_start, {SecondStart::kAuto, SecondStart::kAlways, SecondStart::kNever},
                  SecondStartName,
                  "Second OI start from the mirrored pose: auto (near-planar targets, or a poor first fit), always, "
                  "never")
          .Real("--ambiguity-chi2", &O::ambiguity_chi2, "", B::AtLeast(0).Finite(),
                "Two minima whose chi-square differ by less are flagged ambiguous")
          .Real("--near-planar", &O::near_planar_ratio, "", B::Closed(0, 1),
                "Targets with scatter eigenvalue ratio lambda3/lambda1 below this are near-planar (second start, "
                "homography start)");
  return table;
}

bool PnpOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  const char* w = nullptr;
  if (!oi.Check(&w)) {
    *why = w;
    return false;
  }
  if (refine.max_iterations < 1 || !(refine.step_tol > 0)) {
    *why = "refinement needs max_iterations >= 1 and a positive step tolerance";
    return false;
  }
  if (!(oi_handoff_tol > 0.0) || !(oi_handoff_tol_planar > 0.0)) {
    *why = "OI hand-over tolerance must be > 0";
    return false;
  }
  if (!(retry_rms_px > 0.0)) {
    *why = "retry RMS threshold must be > 0 px";
    return false;
  }
  if (!(distinct_deg > 0.0 && distinct_deg < 180.0)) {
    *why = "distinct-minimum angle must be in (0, 180) degrees";
    return false;
  }
  return true;
}

double RotationAngle(const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb) {
  const Eigen::Matrix3d D = Ra.transpose() * Rb;
  // Robust at small and large angles: sin from the skew part, cos from the trace.
  const Eigen::Vector3d s(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  return std::atan2(0.5 * s.norm(), 0.5 * (D.trace() - 1.0));
}

PnpSolver::PnpSolver(PnpOptions options) : opt_(std::move(options)) {}

PnpSolution PnpSolver::FromStart(const Eigen::Matrix3d& R0, std::span<const Eigen::Vector2d> xn,
                                 std::span<const Eigen::Vector3d> p_body, std::span<const double> sigma_px,
                                 double fx, double fy, bool full_oi) const {
  PnpSolution s;
  OiOptions oi_opt = opt_.oi;
  // Near-planar targets hand over later: their two minima lie in a flat valley and an early
  // hand-over can let LM slide into the other one (tests: a 5°-tilted square).
  if (opt_.polish && !full_oi) {
    const double handoff =
        planarity_ < opt_.near_planar_ratio ? opt_.oi_handoff_tol_planar : opt_.oi_handoff_tol;
    oi_opt.rotation_tol = std::max(oi_opt.rotation_tol, handoff);
  }
  OiResult oi = oi_.Solve(R0, oi_opt);
  // E(R, t) cannot tell a point from its reflection through the camera centre: for a planar
  // model, X → −X is the rotation by π about the plane normal, and OI may converge to that
  // image behind the camera. Restart from the reflected pose when the target lies behind.
  if ((oi.R_cam_body * oi_.centroid_body() + oi.t_cam).z() < 0.0) {
    const Eigen::Matrix3d& E = oi_.scatter_axes();
    const Eigen::Matrix3d flip = E * Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal() * E.transpose();
    const int first = oi.iterations;
    oi = oi_.Solve(oi.R_cam_body * flip, oi_opt);
    oi.iterations += first;
  }
  s.oi_iterations = oi.iterations;
  s.oi_termination = oi.termination;
  s.R_cam_body = oi.R_cam_body;
  s.t_cam = oi.t_cam;
  double sse = 0.0;
  if (opt_.polish) {
    const ReprojRefineResult r =
        RefineReprojection(xn, p_body, sigma_px, fx, fy, oi.R_cam_body, oi.t_cam, opt_.refine);
    s.R_cam_body = r.R_cam_body;
    s.t_cam = r.t_cam;
    s.chi2 = r.chi2;
    s.in_front = r.in_front;
    s.refine_iterations = r.iterations;
    s.information = r.information;
    sse = r.sse_px2;
  } else {
    s.chi2 = ReprojectionChi2(xn, p_body, sigma_px, fx, fy, s.R_cam_body, s.t_cam, &s.in_front, &sse);
    if (s.in_front) s.information = ReprojectionInformation(xn, p_body, sigma_px, fx, fy, s.R_cam_body, s.t_cam);
  }
  s.rms_px = std::sqrt(sse / static_cast<double>(xn.size()));
  return s;
}

PnpResult PnpSolver::Solve(std::span<const Eigen::Vector2d> xn, std::span<const Eigen::Vector3d> p_body,
                           std::span<const double> sigma_px, double fx, double fy) {
  PnpResult res;
  const std::size_t n = xn.size();
  if (n < 3 || p_body.size() != n || (!sigma_px.empty() && sigma_px.size() != n)) {
    res.failure = "fewer than 3 points, or inputs of different sizes";
    return res;
  }
  rays_.resize(n);
  for (std::size_t i = 0; i < n; ++i) rays_[i] = Eigen::Vector3d(xn[i].x(), xn[i].y(), 1.0);
  if (!oi_.Set(rays_, p_body)) {
    res.failure = "degenerate geometry: model points collinear or coincident";
    return res;
  }
  const Eigen::Vector3d& lambda = oi_.scatter_eigenvalues();
  res.planarity = lambda(2) / lambda(0);
  planarity_ = res.planarity;
  WeakPerspectiveStart init;
  if (res.planarity < opt_.near_planar_ratio && n >= 4) init = HomographyInit(rays_, p_body);
  if (!init.ok) init = WeakPerspectiveInit(rays_, p_body);
  if (!init.ok) {
    res.failure = "no weak-perspective start (degenerate geometry)";
    return res;
  }
  // Distinct minima found so far, best (lowest χ², in front) first.
  int found = 0;
  auto consider = [&](const PnpSolution& s) {
    auto better = [](const PnpSolution& a, const PnpSolution& b) {
      return a.in_front != b.in_front ? a.in_front : a.chi2 < b.chi2;
    };
    const double distinct = geo::DegToRad(opt_.distinct_deg);
    if (found == 0) {
      res.best = s;
      found = 1;
      return;
    }
    if (RotationAngle(s.R_cam_body, res.best.R_cam_body) <= distinct) {
      if (better(s, res.best)) res.best = s;
      return;
    }
    if (better(s, res.best)) {
      res.alt = res.best;
      res.best = s;
      found = 2;
      return;
    }
    if (found == 1 || better(s, res.alt)) {  // alt = the best minimum distinct from `best`
      res.alt = s;
      found = 2;
    }
  };
  consider(FromStart(init.R_cam_body[0], xn, p_body, sigma_px, fx, fy));
  const bool run_second = opt_.second_start == SecondStart::kAlways ||
                          (opt_.second_start == SecondStart::kAuto &&
                           (res.planarity < opt_.near_planar_ratio || !res.best.in_front ||
                            res.best.rms_px > opt_.retry_rms_px));
  if (run_second) {
    res.second_start_run = true;
    PnpSolution second = FromStart(init.R_cam_body[1], xn, p_body, sigma_px, fx, fy);
    if (opt_.polish && RotationAngle(second.R_cam_body, res.best.R_cam_body) <= geo::DegToRad(opt_.distinct_deg)) {
      // Landed on the first minimum: was it the early hand-over? Let OI converge fully.
      second = FromStart(init.R_cam_body[1], xn, p_body, sigma_px, fx, fy, /*full_oi=*/true);
    }
    consider(second);
  }
  // Still no solution consistent with the image: the starts fell into wrong basins (small n,
  // strong perspective). Try the first solution turned end over end about the virtual image
  // axes (depth order reversed), the usual other basins of P4P.
  if (opt_.second_start != SecondStart::kNever && (!res.best.in_front || res.best.rms_px > opt_.retry_rms_px)) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (const auto& m : rays_) d += m.normalized();
    const Eigen::Matrix3d Rv = RotationBetween(d, Eigen::Vector3d::UnitZ());
    const Eigen::Matrix3d R1 = res.best.R_cam_body;
    for (const Eigen::Vector3d& axis : {Eigen::Vector3d::UnitX().eval(), Eigen::Vector3d::UnitY().eval()}) {
      const Eigen::Matrix3d flip = 2.0 * axis * axis.transpose() - Eigen::Matrix3d::Identity();  // π about axis
      consider(FromStart(Rv.transpose() * flip * Rv * R1, xn, p_body, sigma_px, fx, fy));
      ++res.extra_starts;
    }
    // Last resort (rare: < 0.1 % of random 4-point problems): the 24 rotations of the cube
    // group as starts, which cover every attitude within 62.8° of one of them.
    if (!res.best.in_front || res.best.rms_px > opt_.retry_rms_px) {
      static const std::vector<Eigen::Matrix3d> kCube = [] {
        std::vector<Eigen::Matrix3d> g;
        const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
        const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        for (const auto& p : perms) {
          for (int signs = 0; signs < 8; ++signs) {
            Eigen::Matrix3d R;
            for (int c = 0; c < 3; ++c) R.col(c) = ((signs >> c) & 1 ? -1.0 : 1.0) * I.col(p[c]);
            if (R.determinant() > 0) g.push_back(R);
          }
        }
        return g;
      }();
      for (const Eigen::Matrix3d& G : kCube) {
        consider(FromStart(Rv.transpose() * G * Rv * R1, xn, p_body, sigma_px, fx, fy));
        ++res.extra_starts;
      }
    }
  }
  res.has_alt = found == 2;
  res.ambiguous = res.has_alt && res.alt.in_front && res.best.in_front &&
                  res.alt.chi2 - res.best.chi2 < opt_.ambiguity_chi2;
  res.ok = res.best.in_front && res.best.R_cam_body.allFinite() && res.best.t_cam.allFinite();
  if (!res.ok) res.failure = "no solution with every point in front of the camera";
  return res;
}

}  // namespace rk::pose

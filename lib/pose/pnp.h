// Pose of a known target from ≥ 4 image points (perspective-n-point), the solver behind
// `rk-attitude oi`:
//   1. weak-perspective start (pose/pose_init.h),
//   2. orthogonal iteration to convergence (pose/oi.h; Lu, Hager & Mjolsness 2000),
//   3. Levenberg–Marquardt polish of the reprojection error (pose/reproj_refine.h), so the
//      result is the maximum-likelihood pose under independent Gaussian pixel noise (OI's
//      object-space error weights points by depth²; the polish removes that bias),
//   4. a second start from the mirrored weak-perspective pose (the other minimum of a planar
//      or near-planar target), run when the target is near-planar (λ3/λ1 of the model scatter
//      below near_planar_ratio), when the first solution fails, or always/never on request.
//      Two distinct minima (rotations more than distinct_deg apart) whose χ² differ by less
//      than ambiguity_chi2 are flagged ambiguous: the data cannot tell them apart at the
//      stated pixel noise. Both are returned, best (lower χ²) first.
// Works for coplanar and non-coplanar models, n ≥ 4 (n = 3 is accepted by the solver but has
// up to four exact solutions; callers require 4). Never trusts a solver flag: the result
// carries χ², the pixel RMS, and whether every point is in front of the camera.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "io/options.h"
#include "pose/oi.h"
#include "pose/reproj_refine.h"

namespace rk::pose {

enum class SecondStart { kAuto, kAlways, kNever };
std::string SecondStartName(SecondStart s);  // "auto" | "always" | "never"

struct PnpOptions {
  OiOptions oi;
  bool polish = true;                 // LM polish of the reprojection error after OI
  // With the polish on, OI hands over once a step changes R by less than this (Frobenius, ≈ rad):
  // OI has then found the basin, and LM converges quadratically from there while OI converges
  // only linearly (slowly for near-planar targets). Measured (attitude_pnp_bench,
  // oi-handoff=T): 1e-3 gives the same estimates as 1e-6 on 12 000 problems at 1/4 of the
  // OI iterations on non-planar targets. Near-planar targets (planarity < near_planar_ratio)
  // hand over at oi_handoff_tol_planar, and a second start that lands on the first minimum is
  // run again with OI to its own convergence: the hand-over must not hide a minimum. > 0.
  double oi_handoff_tol = 1e-3;
  double oi_handoff_tol_planar = 1e-6;
  ReprojRefineOptions refine;
  SecondStart second_start = SecondStart::kAuto;
  double near_planar_ratio = 0.05;    // auto: second start when λ3/λ1 < this, [0, 1]
  double ambiguity_chi2 = 9.0;        // Δχ² (σ-weighted) below which two minima are ambiguous, ≥ 0
  double distinct_deg = 0.5;          // minima whose rotations differ by less are the same (deg), > 0
  // A solution whose RMS reprojection error exceeds this (px) is not trusted: the second start
  // and two further starts (the solution turned end over end) are tried. > 0.
  double retry_rms_px = 2.0;

  // The command-line options of the solver (rk-attitude oi; io/options.h).
  static const io::OptionTable<PnpOptions>& Table();
  bool Check(std::string* why) const;
};

struct PnpSolution {
  Eigen::Matrix3d R_cam_body = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_cam = Eigen::Vector3d::Zero();  // body origin, camera frame (m)
  double chi2 = 0.0;       // Σ (pixel residual / σ)²
  double rms_px = 0.0;     // sqrt(Σ‖r‖² / n), pixels (undistorted image)
  bool in_front = false;   // every point has Z > 0
  int oi_iterations = 0;
  OiTermination oi_termination = OiTermination::kDegenerate;
  int refine_iterations = 0;
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();  // JᵀJ (δθ_cam, δt_cam)
};

struct PnpResult {
  bool ok = false;               // `best` exists and has every point in front of the camera
  std::string failure;           // why not ok
  PnpSolution best;
  bool has_alt = false;          // a second, distinct minimum was found
  PnpSolution alt;
  bool ambiguous = false;        // has_alt and χ²(alt) − χ²(best) < ambiguity_chi2
  bool second_start_run = false;
  int extra_starts = 0;          // starts beyond the first two (see retry_rms_px)
  double planarity = 0.0;        // λ3/λ1 of the model points used
};

// Rotation angle between two rotation matrices (radians, [0, π]).
double RotationAngle(const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb);

// Reusable solver: keeps its work buffers between calls (no allocation once warmed up).
class PnpSolver {
 public:
  explicit PnpSolver(PnpOptions options = {});
  const PnpOptions& options() const { return opt_; }

  // xn: undistorted normalised image points; p_body: model points (m); sigma_px: per-point 1σ
  // (px) or empty (1 px); fx, fy (px).
  PnpResult Solve(std::span<const Eigen::Vector2d> xn, std::span<const Eigen::Vector3d> p_body,
                  std::span<const double> sigma_px, double fx, double fy);

 private:
  PnpSolution FromStart(const Eigen::Matrix3d& R0, std::span<const Eigen::Vector2d> xn,
                        std::span<const Eigen::Vector3d> p_body, std::span<const double> sigma_px, double fx,
                        double fy, bool full_oi = false) const;

  PnpOptions opt_;
  double planarity_ = 1.0;  // of the current problem
  std::vector<Eigen::Vector3d> rays_;
  OrthogonalIteration oi_;
};

}  // namespace rk::pose

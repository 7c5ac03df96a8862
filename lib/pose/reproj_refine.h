// Maximum-likelihood polish of a camera pose under image noise: Levenberg–Marquardt on the
// reprojection error, started from an orthogonal-iteration solution (pose/oi.h), with the
// pose covariance from the information matrix.
//
// Model: X_i = R p_i + t (camera frame), predicted normalised point (X/Z, Y/Z); residual in
// pixels r_i = (f_x (X/Z − x_i), f_y (Y/Z − y_i)) / σ_i with σ_i the point's 1σ pixel noise.
// Cost χ² = Σ ‖r_i‖². Parameters: δθ (rotation vector, camera frame, left perturbation
// R ← exp([δθ]×) R) and δt (m). Jacobian of X: ∂X/∂δθ = −[R p_i]×, ∂X/∂δt = I; of the
// projection: ∂(X/Z)/∂X = (1/Z, 0, −X/Z²). Steps solve (JᵀJ + μ diag(JᵀJ)) δ = −Jᵀr; μ
// shrinks ×0.1 after a step that lowers χ² and grows ×10 otherwise (at most 10 tries).
// At the minimum, Cov(δθ, δt) = (JᵀJ)⁻¹ to first order (Gauss–Newton), valid when the σ_i
// are the true pixel noise and the pixels are unbiased.
// Points must stay in front of the camera (Z > 0): a step that puts one behind is refused.
#pragma once

#include <Eigen/Core>
#include <span>

namespace rk::pose {

struct ReprojRefineOptions {
  int max_iterations = 30;   // LM iterations, ≥ 1
  double step_tol = 1e-10;   // stop when ‖δθ‖ + ‖δt‖/‖t‖ falls below this (rad; 1e-10 rad = 2e-5″)
};

struct ReprojRefineResult {
  Eigen::Matrix3d R_cam_body = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_cam = Eigen::Vector3d::Zero();
  double chi2 = 0.0;        // Σ ‖r_i‖² (σ-weighted)
  double sse_px2 = 0.0;     // Σ of squared pixel residuals (unweighted)
  int iterations = 0;
  bool converged = false;
  bool in_front = false;    // every point has Z > 0 at the result
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();  // JᵀJ at the result
};

// xn: undistorted normalised image points (x, y) = ((u − cx)/fx, (v − cy)/fy); p_body: model
// points (m); sigma_px: per-point 1σ (px), or empty for 1 px everywhere; fx, fy: focal
// lengths (px).
ReprojRefineResult RefineReprojection(std::span<const Eigen::Vector2d> xn, std::span<const Eigen::Vector3d> p_body,
                                      std::span<const double> sigma_px, double fx, double fy,
                                      const Eigen::Matrix3d& R0, const Eigen::Vector3d& t0,
                                      const ReprojRefineOptions& options = {});

// χ² and in-front test of a pose without refining it (same residual definition).
double ReprojectionChi2(std::span<const Eigen::Vector2d> xn, std::span<const Eigen::Vector3d> p_body,
                        std::span<const double> sigma_px, double fx, double fy, const Eigen::Matrix3d& R,
                        const Eigen::Vector3d& t, bool* in_front = nullptr, double* sse_px2 = nullptr);

// JᵀJ of the σ-weighted residuals at a pose (the information matrix, as above), without
// refining: for a pose that was not polished.
Eigen::Matrix<double, 6, 6> ReprojectionInformation(std::span<const Eigen::Vector2d> xn,
                                                    std::span<const Eigen::Vector3d> p_body,
                                                    std::span<const double> sigma_px, double fx, double fy,
                                                    const Eigen::Matrix3d& R, const Eigen::Vector3d& t);

// exp([w]×) (Rodrigues).
Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& w);

}  // namespace rk::pose

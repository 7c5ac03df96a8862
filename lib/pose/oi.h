// Orthogonal iteration (OI) for the pose of a known rigid point set seen by a calibrated
// camera: Lu, Hager & Mjolsness, "Fast and globally convergent pose estimation from video
// images", IEEE TPAMI 22(6):610–622, 2000 (the method of seed 001 §2.3). Own implementation.
//
// Solves for the pose (R, t) such that  λ_i m_i = R p_i + t  with λ_i > 0, where
// m_i = (x_i, y_i, 1) is the undistorted normalised image ray of model point p_i (body
// frame, metres) and R = R_cam_body, t = body origin in the camera frame (metres).
//
// Object-space collinearity error (eq. 17 of the paper): with the line-of-sight projector
//   V_i = m_i m_iᵀ / (m_iᵀ m_i),
//   E(R, t) = Σ_i ‖(I − V_i)(R p_i + t)‖².
// For a given R the optimal t is closed form (eq. 20); with the model centred on its
// centroid (p'_i = p_i − p̄, so Σ p'_i = 0):
//   t'(R) = (n I − Σ V_i)⁻¹ Σ_i V_i R p'_i,        t = t' − R p̄.
// One OI step (eqs. 21–24) projects the current points onto their lines of sight,
// q_i = V_i (R p'_i + t'(R)), and solves the absolute-orientation problem between p'_i and
// q_i: R ← argmax tr(Rᵀ M), M = Σ_i q_i p'_iᵀ (Procrustes, SVD with det = +1). The error
// decreases monotonically; the paper proves global convergence to a critical point.
//
// Cost: everything is linear in R, so the sums are precomputed once (O(n)) and each
// iteration is O(1), independent of n (the paper's §4.2):
//   W_k = Σ_i p'_ik V_i,  Y_kl = Σ_i p'_ik p'_il V_i,  F = (n I − Σ V_i)⁻¹
//   t'(R) = F Σ_k W_k r_k                        (r_k = column k of R)
//   column j of M = Σ_k (Y_jk + W_j F W_k) r_k    → vec M = G vec R, G 9×9
//   E(R) = Σ‖p'_i‖² − vec Rᵀ Y vec R − t'ᵀ (n I − Σ V_i) t'.
// Assumptions: n ≥ 3 rays with positive z (in front of the camera); a model whose points
// are not all collinear. The minimiser of E is not the maximum-likelihood pose under
// pixel noise (E weights each point by its depth²); pose/pnp.h polishes it in image space.
#pragma once

#include <Eigen/Core>
#include <span>

namespace rk::pose {

struct OiOptions {
  int max_iterations = 400;        // hard cap on OI steps, ≥ 1
  double rotation_tol = 1e-10;     // stop when ‖R_{k+1} − R_k‖_F < rotation_tol, > 0
  // Stop early when the object-space error changes by less than this fraction of
  // Σ‖p'_i‖² per step (it is monotone; 0 = rotation test only). ≥ 0.
  double error_tol = 0.0;

  bool Check(const char** why) const;
};

enum class OiTermination { kConverged, kMaxIterations, kDegenerate };
const char* OiTerminationName(OiTermination t);

struct OiResult {
  Eigen::Matrix3d R_cam_body = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_cam = Eigen::Vector3d::Zero();  // body origin in the camera frame (m)
  double object_error_m2 = 0.0;  // E(R, t) at the result (m²), O(1) form: round-off ~1e-15 Σ‖p'‖²
  int iterations = 0;
  OiTermination termination = OiTermination::kDegenerate;
};

// Precomputed sums for one set of correspondences; Solve() may then be called from several
// starts at O(1) cost per iteration. Holds no references to the inputs.
class OrthogonalIteration {
 public:
  // rays: m_i (any positive multiple of (x, y, 1), z > 0), p_body: model points (m).
  // Returns false (and the object is unusable) if n < 3, sizes differ, a ray has z ≤ 0, or
  // the model points are collinear / coincident (no rotation is determined).
  bool Set(std::span<const Eigen::Vector3d> rays, std::span<const Eigen::Vector3d> p_body);

  // Runs OI from the start rotation R0 (orthonormal).
  OiResult Solve(const Eigen::Matrix3d& R0, const OiOptions& options) const;

  // Optimal translation (body origin in the camera frame) for a rotation, and E(R, t(R)).
  Eigen::Vector3d Translation(const Eigen::Matrix3d& R) const;
  double ObjectError(const Eigen::Matrix3d& R) const;

  int size() const { return n_; }
  const Eigen::Vector3d& centroid_body() const { return centroid_; }
  // Eigenvalues of the centred model scatter Σ p'p'ᵀ, descending (m²), and its eigenvectors
  // (columns): λ3/λ1 measures how far the model is from planar.
  const Eigen::Vector3d& scatter_eigenvalues() const { return lambda_; }
  const Eigen::Matrix3d& scatter_axes() const { return axes_; }

 private:
  Eigen::Vector3d TranslationCentred(const Eigen::Matrix3d& R) const;

  int n_ = 0;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d F_ = Eigen::Matrix3d::Zero();      // (n I − Σ V)⁻¹
  Eigen::Matrix3d Finv_ = Eigen::Matrix3d::Zero();   // n I − Σ V
  Eigen::Matrix3d W_[3];                             // Σ p'_k V
  Eigen::Matrix<double, 9, 9> G_ = Eigen::Matrix<double, 9, 9>::Zero();
  Eigen::Matrix<double, 9, 9> Y_ = Eigen::Matrix<double, 9, 9>::Zero();
  double sum_p2_ = 0.0;                              // Σ‖p'‖²
  Eigen::Vector3d lambda_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes_ = Eigen::Matrix3d::Identity();
};

// Rotation maximising tr(Rᵀ M) (orthogonal Procrustes with det R = +1): R = U diag(1, 1,
// det(U Vᵀ)) Vᵀ for M = U S Vᵀ.
Eigen::Matrix3d ProcrustesRotation(const Eigen::Matrix3d& M);

}  // namespace rk::pose

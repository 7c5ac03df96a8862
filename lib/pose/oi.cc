// Orthogonal iteration; equations and assumptions in oi.h.
#include "pose/oi.h"

#include <Eigen/Dense>
#include <cmath>

namespace rk::pose {

bool OiOptions::Check(const char** why) const {
  if (max_iterations < 1) {
    *why = "OI max_iterations must be >= 1";
    return false;
  }
  if (!(rotation_tol > 0.0)) {
    *why = "OI rotation tolerance must be > 0";
    return false;
  }
  if (!(error_tol >= 0.0)) {
    *why = "OI error tolerance must be >= 0";
    return false;
  }
  return true;
}

const char* OiTerminationName(OiTermination t) {
  switch (t) {
    case OiTermination::kConverged:
      return "converged";
    case OiTermination::kMaxIterations:
      return "max_iterations";
    case OiTermination::kDegenerate:
      return "degenerate";
  }
  return "?";
}

Eigen::Matrix3d ProcrustesRotation(const Eigen::Matrix3d& M) {
  // M = U S Vᵀ from the eigen-decomposition of MᵀM = V S² Vᵀ (closed-form 3×3 solver), with V
  // right-handed; u_k = M v_k / s_k for the two largest singular values and u3 = u1 × u2, so
  // R = U Vᵀ is proper and is the det-corrected Procrustes solution U diag(1, 1, ±1) Vᵀ
  // (the sign of s3 is absorbed by u3). Needs s2 > 0, i.e. M of rank ≥ 2: true for OI with a
  // non-collinear model; falls back to the Jacobi SVD otherwise or when s2 is tiny.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(M.transpose() * M);
  const Eigen::Vector3d& ev = es.eigenvalues();  // ascending
  if (es.info() == Eigen::Success && ev(1) > 1e-16 * ev(2) && ev(2) > 0.0) {
    const Eigen::Matrix3d& E = es.eigenvectors();
    const Eigen::Vector3d v1 = E.col(2), v2 = E.col(1);
    const Eigen::Vector3d v3 = v1.cross(v2);
    Eigen::Vector3d u1 = M * v1, u2 = M * v2;
    u1.normalize();
    u2 -= u1.dot(u2) * u1;
    u2.normalize();
    const Eigen::Vector3d u3 = u1.cross(u2);
    Eigen::Matrix3d R = u1 * v1.transpose() + u2 * v2.transpose() + u3 * v3.transpose();
    if (R.allFinite()) return R;
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0.0) U.col(2) = -U.col(2);  // proper rotation
  return U * V.transpose();
}

bool OrthogonalIteration::Set(std::span<const Eigen::Vector3d> rays, std::span<const Eigen::Vector3d> p_body) {
  n_ = 0;
  const std::size_t n = rays.size();
  if (n < 3 || p_body.size() != n) return false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : p_body) c += p;
  c /= static_cast<double>(n);
  centroid_ = c;

  Eigen::Matrix3d S = Eigen::Matrix3d::Zero(), scatter = Eigen::Matrix3d::Zero();
  for (auto& w : W_) w.setZero();
  Eigen::Matrix3d Yb[3][3];
  for (auto& row : Yb) {
    for (auto& b : row) b.setZero();
  }
  sum_p2_ = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& m = rays[i];
    if (!(m.z() > 0.0) || !m.allFinite()) return false;
    const Eigen::Matrix3d V = m * m.transpose() / m.squaredNorm();
    const Eigen::Vector3d q = p_body[i] - c;
    S += V;
    scatter += q * q.transpose();
    sum_p2_ += q.squaredNorm();
    for (int k = 0; k < 3; ++k) {
      W_[k] += q(k) * V;
      for (int l = k; l < 3; ++l) Yb[k][l] += (q(k) * q(l)) * V;
    }
  }
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < k; ++l) Yb[k][l] = Yb[l][k];
  }
  Finv_ = static_cast<double>(n) * Eigen::Matrix3d::Identity() - S;
  // n I − Σ V is positive definite unless all rays are parallel (n ≥ 2 distinct rays).
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(Finv_);
  if (!lu.isInvertible()) return false;
  F_ = lu.inverse();

  // Model scatter: principal axes, and the degenerate (collinear) case.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(scatter);
  // Eigen returns ascending eigenvalues: reorder descending.
  for (int k = 0; k < 3; ++k) {
    lambda_(k) = std::max(0.0, es.eigenvalues()(2 - k));
    axes_.col(k) = es.eigenvectors().col(2 - k);
  }
  if (axes_.determinant() < 0) axes_.col(2) = -axes_.col(2);
  if (!(lambda_(0) > 0.0) || lambda_(1) < 1e-12 * lambda_(0)) return false;  // collinear

  for (int j = 0; j < 3; ++j) {
    for (int k = 0; k < 3; ++k) {
      G_.block<3, 3>(3 * j, 3 * k) = Yb[j][k] + W_[j] * F_ * W_[k];
      Y_.block<3, 3>(3 * j, 3 * k) = Yb[j][k];
    }
  }
  n_ = static_cast<int>(n);
  return true;
}

Eigen::Vector3d OrthogonalIteration::TranslationCentred(const Eigen::Matrix3d& R) const {
  return F_ * (W_[0] * R.col(0) + W_[1] * R.col(1) + W_[2] * R.col(2));
}

Eigen::Vector3d OrthogonalIteration::Translation(const Eigen::Matrix3d& R) const {
  return TranslationCentred(R) - R * centroid_;
}

double OrthogonalIteration::ObjectError(const Eigen::Matrix3d& R) const {
  const Eigen::Map<const Eigen::Matrix<double, 9, 1>> r(R.data());
  const Eigen::Vector3d t = TranslationCentred(R);
  return std::max(0.0, sum_p2_ - r.dot(Y_ * r) - t.dot(Finv_ * t));
}

OiResult OrthogonalIteration::Solve(const Eigen::Matrix3d& R0, const OiOptions& options) const {
  OiResult res;
  if (n_ < 3) return res;  // kDegenerate
  Eigen::Matrix3d R = R0;
  double e_prev = options.error_tol > 0 ? ObjectError(R) : 0.0;
  res.termination = OiTermination::kMaxIterations;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::Map<const Eigen::Matrix<double, 9, 1>> r(R.data());
    Eigen::Matrix3d M;
    Eigen::Map<Eigen::Matrix<double, 9, 1>>(M.data()) = G_ * r;
    const Eigen::Matrix3d R_next = ProcrustesRotation(M);
    const double dR = (R_next - R).norm();
    R = R_next;
    res.iterations = it + 1;
    if (dR < options.rotation_tol) {
      res.termination = OiTermination::kConverged;
      break;
    }
    if (options.error_tol > 0) {
      const double e = ObjectError(R);
      if (std::abs(e_prev - e) < options.error_tol * sum_p2_) {
        res.termination = OiTermination::kConverged;
        break;
      }
      e_prev = e;
    }
  }
  res.R_cam_body = R;
  res.t_cam = Translation(R);
  res.object_error_m2 = ObjectError(R);
  return res;
}

}  // namespace rk::pose

// Weak-perspective starts for OI; method in pose_init.h.
#include "pose/pose_init.h"

#include <Eigen/Dense>
#include <cmath>

#include "pose/oi.h"

namespace rk::pose {
namespace {

// Principal axes (columns, descending eigenvalues, right-handed) and eigenvalues of the centred
// scatter of the model; false if collinear.
bool PrincipalAxes(std::span<const Eigen::Vector3d> p_body, Eigen::Vector3d* pbar, Eigen::Matrix3d* E,
                   Eigen::Vector3d* lambda) {
  *pbar = Eigen::Vector3d::Zero();
  for (const auto& p : p_body) *pbar += p;
  *pbar /= static_cast<double>(p_body.size());
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const auto& p : p_body) C += (p - *pbar) * (p - *pbar).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  for (int k = 0; k < 3; ++k) {
    (*lambda)(k) = std::max(0.0, es.eigenvalues()(2 - k));
    E->col(k) = es.eigenvectors().col(2 - k);
  }
  if (E->determinant() < 0) E->col(2) = -E->col(2);
  return (*lambda)(0) > 0.0 && (*lambda)(1) >= 1e-12 * (*lambda)(0);
}

// Similarity normalising 2-D points to centroid 0 and mean distance √2 (Hartley).
Eigen::Matrix3d Normaliser(const Eigen::Vector2d* pts, std::size_t n) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < n; ++i) c += pts[i];
  c /= static_cast<double>(n);
  double d = 0.0;
  for (std::size_t i = 0; i < n; ++i) d += (pts[i] - c).norm();
  d /= static_cast<double>(n);
  const double s = d > 0 ? std::sqrt(2.0) / d : 1.0;
  Eigen::Matrix3d T;
  T << s, 0, -s * c.x(), 0, s, -s * c.y(), 0, 0, 1;
  return T;
}

}  // namespace

Eigen::Matrix3d RotationBetween(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d a = from.normalized(), b = to.normalized();
  const Eigen::Vector3d v = a.cross(b);
  const double c = a.dot(b);
  const double s = v.norm();
  if (s < 1e-15) {
    if (c > 0) return Eigen::Matrix3d::Identity();
    // Opposite: rotate by π about any axis perpendicular to a.
    Eigen::Vector3d axis = a.cross(Eigen::Vector3d::UnitX());
    if (axis.norm() < 1e-6) axis = a.cross(Eigen::Vector3d::UnitY());
    axis.normalize();
    return 2.0 * axis * axis.transpose() - Eigen::Matrix3d::Identity();
  }
  Eigen::Matrix3d K;
  K << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return Eigen::Matrix3d::Identity() + K + K * K * ((1.0 - c) / (s * s));
}

WeakPerspectiveStart WeakPerspectiveInit(std::span<const Eigen::Vector3d> rays,
                                         std::span<const Eigen::Vector3d> p_body, double planar_ratio) {
  WeakPerspectiveStart out;
  const std::size_t n = rays.size();
  if (n < 3 || p_body.size() != n) return out;

  // 1. Virtual camera looking along the mean ray.
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (const auto& m : rays) {
    if (!(m.z() > 0.0)) return out;
    d += m.normalized();
  }
  const Eigen::Matrix3d R_virt_cam = RotationBetween(d, Eigen::Vector3d::UnitZ());

  // 2. Centred image points (virtual camera) and model in its principal axes.
  Eigen::Vector2d xbar = Eigen::Vector2d::Zero();
  Eigen::Vector3d pbar = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d mv = R_virt_cam * rays[i];
    if (!(mv.z() > 0.0)) return out;
    xbar += mv.head<2>() / mv.z();
    pbar += p_body[i];
  }
  xbar /= static_cast<double>(n);
  pbar /= static_cast<double>(n);
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const auto& p : p_body) C += (p - pbar) * (p - pbar).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  Eigen::Matrix3d E;
  Eigen::Vector3d lambda;
  for (int k = 0; k < 3; ++k) {
    lambda(k) = std::max(0.0, es.eigenvalues()(2 - k));
    E.col(k) = es.eigenvectors().col(2 - k);
  }
  if (E.determinant() < 0) E.col(2) = -E.col(2);
  if (!(lambda(0) > 0.0) || lambda(1) < 1e-12 * lambda(0)) return out;  // collinear model

  Eigen::Matrix<double, 2, 3> B = Eigen::Matrix<double, 2, 3>::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d mv = R_virt_cam * rays[i];
    const Eigen::Vector2d x = mv.head<2>() / mv.z() - xbar;
    B += x * (E.transpose() * (p_body[i] - pbar)).transpose();
  }

  Eigen::Matrix3d Rt;  // R̃: principal model frame → virtual camera
  out.planar = lambda(2) < planar_ratio * lambda(0);
  if (!out.planar) {
    Eigen::Matrix<double, 2, 3> A;
    for (int k = 0; k < 3; ++k) A.col(k) = B.col(k) / lambda(k);
    const Eigen::JacobiSVD<Eigen::Matrix<double, 2, 3>> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Matrix<double, 2, 3> Q = svd.matrixU() * svd.matrixV().leftCols<2>().transpose();
    Rt.row(0) = Q.row(0);
    Rt.row(1) = Q.row(1);
    out.scale = 0.5 * (svd.singularValues()(0) + svd.singularValues()(1));
  } else {
    const Eigen::Vector2d a1(B(0, 0) / lambda(0), B(0, 1) / lambda(1));
    const Eigen::Vector2d a2(B(1, 0) / lambda(0), B(1, 1) / lambda(1));
    const double u = a1.squaredNorm() - a2.squaredNorm();
    const double k = a1.dot(a2);
    const double c1sq = 0.5 * (-u + std::sqrt(u * u + 4.0 * k * k));
    double c1 = std::sqrt(std::max(0.0, c1sq)), c2;
    if (c1 > 1e-12 * std::max(a1.norm(), a2.norm())) {
      c2 = -k / c1;
    } else {
      c1 = 0.0;
      c2 = std::sqrt(std::max(0.0, u));
    }
    Eigen::Vector3d r1(a1.x(), a1.y(), c1), r2(a2.x(), a2.y(), c2);
    out.scale = 0.5 * (r1.norm() + r2.norm());
    if (!(r1.norm() > 0.0) || !(r2.norm() > 0.0)) {
      r1 = Eigen::Vector3d::UnitX();
      r2 = Eigen::Vector3d::UnitY();
    }
    Rt.row(0) = r1.normalized().transpose();
    Rt.row(1) = r2.transpose();
  }
  // Orthonormalise the two rows (Gram–Schmidt) and complete the right-handed frame.
  Eigen::Vector3d r1 = Rt.row(0).transpose().normalized();
  Eigen::Vector3d r2 = Rt.row(1).transpose();
  r2 = (r2 - r1.dot(r2) * r1);
  if (r2.norm() < 1e-12) r2 = r1.unitOrthogonal();
  r2.normalize();
  Rt.row(0) = r1.transpose();
  Rt.row(1) = r2.transpose();
  Rt.row(2) = r1.cross(r2).transpose();

  const Eigen::Matrix3d S = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  out.R_cam_body[0] = R_virt_cam.transpose() * Rt * E.transpose();
  out.R_cam_body[1] = R_virt_cam.transpose() * (S * Rt * S) * E.transpose();
  out.ok = true;
  return out;
}

WeakPerspectiveStart HomographyInit(std::span<const Eigen::Vector3d> rays, std::span<const Eigen::Vector3d> p_body) {
  WeakPerspectiveStart out;
  const std::size_t n = rays.size();
  constexpr std::size_t kMax = 256;  // stack buffers; larger sets use their first kMax points
  if (n < 4 || p_body.size() != n) return out;
  Eigen::Vector3d pbar, lambda;
  Eigen::Matrix3d E;
  if (!PrincipalAxes(p_body, &pbar, &E, &lambda)) return out;
  const std::size_t m = std::min(n, kMax);
  Eigen::Vector2d q[kMax], x[kMax];
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < m; ++i) {
    if (!(rays[i].z() > 0.0)) return out;
    q[i] = (E.transpose() * (p_body[i] - pbar)).head<2>();
    x[i] = rays[i].head<2>() / rays[i].z();
    d += rays[i].normalized();
  }
  const Eigen::Matrix3d Tq = Normaliser(q, m), Tx = Normaliser(x, m);
  Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::Vector3d a = Tq * Eigen::Vector3d(q[i].x(), q[i].y(), 1.0);
    const Eigen::Vector3d b = Tx * Eigen::Vector3d(x[i].x(), x[i].y(), 1.0);
    Eigen::Matrix<double, 9, 1> r1, r2;
    r1 << -a.x(), -a.y(), -1.0, 0.0, 0.0, 0.0, b.x() * a.x(), b.x() * a.y(), b.x();
    r2 << 0.0, 0.0, 0.0, -a.x(), -a.y(), -1.0, b.y() * a.x(), b.y() * a.y(), b.y();
    AtA.noalias() += r1 * r1.transpose() + r2 * r2.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> es(AtA);
  if (es.info() != Eigen::Success) return out;
  const Eigen::Matrix<double, 9, 1> h = es.eigenvectors().col(0);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  const Eigen::Matrix3d H = Tx.inverse() * Hn * Tq;
  const double norm = H.col(0).norm() + H.col(1).norm();
  if (!(norm > 0.0) || !H.allFinite()) return out;
  double lam = 2.0 / norm;
  if (H(2, 2) * lam < 0.0) lam = -lam;  // t_z > 0: the target in front of the camera
  const Eigen::Vector3d r1 = lam * H.col(0), r2 = lam * H.col(1);
  Eigen::Matrix3d A;
  A.col(0) = r1;
  A.col(1) = r2;
  A.col(2) = r1.cross(r2);
  const Eigen::Matrix3d R_cam_principal = ProcrustesRotation(A);
  out.scale = 1.0 / (lam * H(2, 2));

  // Mirror about the virtual image plane (see WeakPerspectiveInit).
  const Eigen::Matrix3d R_virt_cam = RotationBetween(d, Eigen::Vector3d::UnitZ());
  const Eigen::Matrix3d S = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  const Eigen::Matrix3d Rt = R_virt_cam * R_cam_principal;
  out.R_cam_body[0] = R_cam_principal * E.transpose();
  out.R_cam_body[1] = R_virt_cam.transpose() * (S * Rt * S) * E.transpose();
  out.planar = true;
  out.ok = out.R_cam_body[0].allFinite() && out.R_cam_body[1].allFinite();
  return out;
}

}  // namespace rk::pose

// Levenberg–Marquardt reprojection polish; model in reproj_refine.h.
#include "pose/reproj_refine.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "numeric/levenberg_marquardt.h"

namespace rk::pose {

namespace {

// JᵀJ and Jᵀr of the σ-weighted pixel residuals (model in reproj_refine.h).
void NormalEquations(std::span<const Eigen::Vector2d> xn, std::span<const Eigen::Vector3d> p_body,
                     std::span<const double> sigma_px, double fx, double fy, const Eigen::Matrix3d& Rc,
                     const Eigen::Vector3d& tc, Eigen::Matrix<double, 6, 6>* H, Eigen::Matrix<double, 6, 1>* g) {
  H->setZero();
  g->setZero();
  for (std::size_t i = 0; i < xn.size(); ++i) {
    const Eigen::Vector3d Rp = Rc * p_body[i];
    const Eigen::Vector3d X = Rp + tc;
    const double iz = 1.0 / X.z();
    const double w = sigma_px.empty() ? 1.0 : 1.0 / sigma_px[i];
    // d(projection)/dX, rows scaled to pixels and by 1/σ.
    Eigen::Matrix<double, 2, 3> P;
    P << w * fx * iz, 0.0, -w * fx * X.x() * iz * iz, 0.0, w * fy * iz, -w * fy * X.y() * iz * iz;
    Eigen::Matrix3d Rx;  // −[Rp]×
    Rx << 0, Rp.z(), -Rp.y(), -Rp.z(), 0, Rp.x(), Rp.y(), -Rp.x(), 0;
    Eigen::Matrix<double, 2, 6> J;
    J.leftCols<3>() = P * Rx;
    J.rightCols<3>() = P;
    const Eigen::Vector2d r(w * fx * (X.x() * iz - xn[i].x()), w * fy * (X.y() * iz - xn[i].y()));
    H->noalias() += J.transpose() * J;
    g->noalias() += J.transpose() * r;
  }
}

}  // namespace

Eigen::Matrix<double, 6, 6> ReprojectionInformation(std::span<const Eigen::Vector2d> xn,
                                                    std::span<const Eigen::Vector3d> p_body,
                                                    std::span<const double> sigma_px, double fx, double fy,
                                                    const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Matrix<double, 6, 6> H;
  Eigen::Matrix<double, 6, 1> g;
  NormalEquations(xn, p_body, sigma_px, fx, fy, R, t, &H, &g);
  return H;
}

Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& w) {
  const double th2 = w.squaredNorm();
  Eigen::Matrix3d K;
  K << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  double a, b;
  if (th2 < 1e-12) {  // series to O(θ⁴): exact to double precision here
    a = 1.0 - th2 / 6.0;
    b = 0.5 - th2 / 24.0;
  } else {
    const double th = std::sqrt(th2);
    a = std::sin(th) / th;
    b = (1.0 - std::cos(th)) / th2;
  }
  return Eigen::Matrix3d::Identity() + a * K + b * K * K;
}

double ReprojectionChi2(std::span<const Eigen::Vector2d> xn, std::span<const Eigen::Vector3d> p_body,
                        std::span<const double> sigma_px, double fx, double fy, const Eigen::Matrix3d& R,
                        const Eigen::Vector3d& t, bool* in_front, double* sse_px2) {
  double chi2 = 0.0, sse = 0.0;
  bool front = true;
  for (std::size_t i = 0; i < xn.size(); ++i) {
    const Eigen::Vector3d X = R * p_body[i] + t;
    if (!(X.z() > 0.0)) {
      front = false;
      continue;
    }
    const double rx = fx * (X.x() / X.z() - xn[i].x());
    const double ry = fy * (X.y() / X.z() - xn[i].y());
    const double r2 = rx * rx + ry * ry;
    const double s = sigma_px.empty() ? 1.0 : sigma_px[i];
    sse += r2;
    chi2 += r2 / (s * s);
  }
  if (in_front) *in_front = front;
  if (sse_px2) *sse_px2 = sse;
  return front ? chi2 : std::numeric_limits<double>::infinity();
}

ReprojRefineResult RefineReprojection(std::span<const Eigen::Vector2d> xn, std::span<const Eigen::Vector3d> p_body,
                                      std::span<const double> sigma_px, double fx, double fy,
                                      const Eigen::Matrix3d& R0, const Eigen::Vector3d& t0,
                                      const ReprojRefineOptions& options) {
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  ReprojRefineResult res;
  Eigen::Matrix3d R = R0;
  Eigen::Vector3d t = t0;
  bool front = false;
  double chi2 = ReprojectionChi2(xn, p_body, sigma_px, fx, fy, R, t, &front);

  if (!front || xn.size() < 3) {
    res.R_cam_body = R;
    res.t_cam = t;
    res.chi2 = chi2;
    res.in_front = front;
    return res;
  }
  // Levenberg–Marquardt on (rotation increment, translation): R ← Exp(δω) R, t ← t + δt; a candidate
  // with a point behind the camera is rejected. Converged: no step lowers χ², or the step is below
  // step_tol (rotation in rad plus translation relative to |t|).
  struct Polish {
    std::span<const Eigen::Vector2d> xn;
    std::span<const Eigen::Vector3d> p_body;
    std::span<const double> sigma_px;
    double fx, fy, t_scale, step_tol;
    Eigen::Matrix3d R, R_new;
    Eigen::Vector3d t, t_new;
    bool TryStep(const Vec6& delta, double* chi2) {
      R_new = ExpSo3(delta.head<3>()) * R;
      t_new = t + delta.tail<3>();
      bool front = false;
      *chi2 = ReprojectionChi2(xn, p_body, sigma_px, fx, fy, R_new, t_new, &front);
      return front;
    }
    void Accept() {
      R = R_new;
      t = t_new;
    }
    bool Linearize(Mat6* H, Vec6* g) {
      NormalEquations(xn, p_body, sigma_px, fx, fy, R, t, H, g);
      return true;
    }
    bool Converged(const Vec6& delta, double, double) const {
      return delta.head<3>().norm() + delta.tail<3>().norm() / t_scale < step_tol;
    }
  } polish{xn, p_body, sigma_px, fx, fy, std::max(t.norm(), 1e-9), options.step_tol, R, R, t, t};
  Mat6 H;
  Vec6 g;
  polish.Linearize(&H, &g);
  const numeric::LmDamping damping{.initial = 1e-8, .diagonal_floor = 1e-30, .increase = 10.0,
                                   .decrease = 0.1, .min = 1e-12, .max_tries = 10, .accept_equal_cost = true};
  const numeric::LmSummary lm =
      numeric::LevenbergMarquardt<6>(polish, chi2, damping, options.max_iterations, &H, &g);
  // A non-finite step means no step is left: converged at the current point.
  res.converged =
      lm.status == numeric::LmStatus::kConverged || lm.status == numeric::LmStatus::kNonFiniteStep;
  res.iterations = lm.iterations;
  res.R_cam_body = polish.R;
  res.t_cam = polish.t;
  res.chi2 = ReprojectionChi2(xn, p_body, sigma_px, fx, fy, polish.R, polish.t, &res.in_front, &res.sse_px2);
  res.information = H;
  return res;
}

}  // namespace rk::pose

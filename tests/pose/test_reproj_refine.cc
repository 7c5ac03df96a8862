// Reprojection polish and its covariance (pose/reproj_refine.h) against simulated truth
// (sim/attitude_problems.h).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "geo/angles.h"
#include "pose/oi.h"
#include "pose/pnp.h"
#include "pose/reproj_refine.h"
#include "pose_test_util.h"
#include "sim/attitude_problems.h"

namespace rk::pose {
namespace {

using sim::PnpGeometry;
using sim::PnpProblem;
using testing::kJacobianRel;
using testing::Normalised;
using testing::Problem;

// Residuals of the reprojection polish (same definition as reproj_refine.h), for numerical
// derivatives.
Eigen::VectorXd Residuals(const std::vector<Eigen::Vector2d>& xn, const std::vector<Eigen::Vector3d>& p, double fx,
                          double fy, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::VectorXd r(2 * xn.size());
  for (std::size_t i = 0; i < xn.size(); ++i) {
    const Eigen::Vector3d X = R * p[i] + t;
    r(2 * i) = fx * (X.x() / X.z() - xn[i].x());
    r(2 * i + 1) = fy * (X.y() / X.z() - xn[i].y());
  }
  return r;
}

TEST(ReprojRefine, AnalyticInformationMatchesNumericalJacobian) {
  const PnpProblem pb = Problem(PnpGeometry::kBox, 2, 0.5, 7, 7);
  const auto xn = Normalised(pb, true);
  const ReprojRefineResult r = RefineReprojection(xn, pb.p_body, {}, pb.fx, pb.fy, pb.R_cam_body, pb.t_cam);
  ASSERT_TRUE(r.converged);
  ASSERT_TRUE(r.in_front);
  const double h = 1e-6;
  Eigen::MatrixXd J(2 * xn.size(), 6);
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d(k) = h;
    auto at = [&](double s) {
      return Residuals(xn, pb.p_body, pb.fx, pb.fy, ExpSo3(s * d.head<3>()) * r.R_cam_body,
                       r.t_cam + s * d.tail<3>());
    };
    J.col(k) = (at(1.0) - at(-1.0)) / (2 * h);
  }
  const Eigen::MatrixXd H = J.transpose() * J;
  EXPECT_LT((H - r.information).norm(), kJacobianRel * H.norm());
  // At the minimum the gradient Jᵀr vanishes.
  const Eigen::VectorXd g = J.transpose() * Residuals(xn, pb.p_body, pb.fx, pb.fy, r.R_cam_body, r.t_cam);
  EXPECT_LT(g.norm(), 1e-6 * std::sqrt(H.norm()));
}

TEST(ReprojRefine, CovarianceMatchesMonteCarloScatter) {
  // Same pose and model, 400 noise draws at σ = 0.5 px; the spread of the estimates must match
  // σ²(JᵀJ)⁻¹ within sampling error (std of a std estimate with 400 draws ≈ 3.5 %: ±15 % is
  // > 4σ).
  constexpr double kStdRatioTol = 0.15;
  const PnpProblem base = Problem(PnpGeometry::kNarrow, 7, 0.0, 8, 8);
  const double sigma = 0.5;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> g(0, sigma);
  std::vector<Eigen::Matrix<double, 6, 1>> err;
  Eigen::Matrix<double, 6, 6> info = Eigen::Matrix<double, 6, 6>::Zero();
  PnpSolver solver;
  const std::vector<double> sig(base.p_body.size(), sigma);
  for (int run = 0; run < 400; ++run) {
    std::vector<Eigen::Vector2d> xn;
    for (const auto& px : base.px_true) {
      xn.emplace_back((px.x() + g(rng) - base.cx) / base.fx, (px.y() + g(rng) - base.cy) / base.fy);
    }
    const PnpResult r = solver.Solve(xn, base.p_body, sig, base.fx, base.fy);
    ASSERT_TRUE(r.ok);
    const Eigen::Matrix3d dR = r.best.R_cam_body * base.R_cam_body.transpose();
    const Eigen::AngleAxisd aa(dR);
    Eigen::Matrix<double, 6, 1> e;
    e.head<3>() = aa.angle() * aa.axis();
    e.tail<3>() = r.best.t_cam - base.t_cam;
    err.push_back(e);
    info = r.best.information;
  }
  const Eigen::Matrix<double, 6, 6> cov = info.inverse();
  for (int k = 0; k < 6; ++k) {
    double s2 = 0;
    for (const auto& e : err) s2 += e(k) * e(k);
    const double std_mc = std::sqrt(s2 / static_cast<double>(err.size()));
    EXPECT_NEAR(std_mc / std::sqrt(cov(k, k)), 1.0, kStdRatioTol) << "component " << k;
  }
}

}  // namespace
}  // namespace rk::pose

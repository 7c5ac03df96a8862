// Unscented pieces (ukf.h), innovation covariance (adaptive_noise.h) and the golden test: on the linear
// constant-acceleration model without adaptation the AUKF cycle of aukf_series.h equals the linear
// Kalman filter, state and covariance, at both half steps.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "filter/adaptive_noise.h"
#include "filter/aukf_series.h"
#include "filter/ukf.h"
#include "geo/angles.h"

namespace rk::filter {
namespace {

using ukf::StateMat;
using ukf::StateVec;

constexpr double kGoldenTolerance = 1e-9;  // relative; the two filters differ only by rounding
constexpr double kExactTolerance = 1e-12;  // identities that hold to rounding on O(1) numbers

StateMat RandomSpd(int n, std::mt19937* rng) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = g(*rng);
  StateMat P = A * A.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
  return P;
}

TEST(Ukf, WeightsSumToOne) {
  for (double kappa : {0.0, 1.0, 3.0, -2.0}) {
    const auto w = ukf::MakeWeights(9, kappa);
    EXPECT_NEAR(w.sum(), 1.0, kExactTolerance);
    EXPECT_NEAR(w(0), kappa / (9 + kappa), kExactTolerance);
    EXPECT_NEAR(w(5), 1.0 / (2 * (9 + kappa)), kExactTolerance);
  }
}

TEST(Ukf, UnscentedTransformOfLinearMapIsExact) {
  std::mt19937 rng(3);
  const int n = 6;
  StateVec x = StateVec::Random(n);
  StateMat P = RandomSpd(n, &rng);
  ukf::SigmaMat X;
  ASSERT_TRUE(ukf::SigmaPoints(x, P, 1.0, &X));
  const auto w = ukf::MakeWeights(n, 1.0);
  const ukf::AngleRows none;
  StateMat A = StateMat::Random(n, n);
  ukf::SigmaMat Y = A * X;
  StateVec m = ukf::SigmaMean(Y, w, none);
  ukf::SigmaMat D;
  ukf::SigmaResiduals(Y, m, none, &D);
  StateMat Py = ukf::SigmaCovariance(D, w);
  EXPECT_LT((m - A * x).norm(), kExactTolerance * 10);
  EXPECT_LT((Py - A * P * A.transpose()).norm(), 1e-10 * (A * P * A.transpose()).norm());
}

TEST(Ukf, SigmaPointsRejectIndefinite) {
  StateVec x = StateVec::Zero(2);
  StateMat P(2, 2);
  P << 1, 2, 2, 1;  // eigenvalues 3, −1
  ukf::SigmaMat X;
  EXPECT_FALSE(ukf::SigmaPoints(x, P, 1.0, &X));
}

TEST(Ukf, AngleMeanAcrossPi) {
  // Points at 179°, −179° (= 181°) and 180°: the mean is 180°, not 0°.
  ukf::SigmaMat X(1, 3);
  X << geo::DegToRad(180.0), geo::DegToRad(179.0), geo::DegToRad(-179.0);
  ukf::SigmaWeights w(3);
  w << 0.0, 0.5, 0.5;
  ukf::AngleRows angles;
  angles.Add(0);
  const StateVec m = ukf::SigmaMean(X, w, angles);
  EXPECT_NEAR(std::abs(geo::RadToDeg(m(0))), 180.0, 1e-9);
  ukf::SigmaMat D;
  ukf::SigmaResiduals(X, m, angles, &D);
  EXPECT_NEAR(geo::RadToDeg(std::abs(D(0, 1))), 1.0, 1e-9);
  EXPECT_NEAR(geo::RadToDeg(std::abs(D(0, 2))), 1.0, 1e-9);
  // The same without the angle flag: the linear mean is 0°, the wrong answer for an angle.
  const StateVec lin = ukf::SigmaMean(X, w, ukf::AngleRows{});
  EXPECT_NEAR(geo::RadToDeg(lin(0)), 0.0, 1e-9);
}

TEST(Ukf, RepairSpdClampsAndCounts) {
  StateMat A(2, 2);
  A << 1, 2, 2, 1;
  StateVec scale(2);
  scale << 1.0, 10.0;  // second component in other units
  EXPECT_TRUE(ukf::RepairSpd(&A, scale, 1e-6));
  const Eigen::MatrixXd A_dense = A;
  Eigen::LLT<Eigen::MatrixXd> llt(A_dense);
  EXPECT_EQ(llt.info(), Eigen::Success);
  StateMat B = StateMat::Identity(2, 2);
  EXPECT_FALSE(ukf::RepairSpd(&B, scale, 1e-6));  // already SPD (0.01 ≥ 1e-6 in scaled space): unchanged
  EXPECT_EQ(B, StateMat::Identity(2, 2));
}

TEST(Ukf, WhiteJerkQComposesOverSubSteps) {
  // Φ(b) Q(a) Φ(b)ᵀ + Q(b) = Q(a + b): the two half steps give the one-step covariance.
  const double a = 0.03, b = 0.02, q = 7.0;
  Eigen::Matrix3d Phi;
  Phi << 1, b, b * b / 2, 0, 1, b, 0, 0, 1;
  const Eigen::Matrix3d lhs = Phi * WhiteJerkQ(a, q) * Phi.transpose() + WhiteJerkQ(b, q);
  EXPECT_LT((lhs - WhiteJerkQ(a + b, q)).norm(), kExactTolerance * WhiteJerkQ(a + b, q).norm());
}

TEST(AdaptiveNoise, WindowAndFadingMatchDirectSums) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  AdaptiveNoiseOptions wo;
  wo.window = 4;
  AdaptiveNoiseOptions fo;
  fo.memory = AdaptMemory::kFading;
  fo.fading = 0.8;
  InnovationCovariance cw, cf;
  cw.Reset(2, wo);
  cf.Reset(2, fo);
  std::vector<ukf::MeasVec> ds;
  for (int k = 0; k < 9; ++k) {
    ukf::MeasVec d(2);
    d << g(rng), g(rng);
    ds.push_back(d);
    ukf::MeasMat hph = ukf::MeasMat::Identity(2, 2) * (k + 1.0);
    cw.Add(d, hph);
    cf.Add(d, hph);
  }
  Eigen::Matrix2d Cw = Eigen::Matrix2d::Zero(), Cf = Eigen::Matrix2d::Zero();
  double wsum = 0;
  for (int k = 5; k < 9; ++k) Cw += ds[static_cast<std::size_t>(k)] * ds[static_cast<std::size_t>(k)].transpose();
  Cw /= 4;
  for (int k = 0; k < 9; ++k) {
    const double lw = std::pow(0.8, 8 - k);
    Cf += lw * ds[static_cast<std::size_t>(k)] * ds[static_cast<std::size_t>(k)].transpose();
    wsum += lw;
  }
  Cf /= wsum;
  EXPECT_LT((Eigen::Matrix2d(cw.C()) - Cw).norm(), kExactTolerance);
  EXPECT_LT((Eigen::Matrix2d(cf.C()) - Cf).norm(), kExactTolerance);
  EXPECT_NEAR(cw.HPH()(0, 0), (6 + 7 + 8 + 9) / 4.0, kExactTolerance);
  EXPECT_TRUE(cw.Ready());
  EXPECT_EQ(fo.Warmup(), 5);
}

// Linear Kalman filter on the same model (Φ, white-jerk Q, partial H), started from the AUKF's node 0; for the
// per-column-block unscented transform (the default without adaptation) and the joint 9-state one.
void GoldenEqualsLinearKalmanFilter(bool joint_transform) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.03, 0.07);
  Series s;
  s.source = "golden";
  s.columns = {"x_m", "y_m", "z_m"};
  s.is_angle = {false, false, false};
  const int N = 120, m = 3, n = 9;
  s.values.resize(N, m);
  double t = 0;
  for (int k = 0; k < N; ++k) {
    s.t_s.push_back(t);
    s.line.push_back(static_cast<std::size_t>(k + 2));
    for (int c = 0; c < m; ++c) s.values(k, c) = std::sin(0.7 * t + c) * (c + 1) + 0.01 * g(rng);
    t += u(rng);  // irregular sampling
  }
  s.values(40, 1) = std::numeric_limits<double>::quiet_NaN();  // partial update
  for (int c = 0; c < m; ++c) s.values(70, c) = std::numeric_limits<double>::quiet_NaN();  // no update
  AukfOptions opt;
  opt.adapt.mode = AdaptMode::kNone;
  opt.meas_sigma = {0.01, 0.02, 0.015};
  opt.q = {3.0, 1.0, 0.5};
  opt.lead = 0.4;
  opt.kappa = 2.0;
  opt.keep_covariance = true;
  opt.joint_transform = joint_transform;
  const AukfResult r = RunAukf(s, opt);
  ASSERT_EQ(r.t_s.size(), static_cast<std::size_t>(2 * N - 1));
  EXPECT_EQ(r.partial_updates, 1u);
  EXPECT_EQ(r.skipped_updates, 1u);
  EXPECT_EQ(r.status[140], AukfStatus::kPredicted);

  Eigen::VectorXd x = r.x_filter.col(0);
  Eigen::MatrixXd P = r.FilterCovariance(0);
  auto predict = [&](double tau) {
    Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(n, n), Q = Eigen::MatrixXd::Zero(n, n);
    for (int c = 0; c < m; ++c) {
      Phi.block<3, 3>(3 * c, 3 * c) << 1, tau, tau * tau / 2, 0, 1, tau, 0, 0, 1;
      Q.block<3, 3>(3 * c, 3 * c) = WhiteJerkQ(tau, opt.q[static_cast<std::size_t>(c)]);
    }
    x = Phi * x;
    P = Phi * P * Phi.transpose() + Q;
  };
  auto expect_near = [&](std::size_t node) {
    const Eigen::VectorXd xu = r.x_filter.col(static_cast<Eigen::Index>(node));
    const Eigen::MatrixXd Pu = r.FilterCovariance(node);
    for (int i = 0; i < n; ++i) {
      ASSERT_NEAR(xu(i), x(i), kGoldenTolerance * std::max(1.0, std::abs(x(i)))) << "node " << node << " x" << i;
      for (int j = 0; j < n; ++j) {
        ASSERT_NEAR(Pu(i, j), P(i, j), kGoldenTolerance * std::max(1.0, std::abs(P(i, j))))
            << "node " << node << " P" << i << j;
      }
    }
  };
  for (int k = 1; k < N; ++k) {
    const double tau = s.t_s[static_cast<std::size_t>(k)] - s.t_s[static_cast<std::size_t>(k - 1)];
    predict(opt.lead * tau);
    expect_near(static_cast<std::size_t>(2 * k - 1));
    predict(tau - opt.lead * tau);
    std::vector<int> a;
    for (int c = 0; c < m; ++c)
      if (std::isfinite(s.values(k, c))) a.push_back(c);
    if (!a.empty()) {
      const int ma = static_cast<int>(a.size());
      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(ma, n), R = Eigen::MatrixXd::Zero(ma, ma);
      Eigen::VectorXd z(ma);
      for (int i = 0; i < ma; ++i) {
        H(i, 3 * a[static_cast<std::size_t>(i)]) = 1;
        R(i, i) = std::pow(opt.meas_sigma[static_cast<std::size_t>(a[static_cast<std::size_t>(i)])], 2);
        z(i) = s.values(k, a[static_cast<std::size_t>(i)]);
      }
      const Eigen::MatrixXd S = H * P * H.transpose() + R;
      const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
      x += K * (z - H * x);
      P = (Eigen::MatrixXd::Identity(n, n) - K * H) * P;
      P = 0.5 * (P + P.transpose()).eval();
    }
    expect_near(static_cast<std::size_t>(2 * k));
  }
  EXPECT_EQ(r.p_repairs, 0u);
}

TEST(Aukf, GoldenEqualsLinearKalmanFilterAtBothHalfSteps) {
  {
    SCOPED_TRACE("per-column blocks");
    GoldenEqualsLinearKalmanFilter(false);
  }
  {
    SCOPED_TRACE("joint transform");
    GoldenEqualsLinearKalmanFilter(true);
  }
}

// The per-column-block transform and the joint one give the same filter and smoother, with angles through
// ±180°, a partial and an empty row, irregular sampling.
TEST(Aukf, BlockTransformEqualsJointTransform) {
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  Series s;
  s.source = "blocks";
  s.columns = {"yaw_deg", "x_m"};
  s.is_angle = {true, false};
  const int N = 150;
  s.values.resize(N, 2);
  double t = 0;
  for (int k = 0; k < N; ++k) {
    s.t_s.push_back(t);
    s.line.push_back(static_cast<std::size_t>(k + 2));
    s.values(k, 0) = geo::WrapPi(3.0 + 0.4 * t + 0.3 * std::sin(2 * t) + 0.002 * g(rng));  // crosses ±π
    s.values(k, 1) = std::cos(t) + 0.01 * g(rng);
    t += 0.04 + 0.02 * (k % 3);
  }
  s.values(50, 1) = std::numeric_limits<double>::quiet_NaN();
  s.values(90, 0) = s.values(90, 1) = std::numeric_limits<double>::quiet_NaN();
  AukfOptions opt;
  opt.smooth = true;
  opt.keep_covariance = true;
  const AukfResult a = RunAukf(s, opt);
  opt.joint_transform = true;
  const AukfResult b = RunAukf(s, opt);
  ASSERT_EQ(a.t_s.size(), b.t_s.size());
  constexpr double kSameTolerance = 1e-9;  // rounding only
  for (std::size_t j = 0; j < a.t_s.size(); ++j) {
    const Eigen::Index jc = static_cast<Eigen::Index>(j);
    for (int i = 0; i < 6; ++i) {
      const double sc = std::max(1.0, std::abs(b.x_filter(i, jc)));
      EXPECT_NEAR(i == 0 ? geo::AngleDiff(a.x_filter(i, jc), b.x_filter(i, jc)) : a.x_filter(i, jc) - b.x_filter(i, jc),
                  0.0, kSameTolerance * sc);
      EXPECT_NEAR(i == 0 ? geo::AngleDiff(a.x_smooth(i, jc), b.x_smooth(i, jc)) : a.x_smooth(i, jc) - b.x_smooth(i, jc),
                  0.0, kSameTolerance * std::max(1.0, std::abs(b.x_smooth(i, jc))));
      EXPECT_NEAR(a.sd_smooth(i, jc), b.sd_smooth(i, jc), kSameTolerance * std::max(1.0, b.sd_smooth(i, jc)));
    }
    const ukf::StateMat Pa = a.FilterCovariance(j), Pb = b.FilterCovariance(j);
    EXPECT_LT((Pa - Pb).norm(), kSameTolerance * std::max(1.0, Pb.norm())) << "node " << j;
  }
}

}  // namespace
}  // namespace rk::filter

// Unscented pieces (filter/ukf.h): weights, sigma points, the unscented transform, angle means, covariance
// repair and the white-jerk process noise.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "filter/ukf.h"
#include "geo/angles.h"
#include "test_tolerances.h"

namespace rk::filter {
namespace {

using ukf::StateMat;
using ukf::StateVec;

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

}  // namespace
}  // namespace rk::filter

// Singer model (track/singer.h): Ψ and Q against the matrix exponential and
// numerical integration of the continuous model, series vs closed form, and
// filter consistency (NEES) on a simulated Singer process.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

#include "track/singer.h"

namespace rk::track {
namespace {

// Continuous model matrix F of [u, u', u''] with u''' = −a u'' + w.
Eigen::Matrix3d F(double a) {
  Eigen::Matrix3d f;
  f << 0, 1, 0, 0, 0, 1, 0, 0, -a;
  return f;
}

// Q by composite Simpson integration of q c(s) c(s)ᵀ, c(s) = exp(F s) e3.
Eigen::Matrix3d QNumeric(double T, double a, double q) {
  const int n = 2000;  // even
  const double h = T / n;
  Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector3d c = (F(a) * (i * h)).exp().col(2);
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    Q += w * q * c * c.transpose();
  }
  return Q * h / 3.0;
}

// Element-wise relative error, each entry scaled by √(Q_ii Q_jj) (the natural
// size of an off-diagonal entry).
double RelErr(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  double e = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) e = std::max(e, std::fabs(A(i, j) - B(i, j)) / std::sqrt(B(i, i) * B(j, j)));
  return e;
}

// Simpson with 2000 panels: error ~ (T/2000)^4 relative; matrix exponential ~1e-15.
constexpr double kPsiTol = 1e-12;
constexpr double kQNumericTol = 1e-9;
// Series vs closed form in their common range (aT ∈ [0.3, 3]): the closed form
// loses ~(1/aT)^5·eps there at worst → ≤ 1e-11.
constexpr double kSeriesClosedTol = 1e-10;

TEST(Singer, TransitionMatchesMatrixExponential) {
  for (double aT : {1e-6, 1e-3, 0.1, 0.5, 0.99, 1.0, 2.0, 10.0}) {
    for (double T : {0.05, 1.0, 3.0}) {
      const double a = aT / T;
      const Eigen::Matrix3d expm = (F(a) * T).exp();
      const Eigen::Matrix3d psi = SingerTransition(T, a);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double scale = std::max(std::fabs(expm(i, j)), 1e-300);
          EXPECT_LE(std::fabs(psi(i, j) - expm(i, j)) / scale, kPsiTol) << "aT=" << aT << " T=" << T << " (" << i << j << ")";
        }
    }
  }
  // The paper's eq. 9 squares (aT − 1 + e^{−aT}) and (1 − e^{−aT}); ours must not.
  const double a = 2.0, T = 1.0;
  EXPECT_NEAR(SingerTransition(T, a)(0, 2), (a * T - 1 + std::exp(-a * T)) / (a * a), 1e-15);
}

TEST(Singer, ProcessNoiseMatchesNumericalIntegration) {
  for (double aT : {1e-6, 1e-3, 0.1, 0.5, 1.0, 2.0, 10.0}) {
    const double T = 0.5, a = aT / T, sigma_m = 3.0, q = 2 * a * sigma_m * sigma_m;
    const Eigen::Matrix3d Q = SingerProcessNoise(T, a, q);
    const Eigen::Matrix3d Qn = QNumeric(T, a, q);
    EXPECT_LE(RelErr(Q, Qn), kQNumericTol) << "aT=" << aT << "\n" << Q << "\n" << Qn;
    // Symmetric, positive definite.
    EXPECT_EQ((Q - Q.transpose()).norm(), 0.0);
    EXPECT_EQ(Q.llt().info(), Eigen::Success) << "aT=" << aT;
  }
}

TEST(Singer, ProcessNoiseMatchesVanLoan) {
  // Van Loan: exp([[−F, G q Gᵀ], [0, Fᵀ]] T) = [[·, Ψ⁻¹Q], [0, Ψᵀ]].
  for (double aT : {1e-6, 0.2, 1.0, 10.0}) {
    const double T = 1.0, a = aT / T, q = 2 * a * 4.0;
    Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
    M.block<3, 3>(0, 0) = -F(a);
    M(2, 5) = q;
    M.block<3, 3>(3, 3) = F(a).transpose();
    const Eigen::Matrix<double, 6, 6> E = (M * T).exp();
    const Eigen::Matrix3d psi = E.block<3, 3>(3, 3).transpose();
    const Eigen::Matrix3d Qvl = psi * E.block<3, 3>(0, 3);
    EXPECT_LE(RelErr(SingerProcessNoise(T, a, q), Qvl), 1e-8) << "aT=" << aT;
  }
}

TEST(Singer, SeriesAndClosedFormAgree) {
  for (double aT : {0.3, 0.6, 0.9, 1.0, 1.5}) {
    const double T = 0.05, a = aT / T, q = 2 * a * 100.0;
    EXPECT_LE(RelErr(SingerProcessNoiseSeries(T, a, q), SingerProcessNoiseClosed(T, a, q)), kSeriesClosedTol)
        << "aT=" << aT;
  }
  // And the closed form really is unusable for aT ≪ 1 (why the series exists).
  const double T = 1.0, a = 1e-6, q = 2 * a;
  EXPECT_GT(RelErr(SingerProcessNoiseClosed(T, a, q), SingerProcessNoiseSeries(T, a, q)), 1e-3);
}

TEST(Singer, FilterIsConsistentOnSimulatedProcess) {
  // Monte Carlo: the continuous Singer process simulated by fine sub-steps
  // (independent of Ψ/Q), measured at irregular times with noise R; NEES of the
  // 6-state filter must average 6 (χ²(6) mean).
  constexpr int kRuns = 200, kSteps = 60, kSub = 50;
  const double tau = 0.8, sigma_m = 20.0, r_sigma = 0.3;
  const double a = 1.0 / tau;
  SingerAxisOptions ax;
  ax.maneuver_time_s = tau;
  ax.accel_sigma = sigma_m;
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n01;
  std::uniform_real_distribution<double> udt(0.02, 0.12);
  double nees_sum = 0, nis_sum = 0;
  int count = 0;
  for (int run = 0; run < kRuns; ++run) {
    SingerFilter<2> kf({ax, ax});
    // Truth starts from the stationary acceleration distribution.
    Eigen::Matrix<double, 6, 1> x;
    for (int i = 0; i < 2; ++i) {
      x(3 * i) = 5.0 * n01(rng);
      x(3 * i + 1) = 2.0 * n01(rng);
      x(3 * i + 2) = sigma_m * n01(rng);
    }
    const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * r_sigma * r_sigma;
    for (int k = 0; k < kSteps; ++k) {
      const double dt = k == 0 ? 0.0 : udt(rng);
      const double h = dt / kSub;
      for (int s = 0; s < kSub && h > 0; ++s) {
        for (int i = 0; i < 2; ++i) {
          double& u = x(3 * i);
          double& v = x(3 * i + 1);
          double& acc = x(3 * i + 2);
          // Exact OU step for the acceleration, trapezoid for v and u.
          const double acc0 = acc;
          acc = acc * std::exp(-a * h) + sigma_m * std::sqrt(1 - std::exp(-2 * a * h)) * n01(rng);
          const double v0 = v;
          v += 0.5 * (acc0 + acc) * h;
          u += 0.5 * (v0 + v) * h;
        }
      }
      const Eigen::Vector2d z(x(0) + r_sigma * n01(rng), x(3) + r_sigma * n01(rng));
      if (k == 0) {
        kf.Initialise(z, R, 2.0, sigma_m);
        continue;
      }
      kf.Predict(dt);
      const double nis = kf.Mahalanobis2(z, R);
      kf.Update(z, R);
      if (k >= 10) {
        const Eigen::Matrix<double, 6, 1> e = x - kf.state();
        nees_sum += e.dot(kf.covariance().ldlt().solve(e));
        nis_sum += nis;
        ++count;
      }
    }
  }
  const double nees = nees_sum / count, nis = nis_sum / count;
  std::printf("NEES mean %.3f (expect 6), NIS mean %.3f (expect 2) over %d samples\n", nees, nis, count);
  // Band: the samples within a run are correlated; 200 independent runs of 50
  // steps give a standard error of the mean well below 0.3 for χ²(6) (var 12).
  EXPECT_NEAR(nees, 6.0, 0.6);
  EXPECT_NEAR(nis, 2.0, 0.2);
}

TEST(Singer, JosephUpdateKeepsCovarianceSymmetricPositive) {
  SingerAxisOptions ax;
  SingerFilter<1> kf({ax});
  kf.Initialise(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(1e-6), 10.0, 50.0);
  for (int k = 0; k < 100; ++k) {
    kf.Predict(k % 7 == 0 ? 2.5 : 1e-4);
    kf.Update(Eigen::Matrix<double, 1, 1>(1.0 + 1e-3 * k), Eigen::Matrix<double, 1, 1>(1e-8));
    EXPECT_EQ((kf.covariance() - kf.covariance().transpose()).norm(), 0.0);
    EXPECT_EQ(kf.covariance().llt().info(), Eigen::Success) << k;
  }
}

TEST(SingerAxisOptions, Check) {
  SingerAxisOptions o;
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  o.maneuver_time_s = -1;
  EXPECT_FALSE(o.Check(&why));
  o = {};
  o.accel_sigma = std::nan("");
  EXPECT_FALSE(o.Check(&why));
}

}  // namespace
}  // namespace rk::track

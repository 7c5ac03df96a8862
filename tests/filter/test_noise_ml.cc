// Noise estimation for rk-smooth aukf on simulated truth: σ from high-order differences
// (NoiseSigmaFromDifferences) and the maximum-likelihood white-jerk intensity (FitWhiteJerkQMl).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "filter/aukf_series.h"
#include "filter/noise_ml.h"
#include "filter/singer_series.h"
#include "geo/angles.h"

namespace rk::filter {
namespace {

constexpr double kRateHz = 20.0;

// Sum of three sines per series, 0.1–2 Hz at 20 Hz (rk-sim posetrack's head profile in spirit), plus white
// noise σ. Returns the noisy values.
std::vector<double> FastSines(std::mt19937* rng, int n, double amplitude, double sigma, bool angle) {
  std::uniform_real_distribution<double> uf(0.1, 2.0), uph(0.0, geo::kTwoPi);
  std::normal_distribution<double> g(0.0, sigma);
  double f[3], ph[3];
  for (int i = 0; i < 3; ++i) {
    f[i] = uf(*rng);
    ph[i] = uph(*rng);
  }
  std::vector<double> z;
  for (int k = 0; k < n; ++k) {
    double v = 0.0;
    for (int i = 0; i < 3; ++i) v += amplitude / 3 * std::sin(geo::kTwoPi * f[i] * k / kRateHz + ph[i]);
    v += g(*rng);
    z.push_back(angle ? geo::WrapPi(v) : v);
  }
  return z;
}

TEST(NoiseMl, SigmaFromHighOrderDifferencesOnFastMotion) {
  std::mt19937 rng(11);
  constexpr int kSeries = 40, kSamples = 401;
  constexpr double kSigmaDeg = 0.0724;
  // Per series the estimate is a statistic of ~400 differences: ±6 % (1σ) measured, so ±25 % bounds each; the
  // mean over 40 series is within 4 % (a small downward bias from taking the least contaminated order).
  constexpr double kEachTol = 0.25, kMeanTol = 0.04;
  double sum = 0.0, sum4 = 0.0;
  for (int s = 0; s < kSeries; ++s) {
    const std::vector<double> z =
        FastSines(&rng, kSamples, geo::DegToRad(40.0), geo::DegToRad(kSigmaDeg), true);
    int order = 0;
    const double est = geo::RadToDeg(NoiseSigmaFromDifferences(z, true, 3, 8, &order)) / kSigmaDeg;
    EXPECT_NEAR(est, 1.0, kEachTol) << "series " << s;
    EXPECT_GE(order, 3);
    EXPECT_LE(order, 8);
    sum += est;
    sum4 += geo::RadToDeg(EstimateNoiseSigma(z, true, 4)) / kSigmaDeg;
  }
  EXPECT_NEAR(sum / kSeries, 1.0, kMeanTol);
  // Why not the 4th difference alone (rk-smooth singer's estimator): the motion leaks into it here.
  EXPECT_GT(sum4 / kSeries, 1.2);
}

TEST(NoiseMl, SigmaOfNoiseOnlyAndTooShort) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 2.0);
  std::vector<double> z;
  for (int k = 0; k < 4000; ++k) z.push_back(5.0 + 0.1 * k + g(rng));  // a ramp: cancelled by every order ≥ 2
  constexpr double kTol = 0.06;                                        // 4000 samples: ≈ 2 % (1σ)
  EXPECT_NEAR(NoiseSigmaFromDifferences(z, false) / 2.0, 1.0, kTol);
  EXPECT_TRUE(std::isnan(NoiseSigmaFromDifferences({1.0, 2.0, 3.0, 4.0, 5.0}, false, 3, 8)));
}

// White-jerk truth with intensity q, sampled at 20 Hz with noise σ: the filter's own model.
std::vector<double> WhiteJerk(std::mt19937* rng, int n, double q, double sigma, std::vector<double>* t) {
  const double T = 1.0 / kRateHz;
  const Eigen::Matrix3d Q = WhiteJerkQ(T, q);
  const Eigen::Matrix3d L = Q.llt().matrixL();
  Eigen::Matrix3d F;
  F << 1, T, T * T / 2, 0, 1, T, 0, 0, 1;
  std::normal_distribution<double> g;
  Eigen::Vector3d x(0, 1, 0);
  std::vector<double> z;
  t->clear();
  for (int k = 0; k < n; ++k) {
    if (k > 0) x = F * x + L * Eigen::Vector3d(g(*rng), g(*rng), g(*rng));
    t->push_back(k * T);
    z.push_back(x(0) + sigma * g(*rng));
  }
  return z;
}

TEST(NoiseMl, WhiteJerkIntensityRecovered) {
  std::mt19937 rng(5);
  constexpr double kQ = 50.0, kSigma = 0.01;  // m²/s⁵, m
  constexpr int kRuns = 8, kSamples = 3000;
  // 3000 innovations: the ML q scatters by ≈ 10 % (1σ) in these runs; ±35 % each, ±12 % for the mean.
  constexpr double kEachTol = 0.35, kMeanTol = 0.12;
  double sum_log = 0.0;
  for (int r = 0; r < kRuns; ++r) {
    std::vector<double> t;
    const std::vector<double> z = WhiteJerk(&rng, kSamples, kQ, kSigma, &t);
    NoiseMlFit fit;
    // Started 100× away from the truth: the grid covers ±8 decades.
    ASSERT_TRUE(
        FitWhiteJerkQMl(t.data(), z.data(), z.size(), false, kSigma, 100 * kQ, NoiseMlOptions{}, &fit));
    EXPECT_NEAR(fit.q / kQ, 1.0, kEachTol) << "run " << r;
    EXPECT_FALSE(fit.on_bound);
    EXPECT_EQ(fit.innovations, static_cast<std::size_t>(kSamples - 1 - NoiseMlOptions{}.burn_in));
    sum_log += std::log(fit.q / kQ);
  }
  EXPECT_NEAR(std::exp(sum_log / kRuns), 1.0, kMeanTol);
}

TEST(NoiseMl, LongSeriesUseBlocksAndMissingValuesArePredictions) {
  std::mt19937 rng(8);
  constexpr double kQ = 2.0, kSigma = 0.001;
  std::vector<double> t;
  std::vector<double> z = WhiteJerk(&rng, 30000, kQ, kSigma, &t);
  for (std::size_t k = 100; k < z.size(); k += 37) z[k] = std::nan("");
  NoiseMlOptions opt;  // 6000 samples in 6 blocks of 1000
  NoiseMlFit fit;
  ASSERT_TRUE(FitWhiteJerkQMl(t.data(), z.data(), z.size(), false, kSigma, kQ, opt, &fit));
  // Only the blocks enter the likelihood: at most 6 × (1000 − 1 − burn-in) innovations (fewer: NaN rows).
  EXPECT_LE(fit.innovations, static_cast<std::size_t>(opt.blocks) * (1000 - 1 - opt.burn_in));
  EXPECT_GT(fit.innovations, 5500u);
  constexpr double kTol = 0.3;  // ≈ 6000 innovations
  EXPECT_NEAR(fit.q / kQ, 1.0, kTol);
  // Too few values.
  std::vector<double> few(z.begin(), z.begin() + 15), tf(t.begin(), t.begin() + 15);
  EXPECT_FALSE(FitWhiteJerkQMl(tf.data(), few.data(), few.size(), false, kSigma, kQ, opt, &fit));
}

TEST(NoiseMl, AngleColumnAcrossNorth) {
  // The same white-jerk path, as an angle wrapped to (−π, π] and spinning through ±π many times, must give
  // the same likelihood optimum as the unwrapped series.
  std::mt19937 rng(9);
  std::vector<double> t;
  std::vector<double> z = WhiteJerk(&rng, 2000, 0.5, 0.002, &t);
  std::vector<double> w(z.size());
  for (std::size_t k = 0; k < z.size(); ++k) w[k] = geo::WrapPi(z[k] + 3.0 * t[k]);  // + 3 rad/s spin
  for (std::size_t k = 0; k < z.size(); ++k) z[k] += 3.0 * t[k];
  NoiseMlFit a, b;
  ASSERT_TRUE(FitWhiteJerkQMl(t.data(), z.data(), z.size(), false, 0.002, 0.5, NoiseMlOptions{}, &a));
  ASSERT_TRUE(FitWhiteJerkQMl(t.data(), w.data(), w.size(), true, 0.002, 0.5, NoiseMlOptions{}, &b));
  constexpr double kSameTol = 1e-6;  // identical innovations up to rounding
  EXPECT_NEAR(b.q / a.q, 1.0, kSameTol);
}

}  // namespace
}  // namespace rk::filter

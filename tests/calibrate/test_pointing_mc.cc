// Honest uncertainty of rk-calibrate pointing: over Monte Carlo sessions (fixed seeds) the normalised
// estimation error squared, NEES_k = (x̂_k − x_k)² / σ_k², has mean 1 for every parameter when the reported
// σ are right, and so has the joint NEES (x̂ − x)ᵀ P⁻¹ (x̂ − x) / n. The sessions have a stepper turret
// (0.003° steps) whose reading errors dominate the 0.05 px centroid noise: σ computed as if every frame's
// error were independent are several times too small; the model before the slow-slew, creep and rate
// terms (pointing_observations.h "Shared errors") gave mean NEES up to 1.4–1.5 for some parameters
// (docs/benchmarks.md, issue 17).
// The loop and the sessions are shared with bench/pointing_mc (tests/calibrate/test_pointing_common.h).
// DISABLED_FullSizeTargets is issue 17's benchmark (12 landmarks, 24 stars, 2 s dwells at 10 Hz, 2°/s
// slews, 100 mm lens; RK_POINTING_MC_RUNS runs, default 100): run it with --gtest_also_run_disabled_tests,
// or `pointing_mc 100 1` in a Release build (same figures).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "test_pointing_common.h"

namespace rk::calibrate {
namespace {

// CI size: kCiRuns small sessions (SmallMcSession, ≈ 160 image points each; about 40 s under ASan).
constexpr int kCiRuns = 30;
constexpr std::uint64_t kCiFirstSeed = 1000;
// Bands at kBandSigmas standard deviations of a mean of kCiRuns draws (the mean of N χ²(k) draws, divided
// by k, has variance 2/(kN)). The joint NEES per parameter is χ²(9)/9 per run, so its mean over N = 30 runs
// has SD √(2/270) = 0.086: ±3 SD = ±0.26 catches σ about 11 % too small (or 16 % too large) for all
// parameters together. A single parameter's NEES is χ²(1) (SD of the mean √(2/30) = 0.26): its ±3 SD band
// (±0.77) catches only gross errors of one term (σ 25 % too small, or twice too large).
// These bands do not see an error of 15 % in a few σ (the model before this change, NEES up to 1.4–1.5 in
// larger sessions, gives joint 0.98 and per parameter 0.72–1.39 on these sessions). The fit's χ²/dof does:
// with the stated errors right its mean over N runs of d = 2 × points − 9 degrees of freedom each has SD
// √(2/(N d)) (≈ 0.015 here); the errors must not be larger than stated, so it must stay below
// 1 + kBandSigmas SD. (It may be lower: the slow-slew σ are deliberately conservative, 0.83 here; the old
// model gave 1.29.)
constexpr double kBandSigmas = 3.0;
const double kParamBand = kBandSigmas * std::sqrt(2.0 / kCiRuns);
const double kJointBand = kBandSigmas * std::sqrt(2.0 / (kNumPointingParams * kCiRuns));
// The target band for the full-size, 100-run figure.
constexpr double kTargetNeesLow = 0.7, kTargetNeesHigh = 1.3;

TEST(PointingMonteCarlo, MeanNeesOfEveryParameterIsNearOne) {
  const testing::McFigures f = testing::RunMonteCarlo(testing::SmallMcSession(), kCiRuns, kCiFirstSeed);
  testing::PrintMcFigures(f);
  for (int k = 0; k < kNumPointingParams; ++k) {
    EXPECT_NEAR(f.nees[static_cast<std::size_t>(k)], 1.0, kParamBand) << PointingParamName(k);
  }
  EXPECT_NEAR(f.joint_nees, 1.0, kJointBand);
  const double dof = 2.0 * f.observations - static_cast<double>(kNumPointingParams);
  EXPECT_LT(f.chi2_per_dof, 1.0 + kBandSigmas * std::sqrt(2.0 / (kCiRuns * dof)));
}

TEST(PointingMonteCarlo, DISABLED_FullSizeTargets) {
  const char* env = std::getenv("RK_POINTING_MC_RUNS");
  const int runs = env ? std::atoi(env) : 100;
  sim::PointingSimOptions o;  // defaults: 12 landmarks 0–8°, 24 stars 12–75°, 100 mm, 2 s dwells, 2°/s
  o.validation_s = 0.0;
  const testing::McFigures f = testing::RunMonteCarlo(o, runs, 1);
  testing::PrintMcFigures(f);
  for (int k = 0; k < kNumPointingParams; ++k) {
    EXPECT_GT(f.nees[static_cast<std::size_t>(k)], kTargetNeesLow) << PointingParamName(k);
    EXPECT_LT(f.nees[static_cast<std::size_t>(k)], kTargetNeesHigh) << PointingParamName(k);
  }
}

}  // namespace
}  // namespace rk::calibrate

// Honest uncertainty of rk-calibrate pointing: over Monte Carlo sessions (fixed seeds) the normalised
// estimation error squared, NEES_k = (x̂_k − x_k)² / σ_k², has mean 1 for every parameter when the reported
// σ are right. The sessions have a stepper turret (0.003° steps, one reading per dwell) whose shared errors
// dominate the 0.05 px centroid noise: σ computed as if every frame's error were independent would be
// several times too small (NEES ≫ 1), which is what this test guards against.
#include <gtest/gtest.h>

#include "test_pointing_common.h"

namespace rk::calibrate {
namespace {

constexpr int kRuns = 50;
// Mean of 50 χ²(1) draws: standard deviation √(2/50) = 0.2; the band is ±3 of them.
constexpr double kNeesLow = 0.4, kNeesHigh = 1.6;

TEST(PointingMonteCarlo, MeanNeesOfEveryParameterIsNearOne) {
  std::array<double, kNumPointingParams> nees{};
  EstimateSet est{};
  est.fill(true);
  for (int run = 0; run < kRuns; ++run) {
    sim::PointingSimOptions o;
    o.seed = 1000 + static_cast<std::uint64_t>(run);
    o.landmarks = 6;
    o.stars = 8;
    o.dwell_s = 0.6;
    o.frame_rate_hz = 5.0;
    o.validation_s = 0.0;
    const sim::PointingSession s = sim::SimulatePointingSession(o);
    const testing::SessionInputs in = testing::InputsOf(s);
    PointingCalibrationOptions opt;
    const PointingSolution sol = SolvePointing(testing::BuilderOf(in, opt, o.centroid_sigma_px), s.camera_nominal, est, opt);
    const auto truth = testing::TruthOf(s);
    for (int k = 0; k < kNumPointingParams; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      double e = sol.x[ku] - truth[ku];
      if (k == kParamAzOffset) e = geo::WrapPi(e);
      nees[ku] += e * e / (*sol.sigma[ku] * *sol.sigma[ku]) / kRuns;
    }
  }
  for (int k = 0; k < kNumPointingParams; ++k) {
    EXPECT_GT(nees[static_cast<std::size_t>(k)], kNeesLow) << PointingParamName(k);
    EXPECT_LT(nees[static_cast<std::size_t>(k)], kNeesHigh) << PointingParamName(k);
    std::printf("mean NEES %-13s %.3f\n", PointingParamName(k), nees[static_cast<std::size_t>(k)]);
  }
}

}  // namespace
}  // namespace rk::calibrate

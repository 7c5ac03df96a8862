// Named bounds and the consistency check shared by the tests of the three registration methods
// (test_bernoulli.cc, test_kalman.cc, test_batch.cc).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "registration/radar_model.h"

namespace rk::registration::testing {

// Short trials: 300 steps of scenario 3 (the Monte Carlo's 1000 belong in bench/). After 300 steps
// the partitioned filter's RMSE is below the convergence thresholds (docs/benchmarks.md: every
// bias converges by step ~230), so each error must be within a few reported sigmas.
inline constexpr int kSteps = 300;
// |error| ≤ kSigmaBound · reported 1-sigma for each of the 12 biases: 4.5σ keeps the chance of a
// false failure over 12 correlated components below 1e-4 for a consistent filter.
inline constexpr double kSigmaBound = 4.5;
// Converged-filter sigmas must be below the paper's convergence thresholds.
inline constexpr double kRangeSigmaMaxM = 30.0, kAngleSigmaMaxRad = 1e-3;
// Three targets detected with p_D = 0.8 give ~1.9 pairs per step instead of 5: after 300 steps the
// sigmas are ~3 times larger.
inline constexpr double kSparseSigmaFactor = 4.0;

inline void ExpectConsistent(const BiasVector& x, const BiasMatrix& P, const BiasVector& truth, const char* what,
                             double sigma_factor = 1.0) {
  for (int j = 0; j < kBiasDim; ++j) {
    const double s = std::sqrt(P(j, j));
    EXPECT_LE(std::abs(x[j] - truth[j]), kSigmaBound * s) << what << " bias " << j;
    EXPECT_LT(s, sigma_factor * (j % kRadarBiasDim == 0 ? kRangeSigmaMaxM : kAngleSigmaMaxRad)) << what << " bias " << j;
  }
}

}  // namespace rk::registration::testing

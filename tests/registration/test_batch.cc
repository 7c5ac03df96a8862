// The batch ML solve with its covariance on simulated truth (seed 002 scenarios, short trials).
#include <gtest/gtest.h>

#include <cmath>

#include "registration/batch.h"
#include "test_filter_checks.h"
#include "test_radar_common.h"

namespace rk::registration {
namespace {

using testing::ExpectConsistent;
using testing::kSteps;
using testing::ReadSimulated;
using testing::Scenario;
using testing::TruthBiases;

TEST(Batch, GatedMaximumLikelihoodWithCovariance) {
  const sim::RadarSimulator sim(Scenario(3, kSteps, 27));
  const RegistrationInput in = ReadSimulated(sim);
  BatchOptions opt;
  const BatchResult r = RunBatch(in, opt);
  ASSERT_TRUE(r.stats.covariance_ok);
  ExpectConsistent(r.result.x, r.result.P, TruthBiases(sim), "batch");
  // The noise sigmas are right, so the a-posteriori variance factor is ≈ 1 (3n ≈ 4500 dof).
  EXPECT_GT(r.stats.variance_factor, 0.85);
  EXPECT_LT(r.stats.variance_factor, 1.15);
  // Associations by gating: almost all pairs are true pairs.
  int good = 0, total = 0;
  for (std::size_t k = 0; k < in.steps.size(); ++k) {
    for (const auto& [i, j] : r.pairs[k]) {
      ++total;
      if (in.steps[k].plots[0][i].track >= 0 && in.steps[k].plots[0][i].track == in.steps[k].plots[1][j].track) ++good;
    }
  }
  EXPECT_GT(total, 4 * kSteps);
  EXPECT_GT(static_cast<double>(good) / total, 0.95);
  // Every row carries the one whole-trial estimate.
  EXPECT_EQ(r.result.steps.front().x, r.result.steps.back().x);
  // Known association gives the same answer within its sigma.
  BatchOptions known = opt;
  known.association = BatchAssociation::kTrack;
  const BatchResult rk = RunBatch(in, known);
  for (int j = 0; j < kBiasDim; ++j) {
    EXPECT_LE(std::abs(rk.result.x[j] - r.result.x[j]), std::sqrt(r.result.P(j, j))) << j;
  }
}

}  // namespace
}  // namespace rk::registration

// The Bernoulli filter on simulated truth (seed 002 scenarios, short trials): with and without
// partition, and (golden) equal to the known-association KF when there is one target and no clutter.
#include <gtest/gtest.h>

#include <cmath>

#include "registration/bernoulli.h"
#include "registration/kalman.h"
#include "test_filter_checks.h"
#include "test_radar_common.h"

namespace rk::registration {
namespace {

using testing::ExpectConsistent;
using testing::kSparseSigmaFactor;
using testing::kSteps;
using testing::ReadSimulated;
using testing::Scenario;
using testing::TruthBiases;

TEST(Bernoulli, ConvergesWithClutterAndPicksTruePairs) {
  const sim::RadarSimulator sim(Scenario(3, kSteps, 21));
  const RegistrationInput in = ReadSimulated(sim);
  BernoulliOptions opt;
  const BernoulliResult res = RunBernoulli(in, opt);
  ASSERT_EQ(res.result.steps.size(), static_cast<std::size_t>(kSteps));
  ExpectConsistent(res.result.x, res.result.P, TruthBiases(sim), "bernoulli");
  // After the first 50 steps the selected pairs are the true ones (same target in both radars).
  int good = 0, total = 0;
  for (std::size_t k = 50; k < in.steps.size(); ++k) {
    for (const auto& [i, j] : res.selected[k]) {
      ++total;
      const int ta = in.steps[k].plots[0][i].track, tb = in.steps[k].plots[1][j].track;
      if (ta >= 0 && ta == tb) ++good;
    }
  }
  EXPECT_GT(total, 4 * (kSteps - 50));  // about L = 5 pairs per step
  // Targets 1 and 2 fly 1 km apart, inside the noise at these ranges: a few swaps are expected.
  EXPECT_GT(static_cast<double>(good) / total, 0.9);
  EXPECT_EQ(res.stats.counters.covariance_repairs, 0);
  EXPECT_EQ(res.result.steps.back().status, RowStatus::kOk);
}

TEST(Bernoulli, PartitionBeatsNoPartition) {
  const sim::RadarSimulator sim(Scenario(1, kSteps, 22));
  const RegistrationInput in = ReadSimulated(sim);
  BernoulliOptions after, before;
  before.subset_length = 1;
  const BernoulliResult a = RunBernoulli(in, after), b = RunBernoulli(in, before);
  // L = 5 uses ~5 pairs per step, L = 1 one: its covariance must be clearly larger.
  for (int j = 0; j < kBiasDim; ++j) EXPECT_LT(a.result.P(j, j), b.result.P(j, j)) << j;
  EXPECT_NEAR(b.result.stats["mean_subset_length"].get<double>(), 1.0, 1e-12);
}

// Golden test: one target, no clutter, K = L = 1 — the Bernoulli filter has one candidate pair per
// step, so it is exactly the known-association KF.
TEST(Bernoulli, EqualsKalmanWithOneTargetAndNoClutter) {
  sim::RadarSimOptions o = Scenario(1, 100, 23);
  o.targets = 1;
  const sim::RadarSimulator sim(o);
  const RegistrationInput in = ReadSimulated(sim);
  BernoulliOptions bo;
  bo.subsets = 1;
  bo.subset_length = 1;
  bo.gate_d2 = 1e9;  // never gate the only pair
  const BernoulliResult b = RunBernoulli(in, bo);
  KfOptions ko;
  const KfResult k = RunKalman(in, ko);
  ASSERT_EQ(b.result.steps.size(), k.result.steps.size());
  for (std::size_t s = 0; s < b.result.steps.size(); ++s) {
    EXPECT_LT((b.result.steps[s].x - k.result.steps[s].x).cwiseAbs().maxCoeff(), 1e-9) << s;
  }
}

// Scenario 1 drives radar a's pitch past 90° at t ≈ 780 s: a nav folded into ±90° must give the
// same estimates as the continuous one.
TEST(Bernoulli, FoldedPitchNavGivesTheSameEstimates) {
  const sim::RadarSimulator sim(Scenario(1, kSteps, 28));
  const RegistrationInput plain = ReadSimulated(sim), folded = ReadSimulated(sim, {}, true, true);
  EXPECT_EQ(plain.summary.nav_unfolded_rows[0], 0u);
  EXPECT_GT(folded.summary.nav_unfolded_rows[0], 50u);
  const BernoulliResult a = RunBernoulli(plain, BernoulliOptions{}), b = RunBernoulli(folded, BernoulliOptions{});
  // Same rotations up to the 1e-9° rounding of the files.
  EXPECT_LT((a.result.x - b.result.x).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(Bernoulli, MissedDetectionsAndLessTargetsThanL) {
  sim::RadarSimOptions o = Scenario(3, kSteps, 24);
  o.detection_probability = 0.8;
  o.targets = 3;  // L = 5 > 3 targets: subsets stop early
  const sim::RadarSimulator sim(o);
  const RegistrationInput in = ReadSimulated(sim);
  const BernoulliResult res = RunBernoulli(in, BernoulliOptions{});
  EXPECT_GT(res.stats.short_subsets, kSteps / 2);
  ExpectConsistent(res.result.x, res.result.P, TruthBiases(sim), "pd 0.8", kSparseSigmaFactor);
}

TEST(Bernoulli, OptionsCheck) {
  BernoulliOptions o;
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  o.subset_length = 0;
  EXPECT_FALSE(o.Check(&why));
  o = BernoulliOptions{};
  o.detection_probability = 0;
  EXPECT_FALSE(o.Check(&why));
  o = BernoulliOptions{};
  o.filter.noise.sigma_range_m = 0;
  EXPECT_FALSE(o.Check(&why));
}

}  // namespace
}  // namespace rk::registration

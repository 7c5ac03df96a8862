// The three methods on simulated truth (seed 002 scenarios, short trials): Bernoulli with and
// without partition, the known-association KF (golden: equal to the Bernoulli filter when there
// is one target and no clutter), and the batch ML solve with its covariance.
#include <gtest/gtest.h>

#include <cmath>

#include "registration/batch.h"
#include "registration/bernoulli.h"
#include "registration/kalman.h"
#include "test_radar_common.h"

namespace rk::registration {
namespace {

using testing::ReadSimulated;
using testing::Scenario;
using testing::TruthBiases;

// Short trials: 300 steps of scenario 3 (the Monte Carlo's 1000 belong in bench/). After 300 steps
// the partitioned filter's RMSE is below the convergence thresholds (docs/benchmarks.md: every
// bias converges by step ~230), so each error must be within a few reported sigmas.
constexpr int kSteps = 300;
// |error| ≤ kSigmaBound · reported 1-sigma for each of the 12 biases: 4.5σ keeps the chance of a
// false failure over 12 correlated components below 1e-4 for a consistent filter.
constexpr double kSigmaBound = 4.5;
// Converged-filter sigmas must be below the paper's convergence thresholds.
constexpr double kRangeSigmaMaxM = 30.0, kAngleSigmaMaxRad = 1e-3;
// Three targets detected with p_D = 0.8 give ~1.9 pairs per step instead of 5: after 300 steps the
// sigmas are ~3 times larger.
constexpr double kSparseSigmaFactor = 4.0;

void ExpectConsistent(const BiasVector& x, const BiasMatrix& P, const BiasVector& truth, const char* what,
                      double sigma_factor = 1.0) {
  for (int j = 0; j < kBiasDim; ++j) {
    const double s = std::sqrt(P(j, j));
    EXPECT_LE(std::abs(x[j] - truth[j]), kSigmaBound * s) << what << " bias " << j;
    EXPECT_LT(s, sigma_factor * (j % kRadarBiasDim == 0 ? kRangeSigmaMaxM : kAngleSigmaMaxRad)) << what << " bias " << j;
  }
}

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

TEST(Kalman, KnownAssociationConvergesAndPerTrack) {
  const sim::RadarSimulator sim(Scenario(1, kSteps, 25));
  const RegistrationInput in = ReadSimulated(sim);
  KfOptions all;
  const KfResult r = RunKalman(in, all);
  ExpectConsistent(r.result.x, r.result.P, TruthBiases(sim), "kf all");
  EXPECT_EQ(r.counters.updates, 5 * kSteps);
  // Consistency: mean NIS of the 3-dof innovations near 3.
  EXPECT_GT(r.mean_nis, 2.5);
  EXPECT_LT(r.mean_nis, 3.5);
  KfOptions one;
  one.track = "4";
  const KfResult r4 = RunKalman(in, one);
  EXPECT_EQ(r4.counters.updates, kSteps);
  for (int j = 0; j < kBiasDim; ++j) EXPECT_GT(r4.result.P(j, j), r.result.P(j, j));
  KfOptions bad;
  bad.track = "9";
  EXPECT_THROW(RunKalman(in, bad), Error);
}

TEST(Kalman, NeedsTrackId) {
  const sim::RadarSimulator sim(Scenario(1, 5, 26));
  const RegistrationInput in = ReadSimulated(sim, {}, false);
  try {
    RunKalman(in, KfOptions{});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("track_id"), std::string::npos);
  }
}

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

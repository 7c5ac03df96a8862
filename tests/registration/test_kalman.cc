// The known-association Kalman filter on simulated truth (seed 002 scenarios, short trials).
#include <gtest/gtest.h>

#include <cmath>

#include "registration/kalman.h"
#include "test_filter_checks.h"
#include "test_radar_common.h"

namespace rk::registration {
namespace {

using testing::ExpectConsistent;
using testing::kSteps;
using testing::ReadSimulated;
using testing::Scenario;
using testing::TruthBiases;

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

}  // namespace
}  // namespace rk::registration

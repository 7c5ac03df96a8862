// The trial clock (capture/clock.h): the epoch of a trial.
#include <gtest/gtest.h>

#include "capture/clock.h"

namespace rk::capture {
namespace {

TEST(Clock, EpochIsTheWholeSecondBeforeTheStart) {
  const Stamp now = Now();
  const TrialEpoch e = TrialEpoch::FromStamp(now);
  EXPECT_EQ(e.real_ns % kNsPerS, 0);
  EXPECT_LE(e.real_ns, now.real_ns);
  EXPECT_GT(e.real_ns, now.real_ns - kNsPerS);
  // The start is at t_s = (its fraction of a second) on both clocks.
  EXPECT_NEAR(e.TrialSeconds(now.mono_ns), static_cast<double>(now.real_ns - e.real_ns) * 1e-9, 1e-9);
  EXPECT_EQ(FormatUtc(0), "1970-01-01T00:00:00Z");
  EXPECT_EQ(FormatUtc(1795364623123456789LL, 3), "2026-11-22T16:23:43.123Z");
  // Monotonic and real-time readings of one stamp refer to one instant: consecutive stamps agree
  // on the elapsed time to well under a millisecond (no NTP step expected during a test).
  const Stamp a = Now(), b = Now();
  EXPECT_NEAR(static_cast<double>((b.mono_ns - a.mono_ns) - (b.real_ns - a.real_ns)), 0.0, 1e6);
}

}  // namespace
}  // namespace rk::capture

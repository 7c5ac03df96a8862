// The progress display (io/progress.h): what a person sees on a terminal during a long run.
#include <gtest/gtest.h>

#include "io/progress.h"

namespace rk::io {
namespace {

TEST(Progress, KnownTotalShowsDoneTotalPercentRateAndEta) {
  // 1200 of 6000 frames in 3 s: 400/s, 4800 frames left → 12 s.
  EXPECT_EQ(FormatProgress("rk-extract", "frames", 1200, 6000, 3.0), "rk-extract: 1200/6000 frames (20%), 400/s, ETA 0:12");
  // Over an hour: h:mm:ss.
  EXPECT_EQ(FormatProgress("rk-run", "steps", 1, 1000, 5.0), "rk-run: 1/1000 steps (0%), 0.2/s, ETA 1:23:15");
}

TEST(Progress, UnknownTotalShowsDoneAndRateOnly) {
  EXPECT_EQ(FormatProgress("rk-extract", "frames", 50, 0, 2.0), "rk-extract: 50 frames, 25/s");
}

TEST(Progress, NoRateBeforeTimeHasPassedAndNoEtaWhenDone) {
  EXPECT_EQ(FormatProgress("rk-x", "rows", 0, 10, 0.0), "rk-x: 0/10 rows (0%)");
  EXPECT_EQ(FormatProgress("rk-x", "rows", 10, 10, 2.0), "rk-x: 10/10 rows (100%), 5.0/s");
}

TEST(Progress, DisabledMeterWritesNothing) {
  testing::internal::CaptureStderr();
  {
    ProgressMeter m("rk-x", "frames", 10, /*enabled=*/false);
    for (int i = 0; i <= 10; ++i) m.Update(i);
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace rk::io

// Figures of issue 17's pointing targets: over N Monte Carlo calibration sessions (rk-sim pointing defaults:
// 0.05 px, 0.003° encoder steps, 12 landmarks at 0–8°, 24 stars at 12–75°, 100 mm lens, 2 s dwells at 10 Hz,
// 2°/s slews; every parameter estimated) the mean NEES of every parameter and the joint NEES, the RMS
// error, the mean reported σ, and the solve time. The Monte Carlo loop is the test's
// (tests/calibrate/test_pointing_common.h; the same figures as PointingMonteCarlo.DISABLED_FullSizeTargets).
// Usage: pointing_mc [RUNS=100] [FIRST_SEED=1] [small]   (small: the CI test's sessions, SmallMcSession)
#include <cstdlib>
#include <string>

#include "../tests/calibrate/test_pointing_common.h"

int main(int argc, char** argv) {
  using namespace rk::calibrate;
  const int runs = argc > 1 ? std::atoi(argv[1]) : 100;
  const std::uint64_t first = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
  rk::sim::PointingSimOptions o;
  o.validation_s = 0.0;
  if (argc > 3 && std::string(argv[3]) == "small") o = testing::SmallMcSession();
  testing::PrintMcFigures(testing::RunMonteCarlo(o, runs, first));
  return 0;
}

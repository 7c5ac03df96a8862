// Figures of issue 17's pointing targets: over N Monte Carlo calibration sessions (rk-sim pointing; 0.05 px,
// 0.003° encoder steps, 12 landmarks at 0–8°, 24 stars at 12–75°, 100 mm lens, 2°/s slews) the mean NEES of
// every parameter, the RMS error, the mean reported σ (= the Cramér–Rao bound of the linearised model with
// its shared errors: (JᵀJ)⁻¹ with the per-dwell and per-target priors), and the solve time.
// Usage: pointing_mc [RUNS=100] [FIRST_SEED=1]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "../tests/calibrate/test_pointing_common.h"

using namespace rk;
using namespace rk::calibrate;

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 100;
  const std::uint64_t first = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
  std::array<double, kNumPointingParams> nees{}, err2{}, sig{};
  EstimateSet est{};
  est.fill(true);
  double solve_s = 0.0, obs = 0.0;
  for (int run = 0; run < runs; ++run) {
    sim::PointingSimOptions o;
    o.seed = first + static_cast<std::uint64_t>(run);
    const sim::PointingSession s = sim::SimulatePointingSession(o);
    const testing::SessionInputs in = testing::InputsOf(s);
    PointingCalibrationOptions opt;
    const auto t0 = std::chrono::steady_clock::now();
    const PointingSolution sol = SolvePointing(testing::BuilderOf(in, opt, o.centroid_sigma_px), s.camera_nominal, est, opt);
    solve_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    obs += static_cast<double>(sol.used);
    const auto truth = testing::TruthOf(s);
    for (int k = 0; k < kNumPointingParams; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      double e = sol.x[ku] - truth[ku];
      if (k == kParamAzOffset) e = geo::WrapPi(e);
      nees[ku] += e * e / (*sol.sigma[ku] * *sol.sigma[ku]) / runs;
      err2[ku] += e * e / runs;
      sig[ku] += *sol.sigma[ku] / runs;
    }
  }
  std::printf("%d runs, mean %.0f observations used, mean solve %.3f s\n", runs, obs / runs, solve_s / runs);
  std::printf("%-13s %9s %14s %14s  unit\n", "parameter", "mean NEES", "RMS error", "mean sigma");
  for (int k = 0; k < kNumPointingParams; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    double scale = geo::kArcsecPerRad;
    const char* unit = "arcsec";
    if (k == kParamFocal) scale = 100.0, unit = "% of focal";
    if (k == kParamTimeOffset) scale = 1e3, unit = "ms";
    std::printf("%-13s %9.3f %14.5f %14.5f  %s\n", PointingParamName(k), nees[ku], std::sqrt(err2[ku]) * scale,
                sig[ku] * scale, unit);
  }
  return 0;
}

// Speed of rk-calibrate pointing's solve (issue 17 target: a 500-observation solve ≤ 1 s): the full
// estimate (9 parameters) on a simulated session cut to its first 500 observations.
#include <benchmark/benchmark.h>

#include "../tests/calibrate/test_pointing_common.h"

namespace {

void BM_PointingSolve500(benchmark::State& state) {
  using namespace rk::calibrate;
  rk::sim::PointingSimOptions o;
  o.seed = 3;
  const rk::sim::PointingSession s = rk::sim::SimulatePointingSession(o);
  testing::SessionInputs in = testing::InputsOf(s);
  in.points.rows.resize(std::min<std::size_t>(in.points.rows.size(), 500));
  PointingCalibrationOptions opt;
  EstimateSet est{};
  est.fill(true);
  for (auto _ : state) {
    const PointingSolution sol = SolvePointing(testing::BuilderOf(in, opt, 0.05), s.camera_nominal, est, opt);
    benchmark::DoNotOptimize(sol.x);
  }
  state.counters["observations"] = static_cast<double>(in.points.rows.size());
}
BENCHMARK(BM_PointingSolve500)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

// rk-smooth aukf speed (issue 3 target: ≥ 100 000 steps/s for 6 columns = 18 states on one core; a
// 1-hour 20 Hz 6-column file in ≤ 3 s end to end). One "step" = one sample interval: two half-step
// sigma-point predictions, the measurement update and the node storage.
//   BM_AukfStep/<adapt>      forward pass over 20 000 samples (adapt 0 none, 1 r, 2 q, 3 qr), σ and q given
//                            (the per-file noise estimation is measured apart: BM_AukfNoiseEstimate)
//   BM_AukfStepSmooth        forward pass + unscented RTS over the same series, σ and q given
//   BM_AukfNoiseEstimate     RunAukf with σ, q estimated minus nothing: forward pass + estimation (compare
//                            with BM_AukfStep/0 for the estimation's cost)
//   BM_AukfHourEndToEnd      72 000-row CSV text → parse → filter → output CSV text (in memory;
//                            the CLI adds only file reading/writing)
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "filter/aukf_series.h"
#include "io/csv.h"

namespace {

const std::vector<std::string> kColumns = {"e_m", "n_m", "u_m", "yaw_deg", "pitch_deg", "roll_deg"};

std::string PoseCsv(int rows) {
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  std::string text = "t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg\n";
  char buf[256];
  for (int k = 0; k < rows; ++k) {
    const double t = k * 0.05;
    std::snprintf(buf, sizeof(buf), "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", t, 0.2 * std::sin(0.9 * t) + 0.001 * g(rng),
                  0.1 * std::cos(1.3 * t) + 0.001 * g(rng), 0.05 * std::sin(2.1 * t) + 0.001 * g(rng),
                  std::fmod(30 * std::sin(0.4 * t) + 360.0 + 0.05 * g(rng), 360.0), 10 * std::sin(0.7 * t) + 0.05 * g(rng),
                  5 * std::sin(1.1 * t) + 0.05 * g(rng));
    text += buf;
  }
  return text;
}

const rk::filter::Series& BenchSeries() {
  static const rk::io::CsvTable table = rk::io::CsvTable::Parse(PoseCsv(20000), "bench");
  static const rk::filter::Series series = rk::filter::ReadSeries(table, kColumns, 3);
  return series;
}

// The noise of PoseCsv in SI/radians (σ) and a white-jerk intensity that covers its motion (q).
rk::filter::AukfOptions GivenNoise() {
  rk::filter::AukfOptions opt;
  const double deg = 3.14159265358979323846 / 180.0;
  opt.meas_sigma = {0.001, 0.001, 0.001, 0.05 * deg, 0.05 * deg, 0.05 * deg};
  opt.q = {1.0, 1.0, 1.0, 1e3 * deg * deg, 1e3 * deg * deg, 1e3 * deg * deg};
  return opt;
}

void BM_AukfStep(benchmark::State& state) {
  const auto& s = BenchSeries();
  rk::filter::AukfOptions opt = GivenNoise();
  const rk::filter::AdaptMode modes[] = {rk::filter::AdaptMode::kNone, rk::filter::AdaptMode::kR,
                                         rk::filter::AdaptMode::kQ, rk::filter::AdaptMode::kQR};
  opt.adapt.mode = modes[state.range(0)];
  for (auto _ : state) {
    auto r = rk::filter::RunAukf(s, opt);
    benchmark::DoNotOptimize(r.x_filter.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s.rows() - 1));
  state.SetLabel(std::string("adapt ") + rk::filter::AdaptModeName(opt.adapt.mode) + ", 6 columns, items = steps");
}
BENCHMARK(BM_AukfStep)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_AukfNoiseEstimate(benchmark::State& state) {
  const auto& s = BenchSeries();
  rk::filter::AukfOptions opt;  // σ and q estimated (ml): forward pass + estimation
  for (auto _ : state) {
    auto r = rk::filter::RunAukf(s, opt);
    benchmark::DoNotOptimize(r.x_filter.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s.rows() - 1));
  state.SetLabel("adapt none, sigma and q estimated (ml), items = steps");
}
BENCHMARK(BM_AukfNoiseEstimate)->Unit(benchmark::kMillisecond);

void BM_AukfStepSmooth(benchmark::State& state) {
  const auto& s = BenchSeries();
  rk::filter::AukfOptions opt = GivenNoise();
  opt.smooth = true;
  for (auto _ : state) {
    auto r = rk::filter::RunAukf(s, opt);
    benchmark::DoNotOptimize(r.x_smooth.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s.rows() - 1));
}
BENCHMARK(BM_AukfStepSmooth)->Unit(benchmark::kMillisecond);

void BM_AukfHourEndToEnd(benchmark::State& state) {
  const std::string text = PoseCsv(72000);  // 1 hour at 20 Hz
  rk::filter::AukfOptions opt;
  opt.smooth = state.range(0) != 0;
  for (auto _ : state) {
    const auto table = rk::io::CsvTable::Parse(text, "hour.csv");
    const auto series = rk::filter::ReadSeries(table, kColumns, 3);
    const auto r = rk::filter::RunAukf(series, opt);
    const auto csv = rk::filter::AukfCsv(series, r, rk::filter::AukfOutputOptions{});
    benchmark::DoNotOptimize(csv.str().data());
  }
  state.SetLabel(opt.smooth ? "72000 rows, --smooth" : "72000 rows");
}
BENCHMARK(BM_AukfHourEndToEnd)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();

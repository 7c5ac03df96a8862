// rk-register speed (issue 5 target: the 100-run × 1000-step scenario-3 Monte Carlo in ≤ 60 s on
// 2 cores, i.e. sim + filters ≤ 1.2 s of CPU per run). In memory, one scenario-3 trial (seed 1,
// 1000 scans, ≈ 20 000 plots with clutter 5 per radar per scan):
//   BM_Simulate        rk-sim radar's simulator (no file writing)
//   BM_ReadInput       plots + nav CSV text → steps (parse, nav interpolation, geodetic → ECEF)
//   BM_Bernoulli/L     the GM Bernoulli filter, K = 3, L = 1 (before) and 5 (after, default)
//   BM_Kalman          the known-association KF (all tracks)
//   BM_Batch           the batch ML (its Bernoulli pass included)
#include <benchmark/benchmark.h>

#include <string>

#include "geo/angles.h"
#include "io/csv.h"
#include "registration/batch.h"
#include "registration/bernoulli.h"
#include "registration/input.h"
#include "registration/kalman.h"
#include "sim/radar_scenario.h"

namespace {

using namespace rk;

sim::RadarSimOptions Options() {
  sim::RadarSimOptions o;
  o.scenario = 3;
  o.steps = 1000;
  o.seed = 1;
  return o;
}

struct Texts {
  std::string plots, nav;
};

const Texts& TrialTexts() {
  static const Texts t = [] {
    const sim::RadarSimulator sim(Options());
    io::CsvWriter plots({"t_s", "radar", "range_m", "az_deg", "el_deg", "track_id"});
    for (const auto& p : sim.plots()) {
      plots.Add(p.t_s, 9).Add(sim.options().names[p.radar]).Add(p.range_m, 3);
      plots.Add(geo::WrapDeg360(geo::RadToDeg(p.az_rad)), 9).Add(geo::RadToDeg(p.el_rad), 9);
      if (p.target >= 0) {
        plots.Add(p.target + 1);
      } else {
        plots.AddEmpty();
      }
      plots.EndRow();
    }
    io::CsvWriter nav({"t_s", "radar", "lat_deg", "lon_deg", "h_m", "yaw_deg", "pitch_deg", "roll_deg"});
    for (const auto& n : sim.nav()) {
      nav.Add(n.t_s, 9).Add(sim.options().names[n.radar]).Add(n.lat_deg, 10).Add(n.lon_deg, 10).Add(n.h_m, 4);
      nav.Add(geo::WrapDeg360(geo::RadToDeg(n.yaw_rad)), 9).Add(geo::WrapDeg180(geo::RadToDeg(n.pitch_rad)), 9);
      nav.Add(geo::WrapDeg180(geo::RadToDeg(n.roll_rad)), 9).EndRow();
    }
    return Texts{plots.str(), nav.str()};
  }();
  return t;
}

const registration::RegistrationInput& Input() {
  static const registration::RegistrationInput in = registration::ReadRegistrationInput(
      io::CsvTable::Parse(TrialTexts().plots, "plots.csv"), io::CsvTable::Parse(TrialTexts().nav, "nav.csv"), {});
  return in;
}

void BM_Simulate(benchmark::State& state) {
  for (auto _ : state) {
    const sim::RadarSimulator sim(Options());
    benchmark::DoNotOptimize(sim.plots().data());
  }
}
BENCHMARK(BM_Simulate)->Unit(benchmark::kMillisecond);

void BM_ReadInput(benchmark::State& state) {
  const Texts& t = TrialTexts();
  for (auto _ : state) {
    const auto in = registration::ReadRegistrationInput(io::CsvTable::Parse(t.plots, "plots.csv"),
                                                        io::CsvTable::Parse(t.nav, "nav.csv"), {});
    benchmark::DoNotOptimize(in.steps.data());
  }
}
BENCHMARK(BM_ReadInput)->Unit(benchmark::kMillisecond);

void BM_Bernoulli(benchmark::State& state) {
  const auto& in = Input();
  registration::BernoulliOptions opt;
  opt.subset_length = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const auto r = registration::RunBernoulli(in, opt);
    benchmark::DoNotOptimize(r.result.x.data());
  }
  state.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(in.steps.size()) * state.iterations(),
                                                     benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Bernoulli)->Arg(1)->Arg(5)->Unit(benchmark::kMillisecond);

void BM_Kalman(benchmark::State& state) {
  const auto& in = Input();
  for (auto _ : state) {
    const auto r = registration::RunKalman(in, registration::KfOptions{});
    benchmark::DoNotOptimize(r.result.x.data());
  }
}
BENCHMARK(BM_Kalman)->Unit(benchmark::kMillisecond);

void BM_Batch(benchmark::State& state) {
  const auto& in = Input();
  for (auto _ : state) {
    const auto r = registration::RunBatch(in, registration::BatchOptions{});
    benchmark::DoNotOptimize(r.result.x.data());
  }
}
BENCHMARK(BM_Batch)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

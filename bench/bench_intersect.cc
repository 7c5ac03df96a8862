// rk-intersect speed (issue 18 targets): intersected rows per second for three stations on one core
// (≥ 200 000 rows/s), and the whole library run on a 10-minute three-station 20 Hz trial (read the located
// CSVs, align, intersect, smooth, write the CSV; ≤ 2 s). Figures in docs/benchmarks.md (Release build).
#include <benchmark/benchmark.h>

#include <vector>

#include "intersect/intersect.h"
#include "sim/multistation_scenario.h"

namespace {

struct Trial {
  rk::sim::MultistationScenario sim;
  std::vector<std::string> located;  // CSV text per station
  std::string stations_json;
  explicit Trial(double duration_s) : sim(Options(duration_s)) {
    for (std::size_t s = 0; s < sim.stations().size(); ++s) located.push_back(sim.LocatedCsv(s).str());
    stations_json = sim.StationsJson().dump(2);
  }
  static rk::sim::MultistationOptions Options(double duration_s) {
    rk::sim::MultistationOptions o;
    o.stations = 3;
    o.duration_s = duration_s;
    o.rate_hz = 20.0;
    o.path = rk::sim::MultistationPath::kCrossing;
    return o;
  }
};

std::vector<rk::intersect::StationTrack> Tracks(const Trial& t, const rk::intersect::IntersectOptions& opt) {
  std::vector<rk::intersect::StationTrack> tracks;
  for (std::size_t s = 0; s < t.located.size(); ++s) {
    tracks.emplace_back(rk::formats::ReadLocated(rk::io::CsvTable::Parse(t.located[s], "s.csv")), opt.Defaults());
  }
  return tracks;
}

// Align + intersect only (the per-row loop), rows/s.
void BM_IntersectRows(benchmark::State& state) {
  static const Trial trial(60.0);
  const rk::intersect::IntersectOptions opt;
  const rk::formats::StationsFile st = rk::formats::ParseStations(trial.stations_json, "stations.json");
  const std::vector<rk::intersect::StationTrack> tracks = Tracks(trial, opt);
  const std::vector<double> times = rk::intersect::OutputTimes(tracks, opt, {});
  for (auto _ : state) {
    const rk::intersect::IntersectResult r = rk::intersect::Intersect(st, tracks, times, opt);
    benchmark::DoNotOptimize(r.rows_ok);
  }
  state.counters["rows/s"] = benchmark::Counter(static_cast<double>(times.size() * state.iterations()),
                                                benchmark::Counter::kIsRate);
}
BENCHMARK(BM_IntersectRows)->Unit(benchmark::kMillisecond);

// End to end on a 10-minute trial: parse CSV text, align, intersect, smooth, format the output CSV.
void BM_TenMinuteTrialEndToEnd(benchmark::State& state) {
  static const Trial trial(600.0);
  rk::intersect::IntersectOptions opt;
  opt.smooth = true;
  for (auto _ : state) {
    const rk::formats::StationsFile st = rk::formats::ParseStations(trial.stations_json, "stations.json");
    const std::vector<rk::intersect::StationTrack> tracks = Tracks(trial, opt);
    const std::vector<double> times = rk::intersect::OutputTimes(tracks, opt, {});
    const rk::intersect::IntersectResult r = rk::intersect::Intersect(st, tracks, times, opt);
    const rk::io::CsvWriter w = rk::intersect::TrajectoryCsv(r);
    benchmark::DoNotOptimize(w.str().size());
    state.counters["rows"] = static_cast<double>(times.size());
  }
}
BENCHMARK(BM_TenMinuteTrialEndToEnd)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();

// rk-intersect --estimate-time-offsets (issue 33): Monte Carlo over rk-sim multistation trials with known clock
// offsets. Per scenario: the offsets' error, σ and NEES (S−1 dof, band for the runs), the warning rate, and the
// trajectory's 3-D RMS error with the estimated offsets, with the true ones and with none (as given), and the
// trajectory's own NEES. Then the time of one 10-minute three-station 20 Hz trial.
// Usage: time_offsets_mc [runs [knot_interval_s [first-only]]]   (Release build). Prints the docs/benchmarks.md "Issue 33" tables.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "formats/located.h"
#include "formats/stations.h"
#include "intersect/intersect.h"
#include "intersect/time_offsets.h"
#include "io/csv.h"
#include "sim/multistation_scenario.h"

namespace {

using rk::intersect::StationTrack;

struct Scenario {
  const char* name;
  rk::sim::MultistationOptions o;
};

struct Trial {
  rk::formats::StationsFile stations;
  std::vector<rk::formats::LocatedFile> files;
  std::vector<double> truth;  // per station
};

Trial MakeTrial(const rk::sim::MultistationScenario& sim) {
  Trial t;
  t.stations = rk::formats::ParseStations(sim.StationsJson().dump(), "stations.json");
  for (std::size_t s = 0; s < sim.stations().size(); ++s) {
    t.files.push_back(rk::formats::ReadLocated(rk::io::CsvTable::Parse(sim.LocatedCsv(s).str(), sim.stations()[s].name)));
    t.truth.push_back(sim.stations()[s].time_offset_s);
  }
  return t;
}

// The trajectory with the given offsets (and their σ): 3-D squared error sum, NEES sum and rows against the truth.
void Trajectory(const rk::sim::MultistationScenario& sim, const Trial& t, const std::vector<double>& offsets,
                const std::vector<double>* sigma, double* se, double* nees, double* n) {
  rk::intersect::IntersectOptions opt;
  std::vector<StationTrack> tracks;
  for (std::size_t s = 0; s < t.files.size(); ++s) {
    tracks.emplace_back(t.files[s], opt.Defaults(), offsets[s]);
    if (sigma) tracks.back().SetTimeSigma((*sigma)[s]);
  }
  const std::vector<double> times = rk::intersect::OutputTimes(tracks, opt, {});
  const rk::intersect::IntersectResult r = rk::intersect::Intersect(t.stations, tracks, times, opt);
  for (const auto& row : r.rows) {
    if (row.status != rk::RowStatus::kOk) continue;
    const Eigen::Vector3d e = row.result.solution.p - sim.Position(row.t_s);
    *se += e.squaredNorm();
    *nees += e.dot(row.result.solution.P.inverse() * e);
    *n += 1;
  }
}

double g_knot_s = 0.0;  // argv[2]: the knot interval (0: EstimateTimeOffsets' own choice)

void Run(const Scenario& sc, int runs) {
  const std::size_t S = static_cast<std::size_t>(sc.o.stations);
  double nees = 0, warn = 0, e2 = 0, s2 = 0, emax = 0;
  std::vector<double> bias(S, 0.0);
  double se_est = 0, se_true = 0, se_zero = 0, ne_est = 0, ne_true = 0, n_est = 0, n_true = 0, n_zero = 0, dummy = 0;
  double sigma_sum = 0, range_lo = 1e30, range_hi = 0;
  for (int run = 0; run < runs; ++run) {
    rk::sim::MultistationOptions o = sc.o;
    o.seed = 1000 + static_cast<std::uint64_t>(run);
    const rk::sim::MultistationScenario sim(o);
    const Trial t = MakeTrial(sim);
    for (const auto& st : sim.stations()) {
      for (double r : st.true_range_m) {
        range_lo = std::min(range_lo, r);
        range_hi = std::max(range_hi, r);
      }
    }
    std::vector<StationTrack> start;
    rk::intersect::OffsetTarget target;
    for (std::size_t s = 0; s < S; ++s) start.emplace_back(t.files[s], rk::intersect::IntersectOptions{}.Defaults());
    for (std::size_t s = 0; s < S; ++s) {
      target.station.push_back(static_cast<int>(s));
      target.track.push_back(&start[s]);
    }
    rk::intersect::TimeOffsetOptions to;
    to.knot_interval_s = g_knot_s;
    if (std::getenv("RK_ACCEL_SIGMA")) to.accel_sigma_mps2 = std::atof(std::getenv("RK_ACCEL_SIGMA"));
    const rk::intersect::TimeOffsetFit fit = rk::intersect::EstimateTimeOffsets(t.stations, {target}, to);
    // Offsets of stations 2..S (station 1 the reference).
    const Eigen::Index m = static_cast<Eigen::Index>(S - 1);
    Eigen::VectorXd e(m);
    Eigen::MatrixXd C(m, m);
    for (Eigen::Index a = 0; a < m; ++a) {
      const std::size_t sa = static_cast<std::size_t>(a + 1);
      e(a) = fit.offset_s[sa] - t.truth[sa];
      bias[sa] += e(a);
      for (Eigen::Index b = 0; b < m; ++b) {
        const std::size_t sb = static_cast<std::size_t>(b + 1);
        C(a, b) = fit.correlation(a + 1, b + 1) * fit.sigma_s[sa] * fit.sigma_s[sb];
      }
      e2 += e(a) * e(a);
      s2 += fit.sigma_s[sa] * fit.sigma_s[sa];
      sigma_sum += fit.sigma_s[sa];
      emax = std::max(emax, std::abs(e(a)) / fit.sigma_s[sa]);
    }
    nees += e.dot(C.ldlt().solve(e));
    warn += fit.warnings.empty() ? 0 : 1;
    Trajectory(sim, t, fit.offset_s, &fit.sigma_s, &se_est, &ne_est, &n_est);
    Trajectory(sim, t, t.truth, nullptr, &se_true, &ne_true, &n_true);
    Trajectory(sim, t, std::vector<double>(S, 0.0), nullptr, &se_zero, &dummy, &n_zero);
  }
  const double k = static_cast<double>(runs), dof = static_cast<double>(S - 1);
  // 95 % band of the mean NEES over the runs: χ²(runs·dof)/runs, Wilson–Hilferty.
  auto chi2q = [](double nu, double z) {
    const double a = 2.0 / (9.0 * nu);
    return nu * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
  };
  const double lo = chi2q(k * dof, -1.96) / k, hi = chi2q(k * dof, 1.96) / k;
  std::printf("| %s (%.0f–%.0f km) | %d | ", sc.name, range_lo / 1e3, range_hi / 1e3, runs);
  for (std::size_t s = 1; s < S; ++s) std::printf("%s%.4f", s > 1 ? ", " : "", 1e3 * bias[s] / k);
  std::printf(" | %.4f | %.4f | %.2f | %.2f | %.2f [%.2f, %.2f] | %.0f %% | %.3f | %.3f | %.3f | %.2f |\n",
              1e3 * std::sqrt(e2 / (k * dof)), 1e3 * sigma_sum / (k * dof), std::sqrt(e2 / s2), emax, nees / k, lo, hi,
              100.0 * warn / k, std::sqrt(se_est / n_est), std::sqrt(se_true / n_true) > 0 ? std::sqrt(se_est / n_est) / std::sqrt(se_true / n_true) : 0.0,
              std::sqrt(se_zero / n_zero) / std::sqrt(se_true / n_true), ne_est / n_est / 3.0);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 100;
  g_knot_s = argc > 2 ? std::atof(argv[2]) : 0.0;
  const bool only_first = argc > 3;  // argv[3]: the first scenario only (a quick comparison)
  rk::sim::MultistationOptions base;
  base.baseline_km = 10.0;
  base.sigma_angle_arcsec = 2.0;
  base.rate_hz = 20.0;
  base.duration_s = 60.0;
  base.time_offsets = "s2:0.0043,s3:-0.0117";
  std::vector<Scenario> scenarios;
  {
    Scenario s{"climbing turn, 3 stations (triangle)", base};
    s.o.path = rk::sim::MultistationPath::kTurn;
    scenarios.push_back(s);
    {
      Scenario far{"climbing turn, 15 km baseline, from 6 km up", s.o};
      far.o.baseline_km = 15.0;
      far.o.height_m = 6000.0;
      scenarios.push_back(far);
    }
    s.name = "climbing turn, 4 stations";
    s.o.stations = 4;
    s.o.time_offsets = "s2:0.0043,s3:-0.0117,s4:0.0021";
    scenarios.push_back(s);
    s.name = "climbing turn, offsets of tens of ms";
    s.o.stations = 3;
    s.o.time_offsets = "s2:0.037,s3:-0.052";
    scenarios.push_back(s);
    s = Scenario{"straight level pass, triangle", base};
    s.o.path = rk::sim::MultistationPath::kCrossing;
    scenarios.push_back(s);
    s.name = "degenerate: stations on a line, pass along it";
    s.o.layout = rk::sim::MultistationLayout::kLine;
    scenarios.push_back(s);
    s = Scenario{"ballistic arc, triangle", base};
    scenarios.push_back(s);
  }
  std::printf("\n%d Monte Carlo runs per scenario (seeds 1000..), 60 s, 2 arcsec, 20/25/16(/30) Hz, baseline 10 km:\n\n", runs);
  std::printf("| scenario | runs | mean error (ms) | RMS error (ms) | mean 1σ (ms) | RMS err / RMS σ | max |err|/σ | mean NEES "
              "[95 %% band] | warned | trajectory 3-D RMS (m) | ÷ with true offsets | ÷ without estimation | "
              "trajectory NEES / 3 |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Scenario& s : scenarios) {
    Run(s, runs);
    if (only_first) return 0;
  }

  // Speed: one 10-minute three-station trial at 20 Hz (turn at 100 m/s), estimation alone, one core.
  rk::sim::MultistationOptions lo = base;
  lo.path = rk::sim::MultistationPath::kTurn;
  lo.duration_s = 600.0;
  lo.speed_mps = 100.0;
  const rk::sim::MultistationScenario sim(lo);
  const Trial t = MakeTrial(sim);
  std::vector<StationTrack> start;
  rk::intersect::OffsetTarget target;
  for (std::size_t s = 0; s < t.files.size(); ++s) start.emplace_back(t.files[s], rk::intersect::IntersectOptions{}.Defaults());
  for (std::size_t s = 0; s < start.size(); ++s) {
    target.station.push_back(static_cast<int>(s));
    target.track.push_back(&start[s]);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const rk::intersect::TimeOffsetFit fit = rk::intersect::EstimateTimeOffsets(t.stations, {target}, {});
  const auto t1 = std::chrono::steady_clock::now();
  double se = 0, ne = 0, n = 0;
  Trajectory(sim, t, fit.offset_s, &fit.sigma_s, &se, &ne, &n);
  const auto t2 = std::chrono::steady_clock::now();
  std::printf("\n10-minute trial, 3 stations (%zu rows, %zu parameters): estimation %.2f s, the intersection after it "
              "%.2f s (ratio %.1f)\n",
              fit.observations, fit.parameters, std::chrono::duration<double>(t1 - t0).count(),
              std::chrono::duration<double>(t2 - t1).count(),
              std::chrono::duration<double>(t1 - t0).count() / std::chrono::duration<double>(t2 - t1).count());
  return 0;
}

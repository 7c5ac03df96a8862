// Accuracy figures for rk-smooth resample (a figure-printing program: it reports, it never
// asserts; tests/filter/test_resample.cc asserts the chosen defaults with fewer seeds).
//
// Seed 001's case: the true slant range |p_enu(t)| of lib/sim trajectories (target moving up
// to 3 m/s, speed changing all the time on the default trajectory) sampled at 5 Hz with
// white Gaussian noise of 0.35 mm (seed 001: static range std 0.354 mm), resampled to 20 Hz
// frame times with each method and compared with the true range at those times. The range
// clock has a random phase against the frame clock. Figures go into
// docs/rk-smooth-singer-resample.md.
//
//   range_resample_accuracy [seeds=20]
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "filter/resample.h"
#include "filter/series.h"
#include "filter/singer_series.h"
#include "sim/trajectory.h"
#include "track/singer.h"

namespace {

constexpr double kRangeRateHz = 5.0;
constexpr double kFrameRateHz = 20.0;
constexpr double kRangeNoiseM = 0.35e-3;
constexpr double kDurationS = 12.0;

struct Accum {
  double sum_sq = 0.0, max_abs = 0.0;
  std::size_t n = 0;
  void Add(double e) {
    sum_sq += e * e;
    max_abs = std::max(max_abs, std::abs(e));
    ++n;
  }
  double Rms() const { return n ? std::sqrt(sum_sq / static_cast<double>(n)) : std::nan(""); }
};

// A true range history r(t) (m).
struct Case {
  std::string name;
  std::function<double(double)> range_m;
};

// Range changing speed abruptly: plateaus of constant range rate (uniform in [−3, 3] m/s,
// 0.5–2 s long) joined by constant accelerations of ±kStepAccelMps2 (piecewise-quadratic
// range, acceleration jumping between 0 and ±2 m/s²: the hardest case for every method).
constexpr double kStepAccelMps2 = 2.0;
std::function<double(double)> SpeedSteps(std::uint64_t seed) {
  struct Piece {
    double t0, r0, v0, a;
  };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> speed(-3.0, 3.0), hold(0.5, 2.0);
  std::vector<Piece> pieces;
  double t = -1.0, r = 50.0, v = speed(rng);
  while (t < kDurationS + 2.0) {
    const double dwell = hold(rng);
    pieces.push_back({t, r, v, 0.0});
    r += v * dwell;
    t += dwell;
    const double v1 = speed(rng);
    const double a = v1 > v ? kStepAccelMps2 : -kStepAccelMps2;
    const double ramp = (v1 - v) / a;
    pieces.push_back({t, r, v, a});
    r += v * ramp + 0.5 * a * ramp * ramp;
    t += ramp;
    v = v1;
  }
  return [pieces](double tq) {
    std::size_t k = 0;
    while (k + 1 < pieces.size() && pieces[k + 1].t0 <= tq) ++k;
    const Piece& p = pieces[k];
    const double dt = tq - p.t0;
    return p.r0 + p.v0 * dt + 0.5 * p.a * dt * dt;
  };
}

std::function<double(double)> SimRange(const rk::sim::TrajectoryOptions& o) {
  const auto traj = std::make_shared<rk::sim::Trajectory>(o);
  return [traj](double t) { return traj->PositionEnu(t).norm(); };
}

std::vector<Case> Cases() {
  std::vector<Case> cases;
  for (double r : {40.0, 80.0, 120.0}) {
    rk::sim::TrajectoryOptions o;
    o.kind = rk::sim::TrajectoryKind::kDefault;
    o.range_m = r;
    o.speed_mps = 3.0;
    cases.push_back({"default R=" + std::to_string(static_cast<int>(r)) + " v=3", SimRange(o)});
  }
  {
    rk::sim::TrajectoryOptions o;
    o.kind = rk::sim::TrajectoryKind::kStraight;
    o.range_m = 20.0;
    o.speed_mps = 3.0;
    cases.push_back({"straight R=20 v=3", SimRange(o)});
  }
  {
    rk::sim::TrajectoryOptions o;
    o.kind = rk::sim::TrajectoryKind::kTurning;
    o.range_m = 60.0;
    o.speed_mps = 3.0;
    o.turn_rate_rad_s = 0.3;
    cases.push_back({"turning R=60 v=3 w=0.3", SimRange(o)});
  }
  {
    rk::sim::TrajectoryOptions o;
    o.kind = rk::sim::TrajectoryKind::kOverhead;
    o.range_m = 30.0;
    o.speed_mps = 3.0;
    cases.push_back({"overhead R=30 v=3", SimRange(o)});
  }
  cases.push_back({"speed steps a=2 (A)", SpeedSteps(7)});
  cases.push_back({"speed steps a=2 (B)", SpeedSteps(8)});
  return cases;
}

// One simulated range log (5 Hz, random clock phase) as a Series, and the frame times.
rk::filter::Series MakeLog(const std::function<double(double)>& truth, std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, kRangeNoiseM);
  std::uniform_real_distribution<double> phase(0.0, 1.0 / kRangeRateHz);
  const double t0 = phase(rng);
  rk::filter::Series s;
  s.source = "sim";
  s.columns = {"range_m"};
  s.is_angle = {false};
  for (double ts = t0; ts < kDurationS; ts += 1.0 / kRangeRateHz) s.t_s.push_back(ts);
  s.values.resize(static_cast<Eigen::Index>(s.t_s.size()), 1);
  for (std::size_t i = 0; i < s.t_s.size(); ++i) {
    s.values(static_cast<Eigen::Index>(i), 0) = truth(s.t_s[i]) + noise(rng);
  }
  return s;
}

std::vector<double> FrameTimes() {
  std::vector<double> t;
  for (int k = 0; k * (1.0 / kFrameRateHz) < kDurationS; ++k) t.push_back(k / kFrameRateHz);
  return t;
}

struct Variant {
  std::string name;
  rk::filter::ResampleOptions opt;
  bool predict_from_previous = false;  // kalman alternative: Ψ(τ) x_{k|N} from the previous row
};

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
  const std::vector<Case> cases = Cases();
  const std::vector<double> frames = FrameTimes();

  std::vector<Variant> variants;
  {
    Variant v;
    v.name = "linear";
    v.opt.method = rk::filter::ResampleMethod::kLinear;
    variants.push_back(v);
    v.name = "cubic";
    v.opt.method = rk::filter::ResampleMethod::kCubic;
    variants.push_back(v);
    v.name = "kalman (default)";
    v.opt.method = rk::filter::ResampleMethod::kKalman;
    variants.push_back(v);
    v.name = "kalman, fixed sigma_m";
    v.opt.singer.auto_accel_sigma = false;
    variants.push_back(v);
    v.opt.singer.auto_accel_sigma = true;
    v.name = "kalman, sigma_z given";
    v.opt.singer.meas_sigma = {kRangeNoiseM};
    variants.push_back(v);
    v.opt.singer.meas_sigma.clear();
    v.name = "kalman, predict-from-prev";
    v.predict_from_previous = true;
    variants.push_back(v);
  }

  std::printf("# Range resampling to %g Hz frame times from a %g Hz log with %.2f mm white noise; %d seeds x %g s\n",
              kFrameRateHz, kRangeRateHz, kRangeNoiseM * 1e3, seeds, kDurationS);
  std::printf("# kalman defaults: tau_m = %g s, sigma_m by max. likelihood around %g m/s^2 (fixed variant: that "
              "value), sigma_z estimated (MAD of %d-th differences)\n",
              rk::filter::kDefaultManeuverTimeS, rk::filter::kDefaultAccelSigmaMps2,
              rk::filter::kNoiseDifferenceOrder);
  std::printf("%-24s %-28s %10s %10s\n", "trajectory", "method", "rms_mm", "max_mm");
  std::vector<Accum> overall(variants.size());
  std::vector<double> sigma_est3, sigma_est4;
  for (const Case& c : cases) {
    const auto& truth = c.range_m;
    std::vector<Accum> acc(variants.size());
    for (int seed = 0; seed < seeds; ++seed) {
      std::mt19937_64 rng(1000 + seed);
      const rk::filter::Series log = MakeLog(truth, rng);
      {
        std::vector<double> v(log.rows());
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = log.values(static_cast<Eigen::Index>(i), 0);
        sigma_est3.push_back(rk::filter::EstimateNoiseSigma(v, false, 3));
        sigma_est4.push_back(rk::filter::EstimateNoiseSigma(v, false, 4));
      }
      for (std::size_t m = 0; m < variants.size(); ++m) {
        const Variant& var = variants[m];
        if (var.predict_from_previous) {
          const auto sr = rk::filter::RunSingerSeries(log, var.opt.singer);
          for (double tf : frames) {
            if (tf < log.t_s.front() || tf > log.t_s.back()) continue;
            std::size_t k = 0;
            while (k + 1 < log.rows() && log.t_s[k + 1] <= tf) ++k;
            const Eigen::Vector3d x =
                rk::track::SingerTransition(tf - log.t_s[k], sr.tracks[0].a_per_s) * sr.tracks[0].x_smooth[k];
            const double e = x(0) - truth(tf);
            acc[m].Add(e);
            overall[m].Add(e);
          }
          continue;
        }
        const rk::filter::ResampleResult r = rk::filter::Resample(log, frames, var.opt);
        for (std::size_t i = 0; i < frames.size(); ++i) {
          if (r.reason[i] != rk::filter::ResampleReason::kNone) continue;
          const double e = r.values[0][i] - truth(frames[i]);
          acc[m].Add(e);
          overall[m].Add(e);
        }
      }
    }
    for (std::size_t m = 0; m < variants.size(); ++m) {
      std::printf("%-24s %-28s %10.4f %10.4f\n", c.name.c_str(), variants[m].name.c_str(), acc[m].Rms() * 1e3,
                  acc[m].max_abs * 1e3);
    }
  }
  for (std::size_t m = 0; m < variants.size(); ++m) {
    std::printf("%-24s %-28s %10.4f %10.4f\n", "ALL", variants[m].name.c_str(), overall[m].Rms() * 1e3,
                overall[m].max_abs * 1e3);
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s / static_cast<double>(v.size());
  };
  std::printf("\n# sigma_z estimate (true %.3f mm), mean over all logs: 3rd differences %.4f mm, 4th %.4f mm\n",
              kRangeNoiseM * 1e3, mean(sigma_est3) * 1e3, mean(sigma_est4) * 1e3);

  // Tuning grid of the Singer parameters (kalman, sigma_z estimated): RMS over the lib/sim
  // trajectories and over the speed-step histories separately.
  const std::vector<double> taus = {0.5, 1.0, 2.0, 5.0, 10.0};
  const std::vector<double> sigmas = {0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0};
  for (int group = 0; group < 2; ++group) {
    std::printf("\n# kalman tuning grid, %s: RMS (mm), %d seeds; rows tau_m (s), columns sigma_m (m/s^2)\n",
                group == 0 ? "lib/sim trajectories" : "speed steps", seeds);
    std::printf("%-10s", "tau\\sig");
    for (double sg : sigmas) std::printf(" %8.2f", sg);
    std::printf("\n");
    for (double tau : taus) {
      std::printf("%-10.1f", tau);
      for (double sig : sigmas) {
        Accum a;
        rk::filter::ResampleOptions o;
        o.method = rk::filter::ResampleMethod::kKalman;
        o.singer.maneuver_time_s = tau;
        o.singer.accel_sigma = {sig};
        for (const Case& c : cases) {
          const bool steps = c.name.rfind("speed steps", 0) == 0;
          if (steps != (group == 1)) continue;
          const auto& truth = c.range_m;
          for (int seed = 0; seed < seeds; ++seed) {
            std::mt19937_64 rng(1000 + seed);
            const rk::filter::Series log = MakeLog(truth, rng);
            const rk::filter::ResampleResult r = rk::filter::Resample(log, frames, o);
            for (std::size_t i = 0; i < frames.size(); ++i) {
              if (r.reason[i] == rk::filter::ResampleReason::kNone) a.Add(r.values[0][i] - truth(frames[i]));
            }
          }
        }
        std::printf(" %8.4f", a.Rms() * 1e3);
      }
      std::printf("\n");
    }
  }
  return 0;
}

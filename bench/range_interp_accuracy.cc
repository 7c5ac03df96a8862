// Accuracy figures for the interpolation choices of rk-locate (a benchmark:
// it reports, it never asserts; tests/locate asserts the chosen defaults).
//
// Range: the true slant range |p_enu(t)| of lib/sim trajectories is sampled
// at 5 Hz (seed 001's rangefinder) with white Gaussian noise of 0.35 mm
// (seed 001: static range std 0.354 mm), interpolated to 20 Hz frame times
// by each method, and compared with the true range at the frame times.
// Turret: lib/sim's servo boresight (lag + band-limited jitter, 5″ RMS) is
// sampled at 50 Hz without noise and interpolated to frame times; the error
// is the on-sky angle between interpolated and true boresight.
// Output: fixed-width tables on stdout; figures go into docs/rk-locate.md.
//
//   range_interp_accuracy [seeds=20]
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "sim/trajectory.h"
#include "sim/turret_servo.h"
#include "track/interp.h"

namespace {

constexpr double kRangeRateHz = 5.0;
constexpr double kFrameRateHz = 20.0;
constexpr double kTurretRateHz = 50.0;
constexpr double kRangeNoiseM = 0.35e-3;
constexpr double kDurationS = 12.0;

struct Method {
  std::string name;
  rk::track::InterpMethod method;
  int window;
};

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

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
  const std::vector<Method> methods = {
      {"linear", rk::track::InterpMethod::kLinear, 3},
      {"cubic", rk::track::InterpMethod::kCubic, 3},
      {"local-quadratic w=2", rk::track::InterpMethod::kLocalQuadratic, 2},
      {"local-quadratic w=3", rk::track::InterpMethod::kLocalQuadratic, 3},
      {"local-quadratic w=4", rk::track::InterpMethod::kLocalQuadratic, 4},
      {"local-quadratic w=5", rk::track::InterpMethod::kLocalQuadratic, 5},
      {"local-quadratic w=7", rk::track::InterpMethod::kLocalQuadratic, 7},
      {"local-cubic w=3", rk::track::InterpMethod::kLocalCubic, 3},
      {"local-cubic w=4", rk::track::InterpMethod::kLocalCubic, 4},
      {"local-cubic w=5", rk::track::InterpMethod::kLocalCubic, 5},
  };
  struct Case {
    std::string name;
    rk::sim::TrajectoryOptions opt;
  };
  std::vector<Case> cases;
  for (double r : {40.0, 80.0, 120.0}) {
    rk::sim::TrajectoryOptions o;
    o.kind = rk::sim::TrajectoryKind::kDefault;
    o.range_m = r;
    o.speed_mps = 3.0;
    cases.push_back({"default R=" + std::to_string(static_cast<int>(r)) + " v=3", o});
  }
  {
    rk::sim::TrajectoryOptions o;
    o.kind = rk::sim::TrajectoryKind::kStraight;
    o.range_m = 40.0;
    o.speed_mps = 3.0;
    cases.push_back({"straight R=40 v=3", o});
  }
  {
    rk::sim::TrajectoryOptions o;
    o.kind = rk::sim::TrajectoryKind::kTurning;
    o.range_m = 60.0;
    o.speed_mps = 3.0;
    o.turn_rate_rad_s = 0.3;
    cases.push_back({"turning R=60 v=3 w=0.3", o});
  }

  std::printf(
      "# Range interpolation to %g Hz frame times from a %g Hz log with %.2f mm white noise; %d seeds x %g "
      "s\n",
      kFrameRateHz, kRangeRateHz, kRangeNoiseM * 1e3, seeds, kDurationS);
  std::printf("%-24s %-22s %10s %10s\n", "trajectory", "method", "rms_mm", "max_mm");
  std::vector<Accum> overall(methods.size());
  for (const Case& c : cases) {
    const rk::sim::Trajectory traj(c.opt);
    std::vector<Accum> acc(methods.size());
    for (int seed = 0; seed < seeds; ++seed) {
      std::mt19937_64 rng(1000 + seed);
      std::normal_distribution<double> noise(0.0, kRangeNoiseM);
      std::uniform_real_distribution<double> phase(0.0, 1.0 / kRangeRateHz);
      const double t0 = phase(rng);  // range clock not aligned with frames
      std::vector<double> t;
      std::vector<std::optional<double>> r;
      for (double ts = t0; ts < kDurationS; ts += 1.0 / kRangeRateHz) {
        t.push_back(ts);
        r.push_back(traj.PositionEnu(ts).norm() + noise(rng));
      }
      for (std::size_t m = 0; m < methods.size(); ++m) {
        rk::track::InterpOptions io;
        io.method = methods[m].method;
        io.window = methods[m].window;
        const rk::track::TimeSeriesInterpolator interp(t, r, io);
        for (double tf = 0.0; tf < kDurationS; tf += 1.0 / kFrameRateHz) {
          const auto v = interp.At(tf);
          if (!v.ok()) continue;
          const double e = v.value - traj.PositionEnu(tf).norm();
          acc[m].Add(e);
          overall[m].Add(e);
        }
      }
    }
    for (std::size_t m = 0; m < methods.size(); ++m) {
      std::printf("%-24s %-22s %10.4f %10.4f\n", c.name.c_str(), methods[m].name.c_str(), acc[m].Rms() * 1e3,
                  acc[m].max_abs * 1e3);
    }
  }
  for (std::size_t m = 0; m < methods.size(); ++m) {
    std::printf("%-24s %-22s %10.4f %10.4f\n", "ALL", methods[m].name.c_str(), overall[m].Rms() * 1e3,
                overall[m].max_abs * 1e3);
  }

  // Noise-free range: the interpolation (bias) error alone.
  std::printf("\n# Same, noise-free range log (interpolation bias only), default R=40 v=3\n");
  {
    const rk::sim::Trajectory traj(cases[0].opt);
    std::vector<double> t;
    std::vector<std::optional<double>> r;
    for (double ts = 0.05; ts < kDurationS; ts += 1.0 / kRangeRateHz) {
      t.push_back(ts);
      r.push_back(traj.PositionEnu(ts).norm());
    }
    for (const Method& m : methods) {
      rk::track::InterpOptions io;
      io.method = m.method;
      io.window = m.window;
      const rk::track::TimeSeriesInterpolator interp(t, r, io);
      Accum a;
      for (double tf = 0.0; tf < kDurationS; tf += 1.0 / kFrameRateHz) {
        const auto v = interp.At(tf);
        if (v.ok()) a.Add(v.value - traj.PositionEnu(tf).norm());
      }
      std::printf("%-24s %-22s %10.4f %10.4f\n", "default R=40 v=3", m.name.c_str(), a.Rms() * 1e3,
                  a.max_abs * 1e3);
    }
  }

  // Turret boresight interpolation.
  std::printf(
      "\n# Turret boresight (servo lag 0.15 s + 5\" RMS jitter 0.5-5 Hz) from %g Hz to %g Hz frames; "
      "arcsec\n",
      kTurretRateHz, kFrameRateHz);
  std::printf("%-24s %-22s %10s %10s\n", "trajectory", "method", "rms_as", "max_as");
  for (const Case& c : cases) {
    const rk::sim::Trajectory traj(c.opt);
    Accum lin, cub;
    for (int seed = 0; seed < seeds; ++seed) {
      const rk::sim::TurretServo servo(
          rk::sim::TurretServoOptions{}, [&](double ts) { return traj.PositionEnu(ts); }, 0.0, kDurationS,
          static_cast<std::uint64_t>(seed));
      std::vector<double> t;
      std::vector<std::optional<double>> az, el;
      for (double ts = 0.0; ts <= kDurationS; ts += 1.0 / kTurretRateHz) {
        const auto b = servo.Boresight(ts);
        t.push_back(ts);
        az.push_back(b.az_rad);
        el.push_back(b.el_rad);
      }
      for (int m = 0; m < 2; ++m) {
        rk::track::InterpOptions io;
        io.method = m == 0 ? rk::track::InterpMethod::kLinear : rk::track::InterpMethod::kCubic;
        io.angle = true;
        const rk::track::TimeSeriesInterpolator ia(t, az, io);
        io.angle = false;
        const rk::track::TimeSeriesInterpolator ie(t, el, io);
        for (double tf = 0.01; tf < kDurationS - 0.05; tf += 1.0 / kFrameRateHz) {
          const auto a = ia.At(tf), e = ie.At(tf);
          if (!a.ok() || !e.ok()) continue;
          const auto b = servo.Boresight(tf);
          const Eigen::Vector3d d1 = rk::geo::DirectionFromAzEl(a.value, e.value);
          const Eigen::Vector3d d0 = rk::geo::DirectionFromAzEl(b.az_rad, b.el_rad);
          const double ang = std::atan2(d1.cross(d0).norm(), d1.dot(d0)) * rk::geo::kArcsecPerRad;
          (m == 0 ? lin : cub).Add(ang);
        }
      }
    }
    std::printf("%-24s %-22s %10.5f %10.5f\n", c.name.c_str(), "linear", lin.Rms(), lin.max_abs);
    std::printf("%-24s %-22s %10.5f %10.5f\n", c.name.c_str(), "cubic", cub.Rms(), cub.max_abs);
  }
  return 0;
}

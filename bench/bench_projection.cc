// Cost of the one camera and turret geometry (camera/projection.h, issue 28 item 1) in the loops that call it per
// sample: rk-locate's line of sight without and with a pointing model, its 1σ (a 14-input jet per row), the
// ENU → pixel projection of the simulators, and the lens-board renderer's table of undistorted pixel corners
// (one Newton inversion per corner of a 2448 × 2048 sensor). Only public API that predates the change, so the same
// file measures the tree before it (docs/benchmarks.md gives both and the ratio).
// Run (Release): build/bench/bench_projection
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "camera/camera_model.h"
#include "geo/angles.h"
#include "locate/locate_sigma.h"
#include "sim/lens_board.h"

namespace {

rk::camera::CameraModel DistortedCamera() {
  rk::camera::CameraModel c;  // 2448 × 2048, 3.45 µm, 50 mm
  c.distortion = {-0.12, 0.05, 0.0004, -0.0002, 0.01};
  c.mount_yaw_rad = rk::geo::DegToRad(0.05);
  c.mount_roll_rad = rk::geo::DegToRad(0.2);
  return c;
}

struct Sample {
  Eigen::Vector2d px;
  double az, el;
};

std::vector<Sample> Samples() {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sample> s(4096);
  for (auto& x : s) x = {{u(rng) * 2447, u(rng) * 2047}, u(rng) * 6.28, u(rng) * 1.4};
  return s;
}

void BM_RayEnu(benchmark::State& state) {
  const rk::camera::CameraModel cam = DistortedCamera();
  rk::geo::PointingTerms terms;
  if (state.range(0)) terms = {1e-3, -4e-4, 2e-4, 3e-4};
  const std::vector<Sample> s = Samples();
  std::size_t i = 0;
  for (auto _ : state) {
    const Sample& x = s[i++ & 4095];
    benchmark::DoNotOptimize(cam.RayEnu(x.px, x.az, x.el, terms));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RayEnu)->Arg(0)->Arg(1)->ArgName("pointing");

void BM_ProjectEnu(benchmark::State& state) {
  const rk::camera::CameraModel cam = DistortedCamera();
  const std::vector<Sample> s = Samples();
  std::vector<Eigen::Vector3d> dirs;
  for (const Sample& x : s) dirs.push_back(cam.RayEnu(x.px, x.az, x.el));
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 4095;
    benchmark::DoNotOptimize(cam.ProjectEnu(dirs[k], s[k].az, s[k].el));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ProjectEnu);

void BM_LocatedCovariance(benchmark::State& state) {
  const rk::camera::CameraModel cam = DistortedCamera();
  const rk::geo::PointingTerms terms{1e-3, -4e-4, 2e-4, 3e-4};
  rk::locate::SigmaSources src;
  src.turret_rad = 2e-5;
  src.pointing_rad = {1e-5, 1e-5, 1e-5, 1e-5};
  src.range_m = 0.5;
  const std::vector<Sample> s = Samples();
  std::size_t i = 0;
  for (auto _ : state) {
    const Sample& x = s[i++ & 4095];
    rk::locate::SigmaPoint p;
    p.px = x.px;
    p.sigma_px = {0.1, 0.1};
    p.az_rad = x.az;
    p.el_rad = x.el;
    p.range_m = 2000.0;
    benchmark::DoNotOptimize(rk::locate::LocatedCovarianceAt(cam, terms, p, src));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LocatedCovariance);

void BM_BoardRendererTable(benchmark::State& state) {
  const rk::camera::CameraModel cam = DistortedCamera();
  for (auto _ : state) {
    const rk::sim::BoardRenderer r(cam);
    benchmark::DoNotOptimize(&r);
  }
  state.SetItemsProcessed(state.iterations() * (cam.width_px + 1) * (cam.height_px + 1));
}
BENCHMARK(BM_BoardRendererTable)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

// Speed of the seed 004 cylinder attitude pieces (docs/benchmarks.md, issue 4):
//   BM_SolveP3P / BM_SolveSearch  one frame's isosceles P3P at the paper's geometry (1132 m, E 16.274°),
//                                 exact rays and 0.3-px noisy rays
//   BM_Jacobian                   the autodiff Jacobian (10 inputs → 5 outputs) of one frame
//   BM_ExtractSilhouette          rk-extract silhouette on one rendered 1536×1536 frame (in memory)
//   BM_ImageFit                   rk-attitude cylinder --video's image fit of one such frame (298-px image),
//                                 from the three-point solution of the extracted points
#include <benchmark/benchmark.h>

#include <random>

#include "attitude/cylinder_budget.h"
#include "attitude/cylinder_image_fit.h"
#include "attitude/cylinder_solve.h"
#include "extract/silhouette.h"
#include "geo/angles.h"
#include "sim/theodolite_render.h"
#include "sim/theodolite_scene.h"
#include "target/cylinder.h"

namespace {

using namespace rk;

struct Geometry {
  attitude::CylinderRays exact, noisy;
  target::CylinderShape shape{2.5, 0.25};
  attitude::CylinderInputs x;
  Eigen::Vector3d R;
};

const Geometry& Paper() {
  static const Geometry g = [] {
    Geometry g;
    target::CylinderShape shape;
    const double A = geo::DegToRad(326.2), E = geo::DegToRad(16.274);
    const target::CylinderPose pose = target::PoseAt(1132.0, A, E, geo::DegToRad(76.211), geo::DegToRad(31.257), shape);
    const target::SilhouettePoints3d p = target::SilhouettePointsOf(pose, shape);
    const camera::CameraModel cam = sim::Seed004Camera();
    g.exact = {p.nose.normalized(), p.tail1.normalized(), p.tail2.normalized()};
    std::mt19937_64 rng(1);
    std::normal_distribution<double> n(0.0, 0.3);
    const Eigen::Vector3d* pts[3] = {&p.nose, &p.tail1, &p.tail2};
    Eigen::Vector3d* rays[3] = {&g.noisy.nose, &g.noisy.tail1, &g.noisy.tail2};
    g.x(0) = A;
    g.x(1) = E;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d px = *cam.ProjectEnu(*pts[i], A, E);
      g.x(2 + 2 * i) = px.x();
      g.x(3 + 2 * i) = px.y();
      *rays[i] = cam.RayEnu(px + Eigen::Vector2d(n(rng), n(rng)), A, E);
    }
    g.x(8) = 2.5;
    g.x(9) = 0.25;
    g.R = attitude::SolveCylinder(g.exact, g.shape, attitude::CylinderSolveOptions{}).solutions.front().range_m;
    return g;
  }();
  return g;
}

void Solve(benchmark::State& state, attitude::CylinderMethod m, bool noisy) {
  const Geometry& g = Paper();
  attitude::CylinderSolveOptions o;
  o.method = m;
  long evals = 0;
  for (auto _ : state) {
    const auto r = attitude::SolveCylinder(noisy ? g.noisy : g.exact, g.shape, o);
    evals = r.function_evaluations;
    benchmark::DoNotOptimize(r.solutions.data());
  }
  state.counters["branch_evals"] = static_cast<double>(evals);
}
void BM_SolveP3P(benchmark::State& s) { Solve(s, attitude::CylinderMethod::kP3P, s.range(0) != 0); }
void BM_SolveSearch(benchmark::State& s) { Solve(s, attitude::CylinderMethod::kSearch, s.range(0) != 0); }
BENCHMARK(BM_SolveP3P)->Arg(0)->Arg(1);
BENCHMARK(BM_SolveSearch)->Arg(0)->Arg(1);

void BM_Jacobian(benchmark::State& state) {
  const Geometry& g = Paper();
  const camera::CameraModel cam = sim::Seed004Camera();
  attitude::CylinderJacobianMatrix J;
  for (auto _ : state) {
    benchmark::DoNotOptimize(attitude::CylinderJacobian(cam, g.x, g.R, &J));
  }
}
BENCHMARK(BM_Jacobian);

void BM_ExtractSilhouette(benchmark::State& state) {
  sim::TheodoliteSimOptions o;
  o.duration_s = 0.0;
  const sim::TheodoliteSimulator sim(o);
  std::mt19937_64 rng(3);
  const cv::Mat img = sim::RenderSilhouetteFrame(o.camera, sim.frames()[0], o.shape, sim::SilhouetteRenderOptions{}, rng);
  const extract::SilhouetteOptions eo;
  for (auto _ : state) {
    const auto r = extract::ExtractSilhouette(img, eo);
    benchmark::DoNotOptimize(r.px.data());
  }
}
BENCHMARK(BM_ExtractSilhouette)->Unit(benchmark::kMillisecond);

void BM_ImageFit(benchmark::State& state) {
  sim::TheodoliteSimOptions o;
  o.duration_s = 0.0;
  const sim::TheodoliteSimulator sim(o);
  const sim::TheodoliteFrameTruth& f = sim.frames()[0];
  std::mt19937_64 rng(3);
  const cv::Mat img = sim::RenderSilhouetteFrame(o.camera, f, o.shape, sim::SilhouetteRenderOptions{}, rng);
  const extract::SilhouetteResult ex = extract::ExtractSilhouette(img, extract::SilhouetteOptions{});
  const double A = f.boresight_az_rad, E = f.boresight_el_rad;
  const attitude::CylinderRays rays{o.camera.RayEnu(ex.px[0], A, E), o.camera.RayEnu(ex.px[1], A, E),
                                    o.camera.RayEnu(ex.px[2], A, E)};
  const target::CylinderShape& target = o.shape;
  attitude::CylinderSolveOptions so;
  so.max_miss_rad = 1.0 / o.camera.fx();
  const auto sols = attitude::SolveCylinder(rays, target, so).solutions;
  const attitude::CylinderSolution* start = &sols.front();  // the one nearest the truth, as continuity would hold
  for (const auto& c : sols)
    if (attitude::AxisAngle(c.axis_enu, f.pose.Axis()) < attitude::AxisAngle(start->axis_enu, f.pose.Axis())) start = &c;
  attitude::CylinderImageFitResult r;
  for (auto _ : state) {
    r = attitude::FitCylinderImage(img, o.camera, A, E, target, start->tail_centre_enu, start->yaw_rad, start->pitch_rad,
                                   attitude::CylinderImageFitOptions{});
    benchmark::DoNotOptimize(r.yaw_rad);
  }
  state.counters["evaluations"] = r.evaluations;
  state.counters["iterations"] = r.iterations;
  state.counters["window_px"] = r.pixels;
}
BENCHMARK(BM_ImageFit)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

// The PnP solver (pose/pnp.h) against simulated truth (sim/attitude_problems.h).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "geo/angles.h"
#include "pose/pnp.h"
#include "pose_test_util.h"
#include "sim/attitude_problems.h"
#include "rk_test/matchers.h"

namespace rk::pose {
namespace {

using sim::PnpGeometry;
using sim::PnpProblem;
using testing::kNoiseFreeRad;
using testing::Normalised;
using testing::Problem;

TEST(PnpSolver, NoiseFreeIsExactForEveryGeometry) {
  PnpSolver solver;
  for (PnpGeometry g :
       {PnpGeometry::kBox, PnpGeometry::kPlanar, PnpGeometry::kNarrow, PnpGeometry::kNarrowPlanar}) {
    for (std::uint64_t k = 0; k < 50; ++k) {
      const PnpProblem pb = Problem(g, k, 0.0);
      const PnpResult r = solver.Solve(Normalised(pb, false), pb.p_body, {}, pb.fx, pb.fy);
      ASSERT_TRUE(r.ok) << r.failure;
      EXPECT_THAT((test::Pose{r.best.R_cam_body, r.best.t_cam}),
                  test::PoseNear(test::Pose{pb.R_cam_body, pb.t_cam}, kNoiseFreeRad, kNoiseFreeRad * pb.t_cam.norm()))
          << sim::PnpGeometryName(g) << k;
      EXPECT_LT(r.best.rms_px, 1e-6);
    }
  }
}

TEST(PnpSolver, NoisyRandomProblemsRarelyFail) {
  // 1000 box problems, 4–12 points, 0.1–1 px: a gross failure (> 5°) needs the ML minimum
  // itself to be wrong, which happens for a few 4-point problems (OpenCV SQPnP+LM fails on
  // 0.25 % of them; docs/benchmarks.md). Allow 0.5 %.
  constexpr int kMaxFailures = 5;
  PnpSolver solver;
  sim::PnpProblemOptions o;
  o.seed = 5;
  int failures = 0;
  double sum_rot_deg = 0;
  for (std::uint64_t k = 0; k < 1000; ++k) {
    const PnpProblem pb = sim::MakePnpProblem(o, k);
    const PnpResult r = solver.Solve(Normalised(pb, true), pb.p_body, {}, pb.fx, pb.fy);
    const double e = geo::RadToDeg(RotationAngle(r.best.R_cam_body, pb.R_cam_body));
    if (!r.ok || e > 5.0) {
      ++failures;
    } else {
      sum_rot_deg += e;
    }
  }
  EXPECT_LE(failures, kMaxFailures);
  EXPECT_LT(sum_rot_deg / (1000 - failures), 0.25);  // bench: mean 0.18° over 10 000
}

TEST(PnpSolver, FlagsTheTwoMinimaOfANearlyFrontalPlanarTarget) {
  // A 0.7 m square of 5 markers tilted 5° from facing a 100 mm camera at 15–25 m, 0.3 px noise:
  // the two minima (tilt mirrored about the line of sight, ≈ 10° apart) differ by a χ² of a few
  // units, so many frames are ambiguous (Δχ² < 9). Whatever the flag, one of the two minima is
  // the truth within the noise-limited tilt accuracy (≈ 1°, kTiltTolDeg with margin).
  constexpr double kTiltTolDeg = 3.0;
  sim::PnpProblemOptions o;
  o.geometry = PnpGeometry::kNarrowPlanar;
  o.noise_min_px = o.noise_max_px = 0.3;
  o.min_tilt_rad = o.max_tilt_rad = geo::DegToRad(5.0);
  o.min_points = o.max_points = 5;
  PnpSolver solver;
  int ambiguous = 0;
  for (std::uint64_t k = 0; k < 40; ++k) {
    const PnpProblem pb = sim::MakePnpProblem(o, k);
    const std::vector<double> sig(pb.p_body.size(), 0.3);
    const PnpResult r = solver.Solve(Normalised(pb, true), pb.p_body, sig, pb.fx, pb.fy);
    ASSERT_TRUE(r.ok);
    EXPECT_TRUE(r.second_start_run);
    double e = RotationAngle(r.best.R_cam_body, pb.R_cam_body);
    if (r.has_alt) e = std::min(e, RotationAngle(r.alt.R_cam_body, pb.R_cam_body));
    EXPECT_LT(geo::RadToDeg(e), kTiltTolDeg) << k;
    if (r.ambiguous) {
      ++ambiguous;
      EXPECT_TRUE(r.has_alt);
      EXPECT_LT(r.alt.chi2 - r.best.chi2, 9.0);
      EXPECT_GT(geo::RadToDeg(RotationAngle(r.best.R_cam_body, r.alt.R_cam_body)), 3.0);
    }
  }
  EXPECT_GE(ambiguous, 10);
  // Close range with a wide lens (4 m square at 4–8 m, f = 800 px) and 40° tilt, perspective
  // separates the two minima by hundreds in χ²: never ambiguous, and the best is the truth.
  // (At 15–25 m a 0.7 m square stays ambiguous even at 40°: the flag is physics, not a bug.)
  o.geometry = PnpGeometry::kPlanar;
  o.min_tilt_rad = o.max_tilt_rad = geo::DegToRad(40.0);
  for (std::uint64_t k = 0; k < 40; ++k) {
    const PnpProblem pb = sim::MakePnpProblem(o, k);
    const std::vector<double> sig(pb.p_body.size(), 0.3);
    const PnpResult r = solver.Solve(Normalised(pb, true), pb.p_body, sig, pb.fx, pb.fy);
    ASSERT_TRUE(r.ok);
    EXPECT_FALSE(r.ambiguous) << k;
    EXPECT_LT(geo::RadToDeg(RotationAngle(r.best.R_cam_body, pb.R_cam_body)), 1.0) << k;
  }
}

TEST(PnpSolver, DegenerateInputFailsWithReason) {
  PnpSolver solver;
  std::vector<Eigen::Vector2d> xn = {{0, 0}, {0.01, 0}, {0.02, 0}, {0.03, 0}};
  std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  const PnpResult r = solver.Solve(xn, line, {}, 1000, 1000);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.failure.find("collinear"), std::string::npos);
  const PnpResult r2 = solver.Solve(std::span(xn).first(2), std::span(line).first(2), {}, 1000, 1000);
  EXPECT_FALSE(r2.ok);
}

}  // namespace
}  // namespace rk::pose

// Weak-perspective start (pose/pose_init.h) against simulated truth (sim/attitude_problems.h).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "geo/angles.h"
#include "pose/oi.h"
#include "pose/pnp.h"
#include "pose/pose_init.h"
#include "pose_test_util.h"
#include "sim/attitude_problems.h"

namespace rk::pose {
namespace {

using sim::PnpGeometry;
using sim::PnpProblem;
using testing::Normalised;
using testing::Problem;
using testing::Rays;

TEST(WeakPerspectiveInit, NearTruthAtLongRangeAndMirrorIsTheOtherPlanarSolution) {
  // Narrow field, 15–25 m: weak perspective is accurate to the target's depth / range (≈ 2 %).
  constexpr double kWeakPerspectiveRad = 0.1;
  for (std::uint64_t k = 0; k < 20; ++k) {
    const PnpProblem pb = Problem(PnpGeometry::kNarrow, k, 0.0, 8, 12);
    const auto rays = Rays(Normalised(pb, false));
    const WeakPerspectiveStart s = WeakPerspectiveInit(rays, pb.p_body);
    ASSERT_TRUE(s.ok);
    EXPECT_FALSE(s.planar);
    EXPECT_LT(RotationAngle(s.R_cam_body[0], pb.R_cam_body), kWeakPerspectiveRad) << k;
    EXPECT_NEAR(s.scale * pb.t_cam.z(), 1.0, 0.05);
  }
  for (std::uint64_t k = 0; k < 20; ++k) {
    const PnpProblem pb = Problem(PnpGeometry::kNarrowPlanar, k, 0.0, 6, 12);
    const auto rays = Rays(Normalised(pb, false));
    const WeakPerspectiveStart s = WeakPerspectiveInit(rays, pb.p_body);
    ASSERT_TRUE(s.ok);
    EXPECT_TRUE(s.planar);
    const double e0 = RotationAngle(s.R_cam_body[0], pb.R_cam_body);
    const double e1 = RotationAngle(s.R_cam_body[1], pb.R_cam_body);
    EXPECT_LT(std::min(e0, e1), kWeakPerspectiveRad) << k;  // one of the two is the truth
    const WeakPerspectiveStart h = HomographyInit(rays, pb.p_body);
    ASSERT_TRUE(h.ok);
    EXPECT_LT(RotationAngle(h.R_cam_body[0], pb.R_cam_body), 1e-7) << k;  // exact without noise
  }
}

}  // namespace
}  // namespace rk::pose

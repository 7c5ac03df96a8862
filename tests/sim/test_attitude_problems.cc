// Random PnP problems (sim/attitude_problems.h): exact pixels, deterministic per seed and index.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "sim/attitude_problems.h"

namespace rk::sim {
namespace {

TEST(PnpProblems, ExactPixelsAndDeterminism) {
  for (PnpGeometry g : {PnpGeometry::kBox, PnpGeometry::kPlanar, PnpGeometry::kNarrow, PnpGeometry::kNarrowPlanar}) {
    PnpProblemOptions o;
    o.geometry = g;
    for (std::uint64_t k = 0; k < 20; ++k) {
      const PnpProblem a = MakePnpProblem(o, k), b = MakePnpProblem(o, k);
      ASSERT_EQ(a.px.size(), a.p_body.size());
      EXPECT_GE(a.px.size(), 4u);
      EXPECT_LE(a.px.size(), 12u);
      EXPECT_GE(a.noise_px, 0.1);
      EXPECT_LE(a.noise_px, 1.0);
      for (std::size_t i = 0; i < a.px.size(); ++i) {
        EXPECT_EQ(a.px[i], b.px[i]);
        const Eigen::Vector3d X = a.R_cam_body * a.p_body[i] + a.t_cam;
        EXPECT_NEAR(a.fx * X.x() / X.z() + a.cx, a.px_true[i].x(), 1e-9);
        EXPECT_GE(a.px_true[i].x(), 0.0);
        EXPECT_LE(a.px_true[i].x(), a.width_px - 1.0);
      }
      if (g == PnpGeometry::kPlanar || g == PnpGeometry::kNarrowPlanar) {
        for (const auto& p : a.p_body) EXPECT_EQ(p.z(), 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace rk::sim

// The matchers and the temporary folder do what their claims say (the support library is tested like the rest).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>

#include "rk_test/matchers.h"
#include "rk_test/temp_dir.h"

namespace rk::test {
namespace {

constexpr double kArcsec = geo::kPi / 180.0 / 3600.0;

TEST(Matchers, AzElNearWrapsAcrossNorth) {
  const geo::AzEl a{geo::DegToRad(359.9999), 0.3}, b{geo::DegToRad(0.0001), 0.3};
  EXPECT_THAT(a, AzElNear(b, 1.0 * kArcsec));
  EXPECT_THAT(a, ::testing::Not(AzElNear(b, 0.5 * kArcsec)));
  EXPECT_THAT(a, ::testing::Not(AzElNear(geo::AzEl{b.az_rad, 0.3 + 2 * kArcsec}, 1.0 * kArcsec)));
}

TEST(Matchers, EnuNearAndPoseNear) {
  EXPECT_THAT(Eigen::Vector3d(1, 2, 3), EnuNear(Eigen::Vector3d(1, 2, 3.0009), 0.001));
  EXPECT_THAT(Eigen::Vector3d(1, 2, 3), ::testing::Not(EnuNear(Eigen::Vector3d(1, 2, 3.002), 0.001)));
  Pose p, q;
  q.R = Eigen::AngleAxisd(geo::DegToRad(0.01), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  q.t = {0.0005, 0, 0};
  EXPECT_THAT(q, PoseNear(p, geo::DegToRad(0.011), 0.001));
  EXPECT_THAT(q, ::testing::Not(PoseNear(p, geo::DegToRad(0.009), 0.001)));
  EXPECT_THAT(q, ::testing::Not(PoseNear(p, geo::DegToRad(0.011), 0.0004)));
  // Accurate near zero (acos of the trace is not: it cannot see below ≈ 2e-8 rad).
  const Eigen::Matrix3d tiny = Eigen::AngleAxisd(1e-12, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NEAR(RotationAngleRad(Eigen::Matrix3d::Identity(), tiny), 1e-12, 1e-15);
}

TEST(TempDir, IsFreshAndRemovedWithItsContents) {
  std::string kept;
  {
    TempDir a("self"), b("self");
    EXPECT_NE(a.path(), b.path());
    EXPECT_TRUE(std::filesystem::is_empty(a.path()));
    WriteFile(a / "sub/file.txt", "x");
    EXPECT_TRUE(std::filesystem::exists(a / "sub/file.txt"));
    kept = a.path();
  }
  EXPECT_FALSE(std::filesystem::exists(kept));
}

}  // namespace
}  // namespace rk::test

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "geo/angles.h"
#include "geo/line_of_sight.h"

namespace rk::geo {
namespace {

constexpr double kExact = 1e-12;  // pure trigonometry, double precision

TEST(Angles, WrapToContractRanges) {
  EXPECT_NEAR(WrapDeg180(190.0), -170.0, kExact);
  EXPECT_NEAR(WrapDeg180(-180.0), 180.0, kExact);  // (-180, 180]
  EXPECT_NEAR(WrapDeg180(180.0), 180.0, kExact);
  EXPECT_NEAR(WrapDeg360(-0.5), 359.5, kExact);
  EXPECT_NEAR(WrapDeg360(720.25), 0.25, kExact);
  EXPECT_NEAR(AngleDiff(DegToRad(0.1), DegToRad(359.9)), DegToRad(0.2), kExact);
  EXPECT_NEAR(WrapPi(-kPi), kPi, kExact);
  EXPECT_GE(WrapTwoPi(-1e-18), 0.0);
  EXPECT_LT(WrapTwoPi(-1e-18), kTwoPi);
}

TEST(LineOfSight, TurretFrameIsRightHandedAndMatchesSpec) {
  for (double az : {0.0, 0.3, 3.0, 6.2}) {
    for (double el : {-0.5, 0.0, 0.7, 1.39}) {
      Eigen::Matrix3d R = RotationEnuFromTurret(az, el);
      EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 0.0, kExact);
      EXPECT_NEAR(R.determinant(), 1.0, kExact);  // r × d = b
      EXPECT_NEAR((R.col(2) - DirectionFromAzEl(az, el)).norm(), 0.0, kExact);
      AzEl ae = AzElFromEnu(R.col(2));
      EXPECT_NEAR(AngleDiff(ae.az_rad, az), 0.0, 1e-10);
      EXPECT_NEAR(ae.el_rad, el, 1e-10);
    }
  }
  // Boresight north and level: image right is east, image down is down.
  Eigen::Matrix3d R = RotationEnuFromTurret(0.0, 0.0);
  EXPECT_NEAR((R.col(0) - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, kExact);
  EXPECT_NEAR((R.col(1) - Eigen::Vector3d(0, 0, -1)).norm(), 0.0, kExact);
}

TEST(LineOfSight, AzimuthIsClockwiseFromNorth) {
  EXPECT_NEAR(RadToDeg(AzElFromEnu({1, 0, 0}).az_rad), 90.0, kExact);   // east
  EXPECT_NEAR(RadToDeg(AzElFromEnu({0, -1, 0}).az_rad), 180.0, kExact); // south
  EXPECT_NEAR(RadToDeg(AzElFromEnu({-1, 0, 0}).az_rad), 270.0, kExact); // west
  EXPECT_NEAR(RadToDeg(AzElFromEnu({0, 0, 1}).el_rad), 90.0, kExact);
}

}  // namespace
}  // namespace rk::geo

// The pointing model of SPEC.md §3.1: with every term zero it is §3's [r d b]; each term does what the
// contract says it does, at any azimuth (across north) and elevation.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "geo/pointing.h"

namespace rk::geo {
namespace {

constexpr double kPointingExact = 1e-12;  // pure trigonometry, double precision

TEST(Pointing, ZeroTermsAreSpecTurretFrameAtEveryAngle) {
  for (double az : {0.0, 1e-9, 0.3, kPi - 1e-9, kPi, 3.5, kTwoPi - 1e-9}) {
    for (double el : {-1.2, -0.5, 0.0, 0.7, 1.39, kPi / 2}) {
      Eigen::Matrix3d R = RotationEnuFromTurret(az, el, PointingTerms{});
      EXPECT_NEAR((R - RotationEnuFromTurret(az, el)).norm(), 0.0, kPointingExact) << az << " " << el;
    }
  }
}

TEST(Pointing, AzimuthOffsetAddsToTheLoggedAzimuthAcrossNorth) {
  PointingTerms p;
  p.az_offset_rad = DegToRad(0.75);
  for (double az_deg : {359.5, 0.0, 179.6, 180.0}) {
    const double az = DegToRad(az_deg), el = DegToRad(30.0);
    Eigen::Matrix3d R = RotationEnuFromTurret(az, el, p);
    EXPECT_NEAR((R - RotationEnuFromTurret(az + p.az_offset_rad, el)).norm(), 0.0, kPointingExact);
    AzEl ae = AzElFromEnu(R.col(2));
    EXPECT_NEAR(AngleDiff(ae.az_rad, WrapTwoPi(az + p.az_offset_rad)), 0.0, 1e-12);
  }
}

TEST(Pointing, TiltsLeanTheAzimuthAxisTowardNorthAndEast) {
  // The azimuth axis is the turret's vertical: the boresight at E = 90° lies along it.
  const double t = DegToRad(0.02);
  PointingTerms north;
  north.tilt_north_rad = t;
  Eigen::Vector3d axis = RotationEnuFromTurret(1.234, kPi / 2, north).col(2);
  EXPECT_NEAR(axis.x(), 0.0, kPointingExact);
  EXPECT_NEAR(axis.y(), std::sin(t), kPointingExact);  // top leans north
  EXPECT_NEAR(axis.z(), std::cos(t), kPointingExact);
  PointingTerms east;
  east.tilt_east_rad = t;
  axis = RotationEnuFromTurret(4.0, kPi / 2, east).col(2);
  EXPECT_NEAR(axis.x(), std::sin(t), kPointingExact);  // top leans east
  EXPECT_NEAR(axis.y(), 0.0, kPointingExact);
}

TEST(Pointing, PositiveElevationAxisTiltLowersItsRightHandEnd) {
  PointingTerms p;
  p.el_axis_tilt_rad = DegToRad(0.05);
  for (double az_deg : {0.0, 90.0, 359.9}) {
    const double az = DegToRad(az_deg);
    // The elevation axis is the image-x (right) axis at E = 0: its right-hand end goes down.
    Eigen::Vector3d right = RotationEnuFromTurret(az, 0.0, p).col(0);
    EXPECT_NEAR(right.z(), -std::sin(p.el_axis_tilt_rad), kPointingExact);
    // At the horizon the boresight is unaffected.
    Eigen::Vector3d b0 = RotationEnuFromTurret(az, 0.0, p).col(2);
    EXPECT_NEAR((b0 - DirectionFromAzEl(az, 0.0)).norm(), 0.0, kPointingExact);
  }
  const double el = DegToRad(60.0);
  AzEl ae = AzElFromEnu(RotationEnuFromTurret(0.0, el, p).col(2));
  // Raised about an axis whose right end is low, the boresight swings right: exactly
  // az = atan(sin(tilt)·tan E) at a logged azimuth of 0.
  EXPECT_NEAR(AngleDiff(ae.az_rad, 0.0), std::atan(std::sin(p.el_axis_tilt_rad) * std::tan(el)), 1e-12);
}

TEST(Pointing, IsARotationForAnyTerms) {
  PointingTerms p{DegToRad(123.0), DegToRad(0.3), DegToRad(-0.2), DegToRad(0.1)};
  for (double az : {0.0, 2.0, 6.0}) {
    for (double el : {-0.3, 0.9}) {
      Eigen::Matrix3d R = RotationEnuFromTurret(az, el, p);
      EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 0.0, kPointingExact);
      EXPECT_NEAR(R.determinant(), 1.0, kPointingExact);
    }
  }
}

TEST(Pointing, MountRotationMatchesTheContract) {
  // yaw turns the optical axis right, pitch up, roll turns image x toward image down.
  const double a = DegToRad(0.4);
  EXPECT_NEAR((RotationTurretFromCameraT(a, 0.0, 0.0).col(2) - Eigen::Vector3d(std::sin(a), 0, std::cos(a))).norm(),
              0.0, kPointingExact);
  EXPECT_NEAR((RotationTurretFromCameraT(0.0, a, 0.0).col(2) - Eigen::Vector3d(0, -std::sin(a), std::cos(a))).norm(),
              0.0, kPointingExact);
  EXPECT_NEAR((RotationTurretFromCameraT(0.0, 0.0, a).col(0) - Eigen::Vector3d(std::cos(a), std::sin(a), 0)).norm(),
              0.0, kPointingExact);
}

}  // namespace
}  // namespace rk::geo

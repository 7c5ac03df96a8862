// Domain matchers with named tolerances (docs style: "tests read like the claim they make"):
//   EXPECT_THAT(ae, AzElNear(truth, kAngleTol));              azimuth compared across 0/360 (wrapped)
//   EXPECT_THAT(p_enu, EnuNear(truth_enu, kPositionTol_m));   Euclidean distance
//   EXPECT_THAT(pose, PoseNear(truth, kRotTol_rad, kPosTol_m)); rotation angle of R_truthᵀ·R, and distance
// The failure message gives the difference in the claim's units (radians as degrees and arcseconds, metres).
#pragma once

#include <gmock/gmock.h>

#include <Eigen/Core>
#include <cmath>
#include <ostream>

#include "geo/angles.h"
#include "geo/line_of_sight.h"

namespace rk::test {

// A rotation and a translation (m): a body's attitude and position in ENU, or a camera-from-body transform.
struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

// Angle (rad) of the rotation taking `a` to `b` (of aᵀ b), accurate down to rounding.
double RotationAngleRad(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);
// How GoogleTest prints a Pose: its rotation as angle and axis, its position.
void PrintTo(const Pose& p, std::ostream* os);

MATCHER_P2(AzElNear, expected, tol_rad,
           "is within " + ::testing::PrintToString(geo::RadToDeg(tol_rad) * 3600.0) + " arcsec of az " +
               ::testing::PrintToString(geo::RadToDeg(expected.az_rad)) + " deg, el " +
               ::testing::PrintToString(geo::RadToDeg(expected.el_rad)) + " deg") {
  const double daz = geo::WrapPi(arg.az_rad - expected.az_rad), del = arg.el_rad - expected.el_rad;
  *result_listener << "differs by az " << geo::RadToDeg(daz) * 3600.0 << " arcsec, el "
                   << geo::RadToDeg(del) * 3600.0 << " arcsec";
  return std::abs(daz) <= tol_rad && std::abs(del) <= tol_rad;
}

MATCHER_P2(EnuNear, expected, tol_m,
           "is within " + ::testing::PrintToString(tol_m) + " m of (" +
               ::testing::PrintToString(expected.x()) + ", " + ::testing::PrintToString(expected.y()) + ", " +
               ::testing::PrintToString(expected.z()) + ") m ENU") {
  const double d = (Eigen::Vector3d(arg) - Eigen::Vector3d(expected)).norm();
  *result_listener << "is " << d << " m away";
  return d <= tol_m;
}

MATCHER_P3(PoseNear, expected, tol_rad, tol_m,
           "is within " + ::testing::PrintToString(geo::RadToDeg(tol_rad)) + " deg and " +
               ::testing::PrintToString(tol_m) + " m of the expected pose") {
  const double angle = RotationAngleRad(expected.R, arg.R), d = (arg.t - expected.t).norm();
  *result_listener << "rotation differs by " << geo::RadToDeg(angle) << " deg, position by " << d << " m";
  return angle <= tol_rad && d <= tol_m;
}

}  // namespace rk::test

// Unit tests of target/cylinder.h: the silhouette points, the view angle and the target file's checks.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geo/angles.h"
#include "target/cylinder.h"

namespace rk::target {
namespace {

using geo::DegToRad;

constexpr double kGeomM = 1e-9;  // metres, double precision on ~1e3 m coordinates

TEST(Cylinder, SilhouettePointsAreTheEdgeOnDiameter) {
  CylinderShape shape;
  shape.length_m = 3.0;
  shape.diameter_m = 0.4;
  for (double yaw : {0.0, 76.211, 200.0, 359.9}) {
    const CylinderPose pose =
        PoseAt(1500.0, DegToRad(326.2), DegToRad(20.0), DegToRad(yaw), DegToRad(31.257), shape);
    const SilhouettePoints3d p = SilhouettePointsOf(pose, shape);
    const double slant = std::sqrt(0.04 + 9.0);
    EXPECT_NEAR((p.nose - p.tail1).norm(), slant, kGeomM);
    EXPECT_NEAR((p.nose - p.tail2).norm(), slant, kGeomM);
    EXPECT_NEAR((p.tail1 - p.tail2).norm(), 0.4, kGeomM);
    EXPECT_NEAR((p.nose - p.tail_centre).norm(), 3.0, kGeomM);
    // Edge-on: the diameter is perpendicular to the axis and to the line of sight; R2 = R3.
    EXPECT_NEAR((p.tail1 - p.tail2).dot(pose.Axis()), 0.0, kGeomM);
    EXPECT_NEAR((p.tail1 - p.tail2).normalized().dot(p.tail_centre.normalized()), 0.0, 1e-12);
    EXPECT_NEAR(p.tail1.norm(), p.tail2.norm(), kGeomM);
    // The mid-point is at the requested range and direction.
    const Eigen::Vector3d mid = p.tail_centre + 1.5 * pose.Axis();
    EXPECT_NEAR(mid.norm(), 1500.0, kGeomM);
  }
}

TEST(Cylinder, ViewAngleConventions) {
  CylinderShape shape;
  CylinderPose away;  // axis north, target north of the station: tail chase
  away.tail_centre_enu = Eigen::Vector3d(0, 1000, 0);
  away.yaw_rad = 0.0;
  away.pitch_rad = 0.0;
  EXPECT_NEAR(ViewAngle(away), 0.0, 1e-12);
  away.yaw_rad = DegToRad(90.0);
  EXPECT_NEAR(ViewAngle(away), M_PI / 2, 1e-12);
}

TEST(CylinderShape, ChecksValues) {
  std::string why;
  EXPECT_TRUE((CylinderShape{2.5, 0.25}).Check(&why));
  EXPECT_FALSE((CylinderShape{0.0, 0.25}).Check(&why));
  EXPECT_FALSE((CylinderShape{2.5, -1.0}).Check(&why));
  EXPECT_NEAR((CylinderShape{2.0, 1.0}).SlantM(), std::sqrt(4.25), 1e-15);
}

}  // namespace
}  // namespace rk::target

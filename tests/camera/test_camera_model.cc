#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "camera/camera_model.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"

namespace rk::camera {
namespace {

constexpr double kRoundTripPx = 1e-9;    // Newton undistortion converges to machine precision
constexpr double kRayRad = 1e-12;        // exact geometry, double precision

CameraModel DistortedCamera() {
  CameraModel c = DefaultCamera();
  c.distortion = {-0.12, 0.05, 0.0007, -0.0004, -0.01};
  c.principal_point_px = {1230.2, 1019.7};
  return c;
}

TEST(CameraModel, ProjectionAndUndistortionRoundTripOverTheWholeSensor) {
  CameraModel c = DistortedCamera();
  for (double x = 0; x < c.width_px; x += 203.7) {
    for (double y = 0; y < c.height_px; y += 157.3) {
      Eigen::Vector3d m = c.NormalisedRay({x, y});
      auto px = c.Project(m);
      ASSERT_TRUE(px);
      EXPECT_NEAR(px->x(), x, kRoundTripPx);
      EXPECT_NEAR(px->y(), y, kRoundTripPx);
    }
  }
  EXPECT_FALSE(c.Project({0, 0, -1}).has_value());
}

TEST(CameraModel, PrincipalPointLooksAlongTheBoresight) {
  CameraModel c = DefaultCamera();
  for (double el : {0.0, 0.6, 1.4}) {
    Eigen::Vector3d ray = c.RayEnu(c.principal_point_px, 0.4, el);
    EXPECT_NEAR((ray - geo::DirectionFromAzEl(0.4, el)).norm(), 0.0, kRayRad);
  }
  // A pixel to the right of centre is to the right (larger azimuth) at level boresight.
  Eigen::Vector3d right = c.RayEnu(c.principal_point_px + Eigen::Vector2d(100, 0), 0.4, 0.0);
  EXPECT_GT(geo::AzElFromEnu(right).az_rad, 0.4);
  // A pixel below centre is lower.
  Eigen::Vector3d below = c.RayEnu(c.principal_point_px + Eigen::Vector2d(0, 100), 0.4, 0.2);
  EXPECT_LT(geo::AzElFromEnu(below).el_rad, 0.2);
}

TEST(CameraModel, EnuProjectionInvertsRayAtHighElevationAndWithMount) {
  CameraModel c = DistortedCamera();
  c.mount_yaw_rad = geo::DegToRad(0.05);
  c.mount_pitch_rad = geo::DegToRad(-0.03);
  c.mount_roll_rad = geo::DegToRad(0.2);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 200; ++i) {
    double az = geo::kTwoPi * u(rng), el = geo::DegToRad(-5 + 90 * u(rng));
    Eigen::Vector2d px(c.width_px * u(rng), c.height_px * u(rng));
    Eigen::Vector3d ray = c.RayEnu(px, az, el);
    auto back = c.ProjectEnu(ray, az, el);
    ASSERT_TRUE(back);
    EXPECT_NEAR((*back - px).norm(), 0.0, 1e-7);
  }
}

TEST(CameraModel, MountYawTurnsOpticalAxisRight) {
  CameraModel c = DefaultCamera();
  c.mount_yaw_rad = 0.01;
  c.mount_pitch_rad = 0.02;
  Eigen::Vector3d axis = c.RotationTurretFromCamera() * Eigen::Vector3d(0, 0, 1);
  EXPECT_NEAR(axis.x(), std::sin(0.01) * std::cos(0.02), kRayRad);
  EXPECT_NEAR(axis.y(), -std::sin(0.02), kRayRad);
}

TEST(CameraModel, JsonRoundTripAndValidation) {
  CameraModel c = DistortedCamera();
  CameraModel d = CameraModelFromJson(CameraModelToJson(c), "cam.json");
  EXPECT_EQ(d.width_px, c.width_px);
  EXPECT_DOUBLE_EQ(d.distortion[0], c.distortion[0]);
  io::Json j = CameraModelToJson(c);
  j.erase("focal_length_mm");
  try {
    CameraModelFromJson(j, "cam.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("focal_length_mm"), std::string::npos);
  }
  j = CameraModelToJson(c);
  j["pixel_size_mm"] = {0.0, 0.1};
  EXPECT_THROW(CameraModelFromJson(j, "cam.json"), Error);
}

}  // namespace
}  // namespace rk::camera

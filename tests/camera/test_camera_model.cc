#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "geo/angles.h"
#include "geo/pointing.h"
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

TEST(CameraModel, TimeOffsetAndCalibrationBlockRoundTrip) {
  CameraModel c = DistortedCamera();
  io::Json j = CameraModelToJson(c);
  EXPECT_FALSE(j.contains("time_offset_s"));  // files without a latency stay as they were
  EXPECT_FALSE(j.contains("calibration"));
  j["time_offset_s"] = 0.0125;
  j["calibration"] = {{"method", "pointing"}, {"sigma", {{"time_offset_s", 1e-4}}}};
  CameraModel d = CameraModelFromJson(j, "cam.json");
  EXPECT_DOUBLE_EQ(d.time_offset_s, 0.0125);
  EXPECT_DOUBLE_EQ(d.calibration["sigma"]["time_offset_s"].get<double>(), 1e-4);
  io::Json back = CameraModelToJson(d);
  EXPECT_EQ(back["time_offset_s"], j["time_offset_s"]);
  EXPECT_EQ(back["calibration"], j["calibration"]);
  j["time_offset_s"] = 1e6;
  EXPECT_THROW(CameraModelFromJson(j, "cam.json"), Error);
}

TEST(CameraModel, RayThroughPointingModelEqualsTheSpecChain) {
  CameraModel c = DistortedCamera();
  c.mount_yaw_rad = 0.001;
  c.mount_roll_rad = -0.002;
  geo::PointingTerms p{0.5, 1e-4, -2e-4, 3e-4};
  const Eigen::Vector2d px(100.0, 1900.0);
  for (double az : {0.0, 3.0, 6.28}) {
    const double el = 0.8;
    Eigen::Vector3d expected = (geo::RotationEnuFromTurret(az, el, p) * c.RotationTurretFromCamera() *
                                c.NormalisedRay(px)).normalized();
    EXPECT_NEAR((c.RayEnu(px, az, el, p) - expected).norm(), 0.0, 1e-14);
    EXPECT_NEAR((c.RayEnu(px, az, el, geo::PointingTerms{}) - c.RayEnu(px, az, el)).norm(), 0.0, 0.0);
  }
}

TEST(PointingModel, JsonRoundTripKeepsSigmaAndExtraKeys) {
  io::Json j = {{"az_offset_deg", 123.25}, {"tilt_north_deg", 0.01}, {"el_axis_tilt_deg", -0.003},
                {"sigma", {{"az_offset_deg", 0.001}, {"tilt_north_deg", 2e-4}}},
                {"observations", 412}, {"date", "2026-11-26"}};
  PointingModel m = PointingModelFromJson(j, "pointing.json");
  EXPECT_NEAR(m.terms.az_offset_rad, geo::DegToRad(123.25), 1e-15);
  EXPECT_EQ(m.terms.tilt_east_rad, 0.0);  // absent = 0
  ASSERT_TRUE(m.sigma_rad[kAzOffset].has_value());
  EXPECT_FALSE(m.sigma_rad[kTiltEast].has_value());  // not estimated: no sigma
  io::Json back = PointingModelToJson(m);
  EXPECT_EQ(back["observations"], 412);
  EXPECT_NEAR(back["tilt_north_deg"].get<double>(), 0.01, 1e-15);
  EXPECT_FALSE(back["sigma"].contains("tilt_east_deg"));
  j["tilt_east_deg"] = 45.0;  // not a levelling error a calibration can hold
  try {
    PointingModelFromJson(j, "pointing.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("tilt_east_deg"), std::string::npos);
  }
}

// pointing.json errors name the file, line and column of the offending value (SPEC.md §4).
TEST(PointingModel, ErrorsNameLineAndColumnOfTheValue) {
  struct Case {
    const char* text;
    const char* where;  // expected "pointing.json:L:C:" prefix
    const char* key;
  };
  const Case cases[] = {
      {"{\n  \"az_offset_deg\": 1.5,\n  \"tilt_east_deg\": 12\n}\n", "pointing.json:3:20:", "tilt_east_deg"},
      {"{\"az_offset_deg\": \"x\"}", "pointing.json:1:19:", "az_offset_deg"},
      {"{\"az_offset_deg\": 1,\n \"sigma\": {\"tilt_north_deg\": 0.1,\n   \"az_offset_deg\": -1}}",
       "pointing.json:3:21:", "sigma.az_offset_deg"},
      {"{\"sigma\": [1]}", "pointing.json:1:11:", "sigma"},
      {"[1, 2]", "pointing.json:1:1:", "object"},
  };
  for (const Case& c : cases) {
    try {
      ParsePointingModel(c.text, "pointing.json");
      ADD_FAILURE() << c.text;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.code(), ExitCode::kInvalidData) << what;
      EXPECT_EQ(what.rfind(c.where, 0), 0u) << what;
      EXPECT_NE(what.find(c.key), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace rk::camera

// rk-locate pipeline against a simulated station: exact geometry (distortion,
// mount misalignment, high elevation, azimuth through north), range
// interpolation accuracy with rangefinder noise, gaps and device errors,
// turret coverage. The input readers (lib/formats): tests/formats/test_locate_inputs.cc.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "camera/camera_model.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/csv.h"
#include "io/error.h"
#include "formats/beacon_track.h"
#include "formats/range_log.h"
#include "formats/turret_log.h"
#include "locate/locate.h"
#include "sim/trajectory.h"
#include "sim/turret_servo.h"
#include "test_cameras.h"

namespace rk::locate {
namespace {

// Geometry is exact and the turret motion below is a cubic in time, which
// cubic interpolation reproduces: only rounding (~1e-14 rad) and the
// Newton-inverted distortion (~1e-14) remain.
constexpr double kAngleTolerance_rad = 1e-9;
// Issue target: range at frame times RMS ≤ 1 mm with 0.35 mm device noise
// on the default trajectory (bench/range_interp_accuracy: 0.23 mm measured).
constexpr double kRangeRmsTolerance_m = 1.0e-3;
constexpr double kRangeNoise_m = 0.35e-3;  // seed 001: static range std 0.354 mm

using test_data::DistortedMisalignedCamera;

class StationGeometry : public ::testing::TestWithParam<double> {};

TEST_P(StationGeometry, LocatesProjectedTargetExactly) {
  const double el0 = geo::DegToRad(GetParam());
  const camera::CameraModel cam = DistortedMisalignedCamera();
  // Boresight: cubic polynomials in time; azimuth passes through north at t ≈ 1 s.
  auto boresight = [&](double t) {
    const double az = geo::DegToRad(359.7) + geo::DegToRad(0.3) * t - 0.002 * t * t + 0.001 * t * t * t;
    const double el = el0 + 0.01 * t - 0.003 * t * t + 0.0005 * t * t * t;
    return geo::AzEl{az, el};
  };
  // The target sits off the boresight (servo lag), moving in the image.
  auto target_enu = [&](double t) {
    const geo::AzEl b = boresight(t);
    const Eigen::Vector3d m_turret(0.03 * std::sin(1.3 * t), -0.02 + 0.015 * t, 1.0);
    return Eigen::Vector3d(geo::RotationEnuFromTurret(b.az_rad, b.el_rad) * m_turret.normalized());
  };
  formats::TurretLog turret;
  turret.source = "turret.csv";
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.02 * i;
    const geo::AzEl b = boresight(t);
    turret.t_s.push_back(t);
    turret.az_rad.push_back(geo::WrapTwoPi(b.az_rad));  // as logged: [0, 360)
    turret.el_rad.push_back(b.el_rad);
  }
  formats::Track track;
  track.source = "track.csv";
  std::vector<Eigen::Vector3d> truth;
  for (int k = 0; k < 39; ++k) {
    const double t = 0.013 + 0.05 * k;
    const geo::AzEl b = boresight(t);
    const auto px = cam.ProjectEnu(target_enu(t), b.az_rad, b.el_rad);
    ASSERT_TRUE(px.has_value());
    ASSERT_GT((*px)(0), 0.0);
    ASSERT_LT((*px)(0), cam.width_px - 1.0);
    formats::TrackRow row;
    row.t_s = t;
    row.frame = k;
    row.px = *px;
    track.rows.push_back(row);
    truth.push_back(target_enu(t));
  }
  const LocateResult result = Locate(track, cam, turret, nullptr, LocateOptions{});
  ASSERT_EQ(result.rows.size(), track.rows.size());
  bool crossed_north = false;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const LocatedRow& row = result.rows[i];
    ASSERT_TRUE(row.az_rad && row.el_rad);
    const geo::AzEl want = geo::AzElFromEnu(truth[i]);
    EXPECT_LT(std::abs(geo::AngleDiff(*row.az_rad, want.az_rad)) * std::cos(want.el_rad), kAngleTolerance_rad)
        << "t=" << row.t_s;
    EXPECT_LT(std::abs(*row.el_rad - want.el_rad), kAngleTolerance_rad) << "t=" << row.t_s;
    EXPECT_GE(*row.az_rad, 0.0);
    EXPECT_LT(*row.az_rad, geo::kTwoPi);
    if (*row.boresight_az_rad < 0.1) crossed_north = true;
    EXPECT_EQ(row.status, RowStatus::kOk);
    EXPECT_EQ(row.range_status, RangeStatus::kNoLog);
    EXPECT_FALSE(row.range_m.has_value());
  }
  EXPECT_TRUE(crossed_north);
}

INSTANTIATE_TEST_SUITE_P(Elevations0To85, StationGeometry,
                         ::testing::Values(0.0, 10.0, 20.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0));

// The small-angle form (seed 001 eq. 12: az ≈ A + Δx/(f cos E), el ≈ E + Δy/f)
// is wrong by far more than the tolerance at high elevation: the exact
// geometry is what the test above checks.
TEST(StationGeometry, SmallAngleFormWouldFailAtHighElevation) {
  const camera::CameraModel cam = camera::DefaultCamera();
  const double A = 1.0, E = geo::DegToRad(80.0);
  const Eigen::Vector2d px(1223.5 + 800, 1023.5 - 600);
  const geo::AzEl exact = geo::AzElFromEnu(cam.RayEnu(px, A, E));
  const double az_small = A + (px(0) - 1223.5) / cam.fx() / std::cos(E);
  EXPECT_GT(std::abs(geo::AngleDiff(exact.az_rad, az_small)), 1e-3);
}

struct RangeScenario {
  formats::Track track;
  formats::TurretLog turret;
  formats::RangeLog range;
  std::vector<double> true_range_m;
  std::vector<Eigen::Vector3d> true_p_enu;
};

RangeScenario MakeRangeScenario(std::uint64_t seed) {
  sim::TrajectoryOptions topt;  // seed 001 default trajectory
  topt.range_m = 80.0;
  topt.speed_mps = 3.0;
  const sim::Trajectory traj(topt);
  const camera::CameraModel cam = camera::DefaultCamera();
  const double t_end = 12.0;
  const sim::TurretServo servo(
      sim::TurretServoOptions{}, [&](double t) { return traj.PositionEnu(t); }, 0.0, t_end, seed);
  RangeScenario s;
  s.turret.source = "turret.csv";
  for (int i = 0; i <= 600; ++i) {
    const double t = 0.02 * i;
    const geo::AzEl b = servo.Boresight(t);
    s.turret.t_s.push_back(t);
    s.turret.az_rad.push_back(b.az_rad);
    s.turret.el_rad.push_back(b.el_rad);
  }
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, kRangeNoise_m);
  s.range.source = "range.csv";
  for (double t = 0.07; t < t_end; t += 0.2) {
    s.range.t_s.push_back(t);
    s.range.range_m.push_back(traj.PositionEnu(t).norm() + noise(rng));
  }
  s.track.source = "track.csv";
  for (int k = 0; k < 240; ++k) {
    const double t = 0.05 * k;
    const geo::AzEl b = servo.Boresight(t);
    formats::TrackRow row;
    row.t_s = t;
    row.px = *cam.ProjectEnu(traj.PositionEnu(t), b.az_rad, b.el_rad);
    s.track.rows.push_back(row);
    s.true_range_m.push_back(traj.PositionEnu(t).norm());
    s.true_p_enu.push_back(traj.PositionEnu(t));
  }
  return s;
}

TEST(LocateRange, DefaultMethodMeetsOneMillimetreRms) {
  const camera::CameraModel cam = camera::DefaultCamera();
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const RangeScenario s = MakeRangeScenario(seed);
    const LocateResult result = Locate(s.track, cam, s.turret, &s.range, LocateOptions{});
    double sum_sq_r = 0.0, sum_sq_p = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < result.rows.size(); ++i) {
      const LocatedRow& row = result.rows[i];
      if (!row.range_m) {
        // Only the frames before the first range sample (t < 0.07 s) and after the last lack a range.
        EXPECT_EQ(row.range_status, RangeStatus::kOutside);
        continue;
      }
      sum_sq_r += std::pow(*row.range_m - s.true_range_m[i], 2);
      sum_sq_p += (*row.p_enu_m - s.true_p_enu[i]).squaredNorm();
      ++n;
    }
    EXPECT_GT(n, 230u);
    const double rms_r = std::sqrt(sum_sq_r / n), rms_p = std::sqrt(sum_sq_p / n);
    EXPECT_LT(rms_r, kRangeRmsTolerance_m) << "seed " << seed;
    EXPECT_LT(rms_p, kRangeRmsTolerance_m) << "seed " << seed;
    // Linear interpolation, for contrast, misses the target on this trajectory
    // (range acceleration ≈ 0.4 m/s², error ≈ a h²/8 ≈ 2 mm at 5 Hz).
    LocateOptions lin;
    lin.range_method = track::InterpMethod::kLinear;
    const LocateResult rl = Locate(s.track, cam, s.turret, &s.range, lin);
    double sum_sq_l = 0.0;
    std::size_t nl = 0;
    for (std::size_t i = 0; i < rl.rows.size(); ++i) {
      if (!rl.rows[i].range_m) continue;
      sum_sq_l += std::pow(*rl.rows[i].range_m - s.true_range_m[i], 2);
      ++nl;
    }
    EXPECT_GT(std::sqrt(sum_sq_l / nl), rms_r);
  }
}

TEST(LocateRange, GapsAndDeviceErrorsGiveEmptyRange) {
  const camera::CameraModel cam = camera::DefaultCamera();
  RangeScenario s = MakeRangeScenario(7);
  // Device error at index 20 (t = 4.07 s); samples 6.27 .. 6.87 s missing: a 1 s hole.
  s.range.range_m[20] = std::nullopt;
  for (std::size_t i = 31; i < 35; ++i) s.range.range_m[i] = std::nullopt;
  formats::RangeLog holed = s.range;
  holed.t_s.clear();
  holed.range_m.clear();
  for (std::size_t i = 0; i < s.range.t_s.size(); ++i) {
    if (i >= 31 && i < 35) continue;  // rows absent from the log: a time gap
    holed.t_s.push_back(s.range.t_s[i]);
    holed.range_m.push_back(s.range.range_m[i]);
  }
  const LocateResult result = Locate(s.track, cam, s.turret, &holed, LocateOptions{});
  for (const LocatedRow& row : result.rows) {
    ASSERT_TRUE(row.az_rad.has_value());
    EXPECT_EQ(row.status, RowStatus::kOk);
    if (row.t_s > 3.87 + 1e-9 && row.t_s < 4.27 - 1e-9) {
      EXPECT_EQ(row.range_status, RangeStatus::kDeviceError) << row.t_s;
      EXPECT_FALSE(row.range_m.has_value());
      EXPECT_FALSE(row.p_enu_m.has_value());
    } else if (row.t_s > 6.07 + 1e-9 && row.t_s < 7.07 - 1e-9) {
      EXPECT_EQ(row.range_status, RangeStatus::kGap) << row.t_s;
      EXPECT_FALSE(row.range_m.has_value());
    } else if (row.t_s > 0.07 && row.t_s < 11.87) {
      EXPECT_EQ(row.range_status, RangeStatus::kOk) << row.t_s;
      EXPECT_TRUE(row.range_m.has_value());
    }
  }
  EXPECT_GT(result.rows_by_range_status[static_cast<int>(RangeStatus::kDeviceError)], 0u);
  EXPECT_GT(result.rows_by_range_status[static_cast<int>(RangeStatus::kGap)], 0u);
  EXPECT_LT(result.RangeCoverage(), 1.0);
}

TEST(LocateTurret, PartialCoverageMarksMeasuredRowsInvalid) {
  const camera::CameraModel cam = camera::DefaultCamera();
  RangeScenario s = MakeRangeScenario(3);
  s.track.rows[5].px.reset();
  s.track.rows[5].status = RowStatus::kLost;
  s.track.rows[200].px.reset();
  s.track.rows[200].status = RowStatus::kLost;
  // Turret log only up to 8 s.
  formats::TurretLog part = s.turret;
  part.t_s.resize(401);
  part.az_rad.resize(401);
  part.el_rad.resize(401);
  const LocateResult r = Locate(s.track, cam, part, nullptr, LocateOptions{});
  EXPECT_EQ(r.rows[5].status, RowStatus::kLost);
  EXPECT_FALSE(r.rows[5].az_rad.has_value());
  EXPECT_EQ(r.rows[200].status, RowStatus::kLost);  // no measurement: stays lost
  EXPECT_EQ(r.rows[199].status, RowStatus::kInvalid);
  EXPECT_FALSE(r.rows[199].az_rad.has_value());
  EXPECT_EQ(r.rows[100].status, RowStatus::kOk);
  EXPECT_EQ(r.rows_turret_not_covered, 79u);  // frames at 8.05 .. 11.95 s
  EXPECT_EQ(r.measured_rows_turret_not_covered, 78u);

  formats::TurretLog late = s.turret;
  for (double& t : late.t_s) t += 100.0;
  try {
    Locate(s.track, cam, late, nullptr, LocateOptions{});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("turret.csv"), std::string::npos) << e.what();
  }
  // A turret gap longer than the limit makes the frames inside it invalid.
  formats::TurretLog holed = s.turret;
  for (std::size_t i = 100; i < 110; ++i) holed.az_rad[i] = std::nan("");  // empty samples
  const LocateResult rh = Locate(s.track, cam, holed, nullptr, LocateOptions{});
  EXPECT_EQ(rh.rows[41].status, RowStatus::kInvalid);  // t = 2.05 s
  EXPECT_EQ(rh.rows[30].status, RowStatus::kOk);
}

}  // namespace
}  // namespace rk::locate

// Tests of the synthetic beacon trial (sim/beacon_scenario.h): projection
// consistency of the truth, visibility across trajectories, azimuth wrap,
// overhead passes, turret and range logs, determinism, option checks.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numeric>

#include <Eigen/Geometry>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"
#include "sim/beacon_scenario.h"

namespace rk::sim {
namespace {

constexpr double kRayTolRad = 1e-9;         // truth az/el vs ray through the truth pixel: pure float round-off
constexpr double kPixelTolPx = 1e-6;        // forward/back projection of the same direction
constexpr double kCentroidTolPx = 0.01;     // grey centroid of the noise-free signal vs truth (PSF out to 5 sigma)

BeaconSimOptions Small(TrajectoryKind kind = TrajectoryKind::kDefault, double duration_s = 3.0) {
  BeaconSimOptions o;
  CameraPreset("small", &o.camera);
  o.camera_preset = "small";
  o.trajectory = DefaultTrajectoryOptions(kind);
  o.duration_s = duration_s;
  return o;
}

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

TEST(BeaconScenario, TruthPixelAndAzElAgreeThroughTheCameraModel) {
  // A camera with distortion and a mount misalignment, so the whole chain is exercised.
  BeaconSimOptions o = Small();
  o.camera.distortion = {-0.12, 0.05, 1e-4, -2e-4, 0.0};
  o.camera.mount_yaw_rad = geo::DegToRad(0.05);
  o.camera.mount_pitch_rad = geo::DegToRad(-0.03);
  o.camera.mount_roll_rad = geo::DegToRad(0.2);
  const BeaconSimulator sim(o);
  ASSERT_EQ(sim.frame_count(), 60u);
  for (const FrameTruth& f : sim.frames()) {
    const Eigen::Vector3d ray = o.camera.RayEnu(f.centre_px, f.boresight_az_rad, f.boresight_el_rad);
    EXPECT_LT(AngleBetween(ray, geo::DirectionFromAzEl(f.az_rad, f.el_rad)), kRayTolRad) << "frame " << f.frame;
    const auto px = o.camera.ProjectEnu(geo::DirectionFromAzEl(f.az_rad, f.el_rad), f.boresight_az_rad,
                                        f.boresight_el_rad);
    ASSERT_TRUE(px.has_value());
    EXPECT_LT((*px - f.centre_px).norm(), kPixelTolPx);
    // Lamp 0 sits on the body reference point: its ray points exactly at p_enu.
    ASSERT_FALSE(f.lamps.empty());
    const Eigen::Vector3d lamp0 =
        o.camera.RayEnu({f.lamps[0].x_px, f.lamps[0].y_px}, f.boresight_az_rad, f.boresight_el_rad);
    EXPECT_LT(AngleBetween(lamp0, f.p_enu), kRayTolRad);
    // Every lamp is within half the cluster span of the reference point.
    for (const Spot& s : f.lamps) {
      const Eigen::Vector3d r = o.camera.RayEnu({s.x_px, s.y_px}, f.boresight_az_rad, f.boresight_el_rad);
      EXPECT_LT(AngleBetween(r, f.p_enu), 0.5 * o.cluster_span_m / f.range_m * 1.0001);
    }
    EXPECT_NEAR(f.range_m, f.p_enu.norm(), 1e-12);
  }
}

TEST(BeaconScenario, TruthCentreIsTheGreyCentroidOfTheNoiseFreeImage) {
  BeaconSimOptions o = Small(TrajectoryKind::kDefault, 0.5);
  const BeaconSimulator sim(o);
  for (std::size_t k = 0; k < sim.frame_count(); k += 3) {
    const cv::Mat s = sim.RenderSignal(k);
    double sw = 0, sx = 0, sy = 0;
    for (int y = 0; y < s.rows; ++y) {
      for (int x = 0; x < s.cols; ++x) {
        const double v = s.at<float>(y, x);
        sw += v;
        sx += v * x;
        sy += v * y;
      }
    }
    EXPECT_NEAR(sx / sw, sim.frame(k).centre_px.x(), kCentroidTolPx);
    EXPECT_NEAR(sy / sw, sim.frame(k).centre_px.y(), kCentroidTolPx);
  }
}

TEST(BeaconScenario, NoLagNoJitterPutsTheReferenceLampOnThePrincipalPoint) {
  BeaconSimOptions o = Small(TrajectoryKind::kStraight, 2.0);
  o.servo.lag_s = 0;
  o.servo.jitter_arcsec = 0;
  const BeaconSimulator sim(o);
  for (const FrameTruth& f : sim.frames()) {
    EXPECT_NEAR(f.lamps[0].x_px, o.camera.principal_point_px.x(), kPixelTolPx);
    EXPECT_NEAR(f.lamps[0].y_px, o.camera.principal_point_px.y(), kPixelTolPx);
  }
}

TEST(BeaconScenario, TurretLagsByTauTimesTheAngularRate) {
  // First-order servo on a ramp: steady-state error = tau * rate.
  BeaconSimOptions o = Small(TrajectoryKind::kStraight, 2.0);
  o.trajectory.elevation_rad = 0.0;
  o.servo.lag_s = 0.2;
  o.servo.jitter_arcsec = 0;
  const BeaconSimulator sim(o);
  const double t = o.t0_s + 1.0;  // closest approach: azimuth rate = v / R
  const double rate = o.trajectory.speed_mps / o.trajectory.range_m;
  const geo::AzEl target = geo::AzElFromEnu(sim.TargetEnu(t));
  const geo::AzEl bore = sim.TrueBoresight(t);
  constexpr double kLagTolRad = 2e-5;  // curvature of atan over the lag interval (~1e-6) plus margin
  EXPECT_NEAR(geo::AngleDiff(target.az_rad, bore.az_rad), 0.2 * rate, kLagTolRad);
}

TEST(BeaconScenario, JitterHasTheRequestedRms) {
  BeaconSimOptions o = Small(TrajectoryKind::kStatic, 60.0);
  o.fps = 5;
  o.servo.lag_s = 0;
  o.servo.jitter_arcsec = 20.0;
  const BeaconSimulator sim(o);
  const geo::AzEl target = geo::AzElFromEnu(sim.TargetEnu(o.t0_s));
  double s2 = 0;
  int n = 0;
  for (double t = o.t0_s; t < o.t0_s + 60; t += 0.01, ++n) {
    s2 += std::pow(geo::AngleDiff(sim.TrueBoresight(t).el_rad, target.el_rad), 2);
  }
  // Eight random tones: the sample RMS over 60 s is within ~10 % of the design value.
  EXPECT_NEAR(std::sqrt(s2 / n) * geo::kArcsecPerRad, 20.0, 3.0);
}

TEST(BeaconScenario, LampsVisibleInsideTheImageOnEveryTrajectoryAndPreset) {
  for (const char* preset : {"default", "small"}) {
    for (auto kind : {TrajectoryKind::kDefault, TrajectoryKind::kStraight, TrajectoryKind::kTurning,
                      TrajectoryKind::kOverhead, TrajectoryKind::kStatic}) {
      BeaconSimOptions o;
      ASSERT_TRUE(CameraPreset(preset, &o.camera));
      o.trajectory = DefaultTrajectoryOptions(kind);
      o.duration_s = 10.0;
      const BeaconSimulator sim(o);
      ASSERT_EQ(sim.frame_count(), 200u);
      for (const FrameTruth& f : sim.frames()) {
        ASSERT_TRUE(f.visible);
        ASSERT_EQ(f.lamps.size(), 5u);
        for (const Spot& s : f.lamps) {
          EXPECT_GE(s.x_px, 0.0);
          EXPECT_GE(s.y_px, 0.0);
          EXPECT_LE(s.x_px, o.camera.width_px - 1.0);
          EXPECT_LE(s.y_px, o.camera.height_px - 1.0);
        }
      }
    }
  }
}

TEST(BeaconScenario, EveryTrajectoryWorksFrom20mTo10km) {
  for (const char* preset : {"default", "small"}) {
    for (auto kind : {TrajectoryKind::kDefault, TrajectoryKind::kStraight, TrajectoryKind::kTurning,
                      TrajectoryKind::kOverhead, TrajectoryKind::kStatic}) {
      for (double range_m : {20.0, 100.0, 1000.0, 10000.0}) {
        BeaconSimOptions o;
        ASSERT_TRUE(CameraPreset(preset, &o.camera));
        o.trajectory = DefaultTrajectoryOptions(kind, range_m);
        o.fps = 4;
        std::unique_ptr<BeaconSimulator> sim;
        ASSERT_NO_THROW(sim = std::make_unique<BeaconSimulator>(o))
            << preset << " " << TrajectoryKindName(kind) << " " << range_m;
        // Closest approach (straight, overhead) or fixed point (static) at t_mid = frame 20.
        if (kind == TrajectoryKind::kStraight || kind == TrajectoryKind::kOverhead || kind == TrajectoryKind::kStatic) {
          EXPECT_NEAR(sim->frame(20).range_m, range_m, 1e-9 * range_m);
        }
      }
    }
  }
}

TEST(BeaconScenario, DefaultTrajectoryIsANearbySlowTarget) {
  BeaconSimOptions o;
  const BeaconSimulator sim(o);  // default preset, 10 s
  double vmax = 0, rmin = 1e9, rmax = 0;
  for (const FrameTruth& f : sim.frames()) {
    rmin = std::min(rmin, f.range_m);
    rmax = std::max(rmax, f.range_m);
  }
  for (double t = o.t0_s; t < o.t0_s + o.duration_s; t += 0.05) {
    vmax = std::max(vmax, (sim.TargetEnu(t + 1e-3) - sim.TargetEnu(t - 1e-3)).norm() / 2e-3);
  }
  EXPECT_GE(rmin, 40.0);
  EXPECT_LE(rmax, 120.0);
  EXPECT_GT(rmax - rmin, 5.0);  // range changes: interpolation to frame times matters
  EXPECT_LE(vmax, 3.0 + 1e-6);
  EXPECT_GT(vmax, 1.0);
}

TEST(BeaconScenario, AzimuthCrossingNorthWraps) {
  BeaconSimOptions o = Small(TrajectoryKind::kStraight, 4.0);
  o.trajectory.azimuth_rad = 0.0;  // closest approach due north, moving east: crosses 0/360
  const BeaconSimulator sim(o);
  bool below = false, above = false;
  for (std::size_t k = 0; k < sim.frame_count(); ++k) {
    const FrameTruth& f = sim.frame(k);
    EXPECT_GE(f.az_rad, 0.0);
    EXPECT_LT(f.az_rad, geo::kTwoPi);
    EXPECT_GE(f.boresight_az_rad, 0.0);
    EXPECT_LT(f.boresight_az_rad, geo::kTwoPi);
    below |= f.az_rad < geo::DegToRad(10);
    above |= f.az_rad > geo::DegToRad(350);
    if (k > 0) {
      EXPECT_LT(std::abs(geo::AngleDiff(f.az_rad, sim.frame(k - 1).az_rad)), geo::DegToRad(1.0));
    }
    ASSERT_EQ(f.lamps.size(), 5u);  // the turret did not swing round the long way
  }
  EXPECT_TRUE(below);
  EXPECT_TRUE(above);
  for (const TurretSample& s : sim.TurretLog()) {
    EXPECT_GE(s.az_rad, 0.0);
    EXPECT_LT(s.az_rad, geo::kTwoPi);
    EXPECT_LE(std::abs(geo::AngleDiff(s.az_rad, s.true_az_rad)), 0.5 * o.turret_resolution_rad() + 1e-12);
  }
}

TEST(BeaconScenario, OverheadPassReachesHighElevation) {
  BeaconSimOptions o = Small(TrajectoryKind::kOverhead, 10.0);
  const BeaconSimulator sim(o);
  double el_max = -1;
  for (const FrameTruth& f : sim.frames()) {
    el_max = std::max(el_max, f.el_rad);
    const Eigen::Vector3d ray = o.camera.RayEnu(f.centre_px, f.boresight_az_rad, f.boresight_el_rad);
    EXPECT_LT(AngleBetween(ray, geo::DirectionFromAzEl(f.az_rad, f.el_rad)), kRayTolRad);
  }
  EXPECT_GE(geo::RadToDeg(el_max), 75.0);
  EXPECT_LE(geo::RadToDeg(el_max), 80.5);
}

TEST(BeaconScenario, RangeNoiseAndErrorRowsMatchTheOptions) {
  BeaconSimOptions o = Small(TrajectoryKind::kDefault, 400.0);
  o.fps = 1;
  o.range_rate_hz = 50;
  o.range_noise_mm = 0.35;
  o.range_error_rate = 0.02;
  const BeaconSimulator sim(o);
  const auto log = sim.RangeLog();
  ASSERT_GT(log.size(), 19000u);
  double s = 0, s2 = 0;
  int ok = 0, bad = 0;
  for (const RangeSample& r : log) {
    if (r.status == 0) {
      ASSERT_TRUE(std::isfinite(r.range_m));
      const double e = r.range_m - r.true_range_m;
      s += e;
      s2 += e * e;
      ++ok;
    } else {
      EXPECT_EQ(r.status, 255);
      EXPECT_TRUE(std::isnan(r.range_m));
      ++bad;
    }
  }
  const double n = ok, mean = s / n, sd = std::sqrt(s2 / n - mean * mean);
  // Tolerances: 5 standard errors (std of the sample std = sigma / sqrt(2n)).
  EXPECT_NEAR(mean, 0.0, 5 * 0.35e-3 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.35e-3, 5 * 0.35e-3 / std::sqrt(2 * n));
  const double p = static_cast<double>(bad) / static_cast<double>(log.size());
  EXPECT_NEAR(p, 0.02, 5 * std::sqrt(0.02 * 0.98 / static_cast<double>(log.size())));
  // Samples at 50 Hz, offset from the frame grid, covering the frames with margin.
  EXPECT_LT(log.front().t_s, sim.frame(0).t_s);
  EXPECT_GT(log.back().t_s, sim.frames().back().t_s);
  EXPECT_NEAR(log[1].t_s - log[0].t_s, 0.02, 1e-12);
}

TEST(BeaconScenario, TurretLogIsQuantisedAndOffsetFromFrames) {
  BeaconSimOptions o = Small(TrajectoryKind::kDefault, 2.0);
  const BeaconSimulator sim(o);
  const auto log = sim.TurretLog();
  ASSERT_GT(log.size(), 140u);
  const double q = o.turret_resolution_rad();
  for (std::size_t i = 0; i < log.size(); ++i) {
    EXPECT_NEAR(std::remainder(log[i].el_rad, q), 0.0, 1e-12);
    EXPECT_LE(std::abs(log[i].el_rad - log[i].true_el_rad), 0.5 * q + 1e-12);
    const double frame_phase = std::remainder(log[i].t_s - o.t0_s, 1.0 / o.fps);
    EXPECT_GT(std::abs(frame_phase), 1e-3);  // not aligned with frame times
    if (i > 0) {
      EXPECT_NEAR(log[i].t_s - log[i - 1].t_s, 0.02, 1e-12);
    }
    const geo::AzEl b = sim.TrueBoresight(log[i].t_s);
    EXPECT_EQ(b.az_rad, log[i].true_az_rad);
  }
}

TEST(BeaconScenario, OcclusionHidesTheLampsOnlyInItsInterval) {
  BeaconSimOptions o = Small(TrajectoryKind::kDefault, 3.0);
  o.occlusions.push_back({1.5, 0.5});
  const BeaconSimulator sim(o);
  int hidden = 0;
  for (const FrameTruth& f : sim.frames()) {
    const double rel = f.t_s - o.t0_s;
    const bool expect_hidden = rel >= 1.5 - 1e-9 && rel < 2.0 - 1e-9;
    EXPECT_EQ(f.visible, !expect_hidden) << "t " << rel;
    EXPECT_EQ(f.lamps.empty(), expect_hidden);
    hidden += expect_hidden;
  }
  EXPECT_EQ(hidden, 10);
  // Hidden frame: background only, no lamp above the noise.
  double maxv;
  cv::minMaxLoc(sim.RenderFrame(35), nullptr, &maxv);
  EXPECT_LT(maxv, 40.0);
}

// Servo hold (issue 15 item 2): the turret stops, the beacon's image runs off
// with the target's angular rate, and when the hold ends the servo catches up,
// so the image velocity reverses; outside the hold nothing changes.
TEST(BeaconScenario, ServoHoldReversesTheImageMotion) {
  BeaconSimOptions o = Small(TrajectoryKind::kDefault, 4.0);
  o.servo.jitter_arcsec = 0.0;
  const BeaconSimulator plain(o);
  o.servo_holds.push_back({1.5, 0.3});  // frames 30..35 held
  const BeaconSimulator held(o);
  auto vx = [](const BeaconSimulator& s, int k) { return (s.frame(k + 1).centre_px - s.frame(k - 1).centre_px) * 10.0; };
  // Before the hold: identical.
  EXPECT_LT((held.frame(25).centre_px - plain.frame(25).centre_px).norm(), 1e-9);
  // During the hold the image moves with the target (up to ≈ 490 px/s at 80 m; here ≈ 250 px/s) instead of
  // sitting at the lag offset.
  const Eigen::Vector2d during = vx(held, 34), after = vx(held, 38), steady = vx(plain, 34);
  EXPECT_GT(during.norm(), 200.0);
  EXPECT_GT(during.norm(), 10.0 * steady.norm());
  // Catching up: the image velocity points back against the hold's motion.
  EXPECT_LT(during.dot(after), -0.5 * during.norm() * after.norm());
  // Long after the hold the servo is back in its steady state.
  EXPECT_LT((held.frame(70).centre_px - plain.frame(70).centre_px).norm(), 0.5);
  std::string why;
  o.servo_holds = {{1.0, 0.0}};
  EXPECT_FALSE(o.Check(&why));
  o.servo_holds = {{4.5, 1.0}};  // ends 1.5 s after the trial
  EXPECT_FALSE(o.Check(&why));
}

TEST(BeaconScenario, FrameBrightnessMatchesPeakAndBackground) {
  BeaconSimOptions o = Small(TrajectoryKind::kStatic, 0.5);
  const BeaconSimulator sim(o);
  const cv::Mat f = sim.RenderFrame(0);
  ASSERT_EQ(f.type(), CV_8UC1);
  double maxv;
  cv::minMaxLoc(f, nullptr, &maxv);
  // The default 3 cm head at the small preset's range: lamps (amplitude 160 DN, sigma 1.2 px, pixel-
  // integrated ~0.9 of the amplitude) overlap into a blob peaking at ~200 DN above the 10 DN background,
  // clear of 8-bit saturation.
  EXPECT_GT(maxv, 170.0);
  EXPECT_LT(maxv, 240.0);
  cv::Mat corner = f(cv::Rect(0, 0, 100, 100));
  cv::Scalar mean, sd;
  cv::meanStdDev(corner, mean, sd);
  EXPECT_NEAR(mean[0], 10.0, 0.2);
  EXPECT_NEAR(sd[0], std::sqrt(4.0 + 10.0 / 40.0 + 1.0 / 12.0), 0.25);  // read + shot + quantisation
  o.sensor.bit_depth = 16;
  const cv::Mat g = BeaconSimulator(o).RenderFrame(0);
  ASSERT_EQ(g.type(), CV_16UC1);
  cv::meanStdDev(g(cv::Rect(0, 0, 100, 100)), mean, sd);
  EXPECT_NEAR(mean[0], 2560.0, 30.0);
}

TEST(BeaconScenario, DistractorsKeepClearOfTheCluster) {
  BeaconSimOptions o = Small(TrajectoryKind::kDefault, 10.0);
  o.distractors = 6;
  const BeaconSimulator sim(o);
  double dmin = 1e9;
  bool brighter = false;
  for (const FrameTruth& f : sim.frames()) {
    ASSERT_EQ(f.distractors.size(), 6u);
    for (const Spot& d : f.distractors) {
      const double dist = std::hypot(d.x_px - f.centre_px.x(), d.y_px - f.centre_px.y());
      EXPECT_GE(dist, f.cluster_radius_px + 30.0);
      dmin = std::min(dmin, dist);
      brighter |= d.amplitude_dn > o.peak_dn;
      EXPECT_GE(d.x_px, 0.0);
      EXPECT_LE(d.x_px, o.camera.width_px - 1.0);
    }
    EXPECT_NEAR(f.distractor_min_dist_px, [&] {
      double m = 1e9;
      for (const Spot& d : f.distractors) m = std::min(m, std::hypot(d.x_px - f.centre_px.x(), d.y_px - f.centre_px.y()));
      return m;
    }(), 1e-9);
  }
  EXPECT_TRUE(brighter);  // seed 1 draws at least one glint brighter than the beacon
  EXPECT_EQ(BeaconSimulator(Small()).frame(0).distractor_min_dist_px, -1.0);
}

TEST(BeaconScenario, SameSeedSameTrialOtherSeedOtherNoise) {
  BeaconSimOptions o = Small(TrajectoryKind::kDefault, 1.0);
  o.distractors = 2;
  const BeaconSimulator a(o), b(o);
  for (std::size_t k : {0u, 7u, 19u}) {
    EXPECT_EQ(cv::norm(a.RenderFrame(k), b.RenderFrame(k), cv::NORM_INF), 0.0);
    EXPECT_EQ(a.frame(k).centre_px, b.frame(k).centre_px);
    EXPECT_EQ(a.frame(k).boresight_az_rad, b.frame(k).boresight_az_rad);
  }
  const auto ra = a.RangeLog(), rb = b.RangeLog();
  ASSERT_EQ(ra.size(), rb.size());
  for (std::size_t i = 0; i < ra.size(); ++i) {
    EXPECT_TRUE(ra[i].range_m == rb[i].range_m || (std::isnan(ra[i].range_m) && std::isnan(rb[i].range_m)));
  }
  o.seed = 2;
  const BeaconSimulator c(o);
  EXPECT_GT(cv::norm(a.RenderFrame(0), c.RenderFrame(0), cv::NORM_INF), 0.0);
  EXPECT_NE(a.frame(0).boresight_az_rad, c.frame(0).boresight_az_rad);  // jitter differs
}

TEST(BeaconScenario, CheckRejectsBadOptions) {
  auto bad = [](auto mutate) {
    BeaconSimOptions o;
    mutate(o);
    std::string why;
    const bool ok = o.Check(&why);
    EXPECT_FALSE(why.empty() && !ok);
    return !ok;
  };
  EXPECT_FALSE(bad([](BeaconSimOptions&) {}));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.lamps = 4; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.sensor.bit_depth = 12; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.range_noise_mm = -1; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.range_error_rate = 1.0; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.trajectory.range_m = 10; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.trajectory.range_m = 20000; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.fps = 0; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.duration_s = 0; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.duration_s = NAN; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.peak_dn = 300; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.servo.lag_s = -0.1; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.turret_rate_hz = 0; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.occlusions.push_back({1.0, 0.0}); }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) { o.distractors = -1; }));
  EXPECT_TRUE(bad([](BeaconSimOptions& o) {
    o.trajectory = DefaultTrajectoryOptions(TrajectoryKind::kTurning);
    o.trajectory.turn_rate_rad_s = 0.001;  // radius 15 km around a point 600 m away
  }));
  BeaconSimOptions o;
  o.lamps = 3;
  EXPECT_THROW(BeaconSimulator{o}, Error);
  // A target far too fast for the turret leaves the image: refused, not silently clipped.
  BeaconSimOptions fast = Small(TrajectoryKind::kStraight, 2.0);
  fast.trajectory.range_m = 20;
  fast.trajectory.speed_mps = 100;
  try {
    BeaconSimulator s(fast);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
  }
}

// The option tables give the messages (one form "--flag must be ... unit"); the nested tables of the
// trajectory, sensor and servo are checked through the scenario's table.
TEST(BeaconScenario, CheckNamesTheOptionFromTheTables) {
  auto why_of = [](auto mutate) {
    BeaconSimOptions o;
    mutate(o);
    std::string why;
    EXPECT_FALSE(o.Check(&why));
    return why;
  };
  EXPECT_EQ(why_of([](BeaconSimOptions& o) { o.fps = 0; }), "--fps must be in (0, 1000] Hz");
  EXPECT_EQ(why_of([](BeaconSimOptions& o) { o.lamps = 65; }), "--lamps must be in [5, 64]");
  EXPECT_EQ(why_of([](BeaconSimOptions& o) { o.range_noise_mm = -1; }), "--range-noise-mm must be in [0, 10000] mm");
  EXPECT_EQ(why_of([](BeaconSimOptions& o) { o.trajectory.max_elevation_deg = 90; }),
            "--max-el-deg must be in (0, 85] deg");
  EXPECT_EQ(why_of([](BeaconSimOptions& o) { o.sensor.read_noise_dn = 101; }),
            "--read-noise-dn must be in [0, 100] DN");
  EXPECT_EQ(why_of([](BeaconSimOptions& o) { o.sensor.bit_depth = 12; }), "--bit-depth must be 8 or 16");
  EXPECT_EQ(why_of([](BeaconSimOptions& o) { o.servo.lag_s = 3; }), "--turret-lag-s must be in [0, 2] s");
  EXPECT_EQ(why_of([](BeaconSimOptions& o) { o.servo.jitter_min_hz = 6; }),
            "--jitter-max-hz must be >= --jitter-min-hz");
  // Report keys: from the flags, with the unit where the flag does not carry it.
  const BeaconSimOptions defaults;
  const io::Json j = defaults.ToJson();
  EXPECT_EQ(j.at("duration_s"), 10.0);
  EXPECT_EQ(j.at("max_el_deg"), 80.0);
  EXPECT_EQ(j.at("bit_depth"), "8");
  EXPECT_EQ(j.at("jitter_arcsec"), 5.0);
  EXPECT_EQ(j.at("seed"), 1u);
  EXPECT_EQ(j.at("trajectory").at("kind"), "default");
  EXPECT_TRUE(j.at("occlusions").is_array());
}

TEST(BeaconScenario, ParseOcclusion) {
  OcclusionInterval occ;
  std::string why;
  ASSERT_TRUE(ParseOcclusion("1.5:0.5", &occ, &why));
  EXPECT_EQ(occ.start_s, 1.5);
  EXPECT_EQ(occ.duration_s, 0.5);
  ASSERT_TRUE(ParseOcclusion("2:long", &occ, &why));
  EXPECT_EQ(occ.duration_s, 5.0);
  ASSERT_TRUE(ParseOcclusion("0:short", &occ, &why));
  EXPECT_EQ(occ.duration_s, 0.5);
  EXPECT_FALSE(ParseOcclusion("1.5", &occ, &why));
  EXPECT_FALSE(ParseOcclusion("x:1", &occ, &why));
  EXPECT_FALSE(ParseOcclusion("1:0", &occ, &why));
  EXPECT_FALSE(ParseOcclusion("-1:1", &occ, &why));
  EXPECT_FALSE(ParseOcclusion("1:2s", &occ, &why));
}

}  // namespace
}  // namespace rk::sim

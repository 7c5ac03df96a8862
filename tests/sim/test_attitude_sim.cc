// rk-sim attitude: motion profile of seed 001's dynamic test, truth consistency, rendering,
// turret log, random PnP problems, and the atomic trial folder.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>

#include "geo/angles.h"
#include "geo/body_attitude.h"
#include "io/error.h"
#include "sim/attitude_problems.h"
#include "sim/attitude_render.h"
#include "sim/attitude_scenario.h"
#include "sim/attitude_trial.h"
#include "sim/trial_folder.h"

namespace rk::sim {
namespace {

using geo::DegToRad;
using geo::RadToDeg;

constexpr double kExact = 1e-9;  // closed forms evaluated in double precision

AttitudeSimOptions Quick(double duration_s = 22.0) {
  AttitudeSimOptions o;
  o.duration_s = duration_s;
  o.fps = 5.0;  // truth only: a coarse frame grid keeps the test fast
  return o;
}

TEST(AttitudeSim, SeedOneProfileSixMetresInFiveBackAndTheAttitudeSwing) {
  const AttitudeSimulator sim(Quick());
  const AttitudeSimOptions& o = sim.options();
  const double t0 = o.t0_s;
  // Along the path: 6 m toward the station after the first leg, 1 m net at the end.
  const Eigen::Vector3d p0 = sim.PositionEnu(t0);
  const Eigen::Vector3d p1 = sim.PositionEnu(t0 + o.leg_in_s);
  const Eigen::Vector3d p2 = sim.PositionEnu(t0 + o.leg_in_s + o.leg_out_s);
  EXPECT_NEAR((p1 - p0).norm(), 6.0, kExact);
  EXPECT_NEAR((p2 - p0).norm(), 1.0, kExact);
  EXPECT_NEAR(p0.norm(), 22.0, kExact);
  EXPECT_LT(p1.norm(), p0.norm() - 4.0);  // approach: the range drops (path at 30° to the line of sight)
  EXPECT_NEAR(p1.z(), p0.z(), kExact);    // horizontal motion
  // Attitude: +10° yaw, +7° pitch, +5° roll at the turn, back to the start at the end.
  const geo::EulerZyx a0 = sim.Attitude(t0), a1 = sim.Attitude(t0 + o.leg_in_s), a2 = sim.Attitude(t0 + 22.0);
  EXPECT_NEAR(RadToDeg(geo::AngleDiff(a1.yaw_rad, a0.yaw_rad)), 10.0, 1e-7);
  EXPECT_NEAR(RadToDeg(a1.pitch_rad - a0.pitch_rad), 7.0, 1e-7);
  EXPECT_NEAR(RadToDeg(geo::AngleDiff(a1.roll_rad, a0.roll_rad)), 5.0, 1e-7);
  EXPECT_NEAR(RadToDeg(geo::AngleDiff(a2.yaw_rad, a0.yaw_rad)), 0.0, 1e-7);
  EXPECT_NEAR(RadToDeg(a0.yaw_rad), 300.0, 1e-7);
  // Smooth: no speed at the start, the turn and the end.
  const double h = 1e-4;
  for (double t : {t0, t0 + o.leg_in_s, t0 + 22.0}) {
    EXPECT_LT((sim.PositionEnu(t + h) - sim.PositionEnu(t - h)).norm() / (2 * h), 1e-3) << t;
  }
}

TEST(AttitudeSim, TruthPointsAreTheProjectedModelAtTheTrueBoresight) {
  const AttitudeSimulator sim(Quick(4.0));
  const auto& o = sim.options();
  for (const AttitudeFrameTruth& f : sim.frames()) {
    EXPECT_LT((f.R_enu_body - geo::RotationEnuFromBody(f.attitude)).norm(), kExact);
    for (std::size_t i = 0; i < o.marker_ids.size(); ++i) {
      // Back-project the truth pixel: the ray must pass through the marker centre.
      const Eigen::Vector3d ray = o.camera.RayEnu(f.marker_px[i], f.boresight.az_rad, f.boresight.el_rad);
      const Eigen::Vector3d p = f.p_enu + f.R_enu_body * o.markers_body[i];
      EXPECT_LT((p - p.dot(ray) * ray).norm(), 1e-9 * p.norm());
      EXPECT_NEAR(f.marker_radius_px[i], o.camera.fx() * std::asin(o.marker_radius_m / p.norm()), 1e-9);
    }
    EXPECT_GT(f.min_separation_px, 60.0);  // the default layout keeps markers apart
  }
}

TEST(AttitudeSim, YawAndRollWrapInsideTheRun) {
  AttitudeSimOptions o = Quick();
  o.yaw0_deg = 355.0;
  o.roll0_deg = 177.0;
  o.path_angle_deg = 0.0;
  const AttitudeSimulator sim(o);
  bool yaw_lo = false, yaw_hi = false, roll_pos = false, roll_neg = false;
  for (const auto& f : sim.frames()) {
    const double y = RadToDeg(f.attitude.yaw_rad), r = RadToDeg(f.attitude.roll_rad);
    EXPECT_GE(y, 0.0);
    EXPECT_LT(y, 360.0);
    EXPECT_GT(r, -180.0);
    EXPECT_LE(r, 180.0);
    yaw_lo |= y < 5.0;
    yaw_hi |= y > 355.0;
    roll_pos |= r > 177.0;
    roll_neg |= r < -178.0;
  }
  EXPECT_TRUE(yaw_lo && yaw_hi && roll_pos && roll_neg);
}

TEST(AttitudeSim, RefusesAMarkerOutsideTheImage) {
  AttitudeSimOptions o = Quick(2.0);
  o.range_m = 5.0;  // a 0.8 m target at 5 m fills more than the 100 mm camera's 0.4 m field
  o.approach_m = 1.0;
  o.return_m = 1.0;
  try {
    AttitudeSimulator sim(o);
    ADD_FAILURE() << "expected a usage error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    EXPECT_NE(std::string(e.what()).find("leaves the 2448x2048 image in frame 0"), std::string::npos);
  }
  AttitudeSimOptions bad = Quick();
  bad.hides.push_back({"nosecone", 0.0, 1.0});
  std::string why;
  DefaultAttitudeMarkers(&bad.marker_ids, &bad.markers_body);
  EXPECT_FALSE(bad.Check(&why));
  EXPECT_NE(why.find("nosecone"), std::string::npos);
  MarkerHide h;
  EXPECT_TRUE(ParseMarkerHide("fin:1.5:0.25", &h, &why));
  EXPECT_EQ(h.id, "fin");
  EXPECT_DOUBLE_EQ(h.start_s, 1.5);
  EXPECT_FALSE(ParseMarkerHide("fin:1.5", &h, &why));
  EXPECT_FALSE(ParseMarkerHide("fin:a:1", &h, &why));
}

TEST(AttitudeRender, DiscCentroidIsTheCentre) {
  // Noise-free disc at sub-pixel positions: its intensity centroid (and so any symmetric fit)
  // is the commanded centre (sub-sampling error < 1e-3 px).
  constexpr double kCentroidTol = 2e-3;
  for (double dx : {0.0, 0.17, 0.5, 0.73}) {
    cv::Mat s = cv::Mat::zeros(64, 64, CV_32FC1);
    Disc d;
    d.x_px = 31.0 + dx;
    d.y_px = 30.0 + 0.61 * dx;
    d.radius_px = 9.3;
    AddDiscs(&s, std::span<const Disc>(&d, 1));
    double sw = 0, sx = 0, sy = 0;
    for (int y = 0; y < s.rows; ++y) {
      for (int x = 0; x < s.cols; ++x) {
        const double v = s.at<float>(y, x);
        sw += v;
        sx += v * x;
        sy += v * y;
      }
    }
    EXPECT_NEAR(sx / sw, d.x_px, kCentroidTol);
    EXPECT_NEAR(sy / sw, d.y_px, kCentroidTol);
    EXPECT_NEAR(sw, d.amplitude_dn * M_PI * d.radius_px * d.radius_px, 0.01 * sw);  // flux = a π ρ²
    EXPECT_NEAR(s.at<float>(30, 31), d.amplitude_dn, 1e-3);  // flat top
  }
}

TEST(AttitudeSim, FramesRenderDeterministicallyWithBodyAndHiddenMarkers) {
  AttitudeSimOptions o = Quick(1.0);
  o.camera.width_px = 1000;  // a small sensor and a longer range keep the test fast
  o.camera.height_px = 800;
  o.camera.principal_point_px = {499.5, 399.5};
  o.range_m = 40.0;
  o.hides.push_back({"fin", 0.0, 0.5});
  const AttitudeSimulator sim(o);
  const cv::Mat a = sim.RenderFrame(1), b = sim.RenderFrame(1);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  const AttitudeFrameTruth& f = sim.frame(1);
  const std::size_t fin = 2;  // belly canopy fin ...
  ASSERT_EQ(sim.marker_ids()[fin], "fin");
  EXPECT_FALSE(f.visible[fin]);
  EXPECT_TRUE(sim.frame(4).visible[fin]);  // t = 0.8 s
  const cv::Mat sig = sim.RenderSignal(1);
  const Eigen::Vector2d pf = f.marker_px[fin], pn = f.marker_px[5];
  EXPECT_NEAR(sig.at<float>(static_cast<int>(std::lround(pf.y())), static_cast<int>(std::lround(pf.x()))), o.body_dn,
              1e-3);  // hidden: body paint only
  EXPECT_NEAR(sig.at<float>(static_cast<int>(std::lround(pn.y())), static_cast<int>(std::lround(pn.x()))),
              o.body_dn + o.marker_dn, 1e-2);
}

TEST(AttitudeSim, TurretLogIsQuantisedTrueBoresight) {
  const AttitudeSimulator sim(Quick(2.0));
  const auto log = sim.TurretLog();
  ASSERT_GT(log.size(), 100u);
  const double q = sim.options().turret_resolution_rad();
  for (const auto& s : log) {
    EXPECT_LE(std::abs(geo::AngleDiff(s.az_rad, s.true_az_rad)), 0.5 * q + 1e-12);
    EXPECT_LE(std::abs(s.el_rad - s.true_el_rad), 0.5 * q + 1e-12);
  }
  EXPECT_NEAR(log[1].t_s - log[0].t_s, 0.02, 1e-12);
}

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

TEST(TrialFolder, AtomicAndRefusesToOverwrite) {
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / ("rk_staged_" + std::to_string(::getpid()));
  fs::remove_all(base);
  fs::create_directories(base / "keep");
  std::ofstream(base / "keep" / "precious.txt") << "x";
  EXPECT_THROW(TrialFolder((base / "keep").string(), false), Error);
  {
    TrialFolder d((base / "new").string(), false);
    std::ofstream(d.Path("a.txt")) << "a";
    // Destroyed without Commit: nothing appears.
  }
  EXPECT_FALSE(fs::exists(base / "new"));
  {
    TrialFolder d((base / "keep").string(), true);
    std::ofstream(d.Path("b.txt")) << "b";
    d.Commit();
  }
  EXPECT_TRUE(fs::exists(base / "keep" / "b.txt"));
  EXPECT_FALSE(fs::exists(base / "keep" / "precious.txt"));
  std::size_t leftovers = 0;
  for (const auto& e : fs::directory_iterator(base)) leftovers += e.path().filename().string()[0] == '.';
  EXPECT_EQ(leftovers, 0u);
  fs::remove_all(base);
}

}  // namespace
}  // namespace rk::sim

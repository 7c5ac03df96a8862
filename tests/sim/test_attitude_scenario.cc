// rk-sim attitude's simulator (sim/attitude_scenario.h): the motion profile of seed 001's dynamic test, truth
// consistency, rendered frames and the turret log.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/core.hpp>

#include "geo/angles.h"
#include "geo/body_attitude.h"
#include "io/error.h"
#include "sim/attitude_scenario.h"

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

}  // namespace
}  // namespace rk::sim

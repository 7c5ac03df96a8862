// rk-sim radar (sim/radar_scenario.h): seed 002's scenario parameters, the measurement geometry on
// a hand-checked case, clutter and detection statistics, determinism per seed.
#include <gtest/gtest.h>

#include <GeographicLib/LocalCartesian.hpp>
#include <cmath>
#include <map>

#include "geo/angles.h"
#include "sim/radar_scenario.h"

namespace rk::sim {
namespace {

RadarSimOptions Opt(int scenario, int steps, std::uint64_t seed) {
  RadarSimOptions o;
  o.scenario = scenario;
  o.steps = steps;
  o.seed = seed;
  return o;
}

TEST(RadarSim, PaperScenarioParameters) {
  const RadarSimulator s1(Opt(1, 3, 1)), s2(Opt(2, 3, 1));
  // κ = t − t0 in seconds (default): s_a(κ) = [−10000, −20000 + 200κ, 40000] at t = 10 s.
  EXPECT_LT((s1.PlatformEnu(0, 10.0) - Eigen::Vector3d(-10000, -18000, 40000)).norm(), 1e-9);
  EXPECT_LT((s1.PlatformEnu(1, 10.0) - Eigen::Vector3d(20100, 20080, 20000)).norm(), 1e-9);
  EXPECT_LT((s1.PlatformAttitude(0, 10.0) - Eigen::Vector3d(0.02, 0.03, 0.03)).norm(), 1e-12);
  EXPECT_LT((s1.PlatformAttitude(1, 10.0) - Eigen::Vector3d(0.02, 0.01, 0.01)).norm(), 1e-12);
  EXPECT_LT((s2.PlatformAttitude(0, 10.0) - Eigen::Vector3d(0.008, 0.018, 0.018)).norm(), 1e-12);
  EXPECT_LT((s2.PlatformAttitude(1, 10.0) - Eigen::Vector3d(0.008, 0.004, 0.004)).norm(), 1e-12);
  // Target 5: [3000, 300, 3600, 400, 20000, 0] → after 5 s.
  EXPECT_LT((s1.TargetEnu(4, 5.0) - Eigen::Vector3d(4500, 5600, 20000)).norm(), 1e-9);
  EXPECT_EQ(s1.platforms()[0].bias[0], 1200.0);
  EXPECT_EQ(s1.platforms()[1].bias[5], 0.0037);
  // The other reading: κ = scan index.
  RadarSimOptions o = Opt(1, 3, 1);
  o.index_unit = RadarIndexUnit::kStep;
  const RadarSimulator st(o);
  EXPECT_LT((st.PlatformEnu(0, 10.0) - Eigen::Vector3d(-10000, -19600, 40000)).norm(), 1e-9);
  EXPECT_EQ(RadarSimOptions{}.ClutterRate(), 0.0);
  EXPECT_EQ(Opt(3, 1, 1).ClutterRate(), 5.0);
}

// A target straight ahead of a level platform heading north (yaw 0): θ = 0, φ from the geometry.
// Short baseline so that the Earth's curvature is negligible at the 1e-6 level.
TEST(RadarSim, TrueMeasurementHandChecked) {
  const Eigen::Vector3d platform(0, 0, 1000), target(0, 1000, 2000);
  const Eigen::Vector3d m = TrueRadarMeasurement(target, platform, Eigen::Vector3d::Zero(), 25, 110, 0);
  EXPECT_NEAR(m[0], std::sqrt(2.0) * 1000, 1e-3);
  EXPECT_NEAR(geo::WrapPi(m[1]), 0.0, 1e-6);
  EXPECT_NEAR(m[2], geo::kPi / 4, 2e-4);  // curvature over 1 km: 1000/6.4e6 rad
  // Yaw 90° (heading east): the same target is now on the left, θ = 270°.
  const Eigen::Vector3d m2 = TrueRadarMeasurement(target, platform, Eigen::Vector3d(geo::kPi / 2, 0, 0), 25, 110, 0);
  EXPECT_NEAR(m2[1], 1.5 * geo::kPi, 1e-6);
  // Positive pitch lowers the nose: the target appears higher.
  const Eigen::Vector3d m3 = TrueRadarMeasurement(target, platform, Eigen::Vector3d(0, 0.1, 0), 25, 110, 0);
  EXPECT_NEAR(m3[2], m[2] + 0.1, 1e-6);
}

TEST(RadarSim, PlotsNavAndBiases) {
  RadarSimOptions o = Opt(3, 200, 5);
  const RadarSimulator sim(o);
  std::map<int, int> per_radar;
  std::int64_t clutter = 0;
  double prev_t = -1;
  for (const SimRadarPlot& p : sim.plots()) {
    EXPECT_GE(p.t_s, prev_t);
    prev_t = p.t_s;
    EXPECT_GE(p.az_rad, 0.0);
    EXPECT_LT(p.az_rad, geo::kTwoPi);
    EXPECT_LE(std::abs(p.el_rad), geo::kPi / 2);
    EXPECT_GT(p.range_m, 0);
    ++per_radar[p.radar];
    if (p.target < 0) ++clutter;
  }
  EXPECT_EQ(clutter, sim.clutter_plots());
  // Poisson(5) per radar per scan over 400 scans: mean 2000, sd 45.
  EXPECT_NEAR(static_cast<double>(clutter), 2000.0, 200.0);
  EXPECT_EQ(per_radar[0] + per_radar[1], static_cast<int>(sim.plots().size()));
  EXPECT_EQ(sim.missed_detections(), 0);
  // Nav at the plot times, attitude = true + bias.
  ASSERT_EQ(sim.nav().size(), 400u);
  const SimNavRow& n = sim.nav()[2];  // radar a at t = 5
  EXPECT_EQ(n.radar, 0);
  EXPECT_NEAR(n.yaw_rad, sim.PlatformAttitude(0, 5.0)[0] + 0.0105, 1e-12);
  EXPECT_NEAR(n.pitch_rad, sim.PlatformAttitude(0, 5.0)[1] + 0.0035, 1e-12);
  GeographicLib::LocalCartesian lc(25, 110, 0);
  double x, y, z;
  lc.Forward(n.lat_deg, n.lon_deg, n.h_m, x, y, z);
  EXPECT_LT((Eigen::Vector3d(x, y, z) - sim.PlatformEnu(0, 5.0)).norm(), 1e-6);
}

TEST(RadarSim, DetectionProbabilityAndOffset) {
  RadarSimOptions o = Opt(1, 400, 6);
  o.detection_probability = 0.7;
  o.time_offset_b_s = 0.2;
  o.nav_rate_hz = 1.0;
  const RadarSimulator sim(o);
  // 2 radars × 5 targets × 400 scans, missed with probability 0.3: mean 1200, sd 29.
  EXPECT_NEAR(static_cast<double>(sim.missed_detections()), 1200.0, 120.0);
  for (const SimRadarPlot& p : sim.plots()) {
    const double frac = p.t_s - 5.0 * std::floor(p.t_s / 5.0 + 1e-9);
    EXPECT_NEAR(frac, p.radar == 1 ? 0.2 : 0.0, 1e-9);
  }
  // 1 Hz nav covering 0 … 1995.2 s for both radars.
  EXPECT_EQ(sim.nav().front().t_s, 0.0);
  EXPECT_GE(sim.nav().back().t_s, 1995.2);
}

TEST(RadarSim, DeterministicPerSeed) {
  const RadarSimulator a(Opt(3, 50, 9)), b(Opt(3, 50, 9)), c(Opt(3, 50, 10));
  ASSERT_EQ(a.plots().size(), b.plots().size());
  for (std::size_t i = 0; i < a.plots().size(); ++i) {
    EXPECT_EQ(a.plots()[i].range_m, b.plots()[i].range_m);
    EXPECT_EQ(a.plots()[i].target, b.plots()[i].target);
  }
  bool differs = a.plots().size() != c.plots().size();
  for (std::size_t i = 0; !differs && i < a.plots().size(); ++i) differs = a.plots()[i].range_m != c.plots()[i].range_m;
  EXPECT_TRUE(differs);
}

TEST(RadarSim, OptionsCheck) {
  std::string why;
  RadarSimOptions o;
  EXPECT_TRUE(o.Check(&why));
  o.scenario = 4;
  EXPECT_FALSE(o.Check(&why));
  o = RadarSimOptions{};
  o.time_offset_b_s = 3.0;  // more than half of dt = 5 s
  EXPECT_FALSE(o.Check(&why));
  o = RadarSimOptions{};
  o.names = {"a", "a"};
  EXPECT_FALSE(o.Check(&why));
  o = RadarSimOptions{};
  o.detection_probability = 0;
  EXPECT_FALSE(o.Check(&why));
}

}  // namespace
}  // namespace rk::sim

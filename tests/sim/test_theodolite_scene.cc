// rk-sim theodolite's scene and simulator (sim/theodolite_scene.h): seed 004 geometry, exact projection,
// tracking and the theodolite log, quantisation and determinism.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"
#include "sim/theodolite_scene.h"

namespace rk::sim {
namespace {

using geo::DegToRad;

constexpr double kPixel = 1e-7;   // px, projection round trips

TEST(TheodoliteScene, Seed004CameraIsThePapersSetUp) {
  const camera::CameraModel c = Seed004Camera();
  EXPECT_EQ(c.width_px, 1536);  // 16.9 mm / 0.011 mm
  EXPECT_NEAR(c.fx(), 1500.0 / 0.011, 1e-9);
  EXPECT_NEAR(c.principal_point_px.x(), 767.5, 0);
}

TEST(TheodoliteSimulator, ExactProjectionTrackingAndLog) {
  TheodoliteSimOptions o;
  o.duration_s = 1.0;
  o.speed_mps = 150.0;
  o.track_error_px = 25.0;
  o.theodolite_rate_hz = 50.0;
  o.encoder_step_arcsec = 1.0;
  const TheodoliteSimulator sim(o);
  ASSERT_EQ(sim.frames().size(), 21u);
  const camera::CameraModel& cam = o.camera;
  for (const TheodoliteFrameTruth& f : sim.frames()) {
    // Each pixel's line of sight at the true boresight points at its 3-D point.
    const Eigen::Vector3d ray = cam.RayEnu(f.nose_px, f.boresight_az_rad, f.boresight_el_rad);
    EXPECT_LT(ray.cross(f.points.nose.normalized()).norm(), 1e-12);
    // The tracking offset keeps the mid-point within track_error_px of the principal point.
    const Eigen::Vector3d mid = f.pose.tail_centre_enu + 0.5 * o.shape.length_m * f.pose.Axis();
    const Eigen::Vector2d m = *cam.ProjectEnu(mid, f.boresight_az_rad, f.boresight_el_rad);
    EXPECT_LE((m - cam.principal_point_px).norm(), 25.0 * std::sqrt(2.0) + kPixel);
    EXPECT_EQ(f.measured_px[0], f.nose_px);  // no noise, no quantisation by default
    // tail1 is left of the tail → nose direction on the screen (x right, y down).
    const Eigen::Vector2d dir = f.nose_px - 0.5 * (f.tail1_px + f.tail2_px);
    const Eigen::Vector2d left(dir.y(), -dir.x());
    EXPECT_GT((f.tail1_px - f.tail2_px).dot(left), 0.0);
    ASSERT_TRUE(f.alt_yaw_rad.has_value());
  }
  // Moving at 150 m/s along the axis, the elevation changes.
  EXPECT_GT(std::abs(sim.frames().back().boresight_el_rad - sim.frames().front().boresight_el_rad), 1e-3);
  const auto log = sim.TheodoliteLog();
  const double step = DegToRad(1.0 / 3600.0);
  for (const TheodoliteSample& s : log) {
    EXPECT_NEAR(std::remainder(s.el_rad, step), 0.0, 1e-12);
    EXPECT_LE(std::abs(s.el_rad - s.true_el_rad), 0.5 * step + 1e-12);
    EXPECT_GE(s.az_rad, 0.0);
    EXPECT_LT(s.az_rad, geo::kTwoPi);
  }
  EXPECT_LT(log.front().t_s, sim.frames().front().t_s);
  EXPECT_GT(log.back().t_s, sim.frames().back().t_s);
}

TEST(TheodoliteSimulator, QuantisationAndDeterminism) {
  TheodoliteSimOptions o;
  o.quantise = true;
  o.point_noise_px = 0.2;
  o.seed = 9;
  const TheodoliteSimulator a(o), b(o);
  for (std::size_t k = 0; k < a.frames().size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d& p = a.frames()[k].measured_px[static_cast<std::size_t>(i)];
      EXPECT_EQ(p.x(), std::round(p.x()));
      EXPECT_EQ(p, b.frames()[k].measured_px[static_cast<std::size_t>(i)]);
    }
  }
  TheodoliteSimOptions bad = o;
  bad.range_m = 12.0;  // a 2.5 m target at 12 m does not fit the 1500 mm camera's field
  EXPECT_THROW(TheodoliteSimulator{bad}, Error);
  bad = o;
  bad.shape.nose_length_m = 3.0;
  std::string why;
  EXPECT_FALSE(bad.Check(&why));
}

}  // namespace
}  // namespace rk::sim

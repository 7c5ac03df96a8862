// Marker tracking (extract/features_tracker.h) through a hidden marker, without identity errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "extract/features_tracker.h"
#include "sim/attitude_scenario.h"
#include "target/feature_model.h"

namespace rk::extract {
namespace {

TEST(FeatureTracker, TracksThroughAHiddenMarkerWithoutIdentityErrors) {
  // Small sensor, 40 m: 20 frames at 10 Hz; the fin is hidden from 0.4 s to 0.8 s.
  sim::AttitudeSimOptions o;
  o.camera.width_px = 1000;
  o.camera.height_px = 800;
  o.camera.principal_point_px = {499.5, 399.5};
  o.range_m = 40.0;
  o.duration_s = 2.0;
  o.fps = 10.0;
  o.leg_in_s = 4.0;  // a brisk approach: 2.3 m in 2 s
  o.hides.push_back({"fin", 0.4, 0.4});
  const sim::AttitudeSimulator sim(o);
  target::FeatureModel model;
  model.source = "target.json";
  model.ids = sim.marker_ids();
  model.p_body = sim.options().markers_body;
  FeatureTracker tracker(model, FeatureTrackOptions{});
  const std::size_t fin = 2;
  double s2 = 0;
  int n = 0;
  for (std::size_t k = 0; k < sim.frame_count(); ++k) {
    const FeatureFrameResult r = tracker.Process(sim.RenderFrame(k), static_cast<std::int64_t>(k), sim.frame(k).t_s);
    for (std::size_t i = 0; i < model.size(); ++i) {
      const FeaturePoint& p = r.points[i];
      const bool visible = sim.frame(k).visible[i];
      if (!visible) {
        EXPECT_FALSE(p.has_xy) << "frame " << k << " " << model.ids[i];
        EXPECT_EQ(p.status, RowStatus::kLost);
        continue;
      }
      ASSERT_TRUE(p.has_xy) << "frame " << k << " " << model.ids[i];
      const double e = (p.px - sim.frame(k).marker_px[i]).norm();
      EXPECT_LT(e, 0.2) << "frame " << k << " " << model.ids[i];  // an identity error would be ≫ 10 px
      s2 += e * e / 2;
      ++n;
    }
    if (k == 8) {
      EXPECT_EQ(r.points[fin].status, RowStatus::kReacquired);  // t = 0.8 s: back
    }
    if (k > 0) {
      EXPECT_FALSE(r.acquisition) << k;  // tracked, not re-identified
    }
  }
  EXPECT_LT(std::sqrt(s2 / n), 0.03);
  const FeatureTrackSummary& s = tracker.summary();
  EXPECT_EQ(s.acquisitions, 1);
  EXPECT_EQ(s.rows_by_status[static_cast<std::size_t>(RowStatus::kLost)], 4);
  EXPECT_EQ(s.rows_by_status[static_cast<std::size_t>(RowStatus::kReacquired)], 1);
  EXPECT_EQ(s.frames_with_4, 20);
}

}  // namespace
}  // namespace rk::extract

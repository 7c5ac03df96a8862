// Sub-pixel accuracy of the beacon centroid (seed 001 §2.1) against the
// simulator's truth, the flux-weighted mean of the lamp positions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "extract/beacon_detect.h"
#include "test_beacon_common.h"

namespace rk::extract {
namespace {

using testing::Cluster;
using testing::Render;
using testing::kMovingRmsPx;

using testing::kStaticBiasPx;
using testing::kStaticStdPx;
// A single-Gaussian fit / brightest-lamp locator lands on a lamp ≥ 2.6 px from
// the cluster centre; anything within 1 px of truth is the cluster, not a lamp.
constexpr double kNotOneLampPx = 1.0;

struct Stats {
  double max_abs_bias = 0, max_std = 0, rms = 0;
};

// Measures the cluster at `positions` with `reps` noise realisations each.
Stats Measure(int positions, int reps, int bit_depth, double scale_dn, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SpotDetector det;
  Stats st;
  double sum2 = 0;
  int n = 0;
  for (int p = 0; p < positions; ++p) {
    const double cx = 40 + u(rng), cy = 38 + u(rng);
    const auto spots = Cluster(cx, cy);
    const cv::Point2d truth = sim::FluxWeightedCentre(spots);
    double sx = 0, sy = 0, sxx = 0, syy = 0;
    for (int r = 0; r < reps; ++r) {
      cv::Mat f = Render(80, 80, spots, rng, bit_depth, scale_dn);
      const NoiseStats noise = det.FrameStats(f, 3);
      std::vector<SpotMeasurement> c;
      det.FindInBox(f, PixelBox{30, 30, 50, 50}, noise, &c);
      std::erase_if(c, [](const SpotMeasurement& m) { return m.area_px <= 0; });
      EXPECT_EQ(c.size(), 1u) << "the 5 lamps must merge into one region";
      if (c.empty()) return st;
      const double ex = c[0].x_px - truth.x, ey = c[0].y_px - truth.y;
      sx += ex;
      sy += ey;
      sxx += ex * ex;
      syy += ey * ey;
      sum2 += ex * ex + ey * ey;
      ++n;
    }
    const double mx = sx / reps, my = sy / reps;
    st.max_abs_bias = std::max({st.max_abs_bias, std::fabs(mx), std::fabs(my)});
    st.max_std = std::max({st.max_std, std::sqrt(sxx / reps - mx * mx), std::sqrt(syy / reps - my * my)});
  }
  st.rms = std::sqrt(sum2 / (2.0 * n));  // per axis
  return st;
}

TEST(BeaconCentroid, StaticBiasAndStd8Bit) {
  const Stats st = Measure(12, 60, 8, 1.0, 11);
  std::printf("8-bit: max |bias| %.4f px, max std %.4f px, rms %.4f px\n", st.max_abs_bias, st.max_std, st.rms);
  EXPECT_LE(st.max_abs_bias, kStaticBiasPx);
  EXPECT_LE(st.max_std, kStaticStdPx);
}

TEST(BeaconCentroid, StaticBiasAndStd16Bit) {
  // 16-bit sensor: everything ×100 in DN (thresholds must follow the data).
  const Stats st = Measure(8, 40, 16, 100.0, 12);
  std::printf("16-bit: max |bias| %.4f px, max std %.4f px, rms %.4f px\n", st.max_abs_bias, st.max_std, st.rms);
  EXPECT_LE(st.max_abs_bias, kStaticBiasPx);
  EXPECT_LE(st.max_std, kStaticStdPx);
}

TEST(BeaconCentroid, RandomPositionsRms) {
  // One realisation at each of many random positions: the RMS error a moving
  // beacon sees.
  const Stats st = Measure(300, 1, 8, 1.0, 13);
  std::printf("moving: rms %.4f px\n", st.rms);
  EXPECT_LE(st.rms, kMovingRmsPx);
}

TEST(BeaconCentroid, ClusterNotLockedToOneLamp) {
  std::mt19937_64 rng(5);
  const auto spots = Cluster(40.3, 39.7);
  const cv::Point2d truth = sim::FluxWeightedCentre(spots);
  cv::Mat f = Render(80, 80, spots, rng);
  SpotDetector det;
  std::vector<SpotMeasurement> c;
  det.FindInBox(f, PixelBox{0, 0, 79, 79}, det.FrameStats(f, 3), &c);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_LT(std::hypot(c[0].x_px - truth.x, c[0].y_px - truth.y), kNotOneLampPx);
  // The region spans the lamps (≥ 6 px wide), not one PSF.
  EXPECT_GE(c[0].region.width(), 6);
  EXPECT_GE(c[0].region.height(), 6);
  EXPECT_GT(c[0].size_px, 2.5);  // one PSF has size √2·1.2 ≈ 1.7 px
}

}  // namespace
}  // namespace rk::extract

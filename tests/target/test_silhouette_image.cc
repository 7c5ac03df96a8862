// Unit tests of target/silhouette_image.h: exact pixel coverage and the outline of the cylinder on a frame of
// rk-sim theodolite (the simulator gives the truth: pose, boresight and the exact points).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sim/theodolite_scene.h"
#include "target/silhouette_image.h"

namespace rk::target {
namespace {

constexpr double kPixel = 1e-7;  // px, projection round trips
constexpr double kArea = 1e-5;   // px², polygon clipping sums (float coverage)

TEST(SilhouetteImage, CoverageSumsToThePolygonArea) {
  // A slanted quadrilateral and a thin sliver: per-pixel clipped areas add up to the area.
  const std::vector<std::vector<Eigen::Vector2d>> polys = {
      {{10.3, 5.2}, {30.7, 9.9}, {25.1, 28.4}, {8.9, 20.05}},
      {{3.0, 3.0}, {40.0, 3.4}, {40.0, 3.9}},
  };
  for (const auto& poly : polys) {
    const cv::Mat cov = RasterizeConvexPolygon(poly, cv::Rect(0, 0, 48, 40));
    EXPECT_NEAR(cv::sum(cov)[0], PolygonArea(poly), kArea);
  }
  // Pixel (5, 5) fully inside a big square, pixel (9, 5) half covered.
  const std::vector<Eigen::Vector2d> sq = {{0.0, 0.0}, {9.0, 0.0}, {9.0, 9.0}, {0.0, 9.0}};
  const cv::Mat cov = RasterizeConvexPolygon(sq, cv::Rect(0, 0, 12, 12));
  EXPECT_NEAR(cov.at<float>(5, 5), 1.0, 1e-6);
  EXPECT_NEAR(cov.at<float>(5, 9), 0.5, 1e-6);
  EXPECT_NEAR(cov.at<float>(5, 10), 0.0, 1e-6);
}

TEST(SilhouetteImage, OutlineHasTheTipAndTheTailPoints) {
  sim::TheodoliteSimOptions o;
  const sim::TheodoliteSimulator sim(o);
  const sim::TheodoliteFrameTruth& f = sim.frames().front();
  const auto poly = SilhouettePolygon(o.camera, f.pose, o.shape, f.boresight_az_rad, f.boresight_el_rad);
  ASSERT_GE(poly.size(), 8u);
  double best_tip = 1e9, best_t1 = 1e9, best_t2 = 1e9;
  for (const auto& p : poly) {
    best_tip = std::min(best_tip, (p - f.nose_px).norm());
    best_t1 = std::min(best_t1, (p - f.tail1_px).norm());
    best_t2 = std::min(best_t2, (p - f.tail2_px).norm());
  }
  EXPECT_LT(best_tip, kPixel);  // the tip is a hull vertex
  // The rim is sampled every 2π/2048: the tail points are within one sample spacing of a hull vertex.
  const double r_px = 0.5 * (f.tail1_px - f.tail2_px).norm();
  EXPECT_LT(best_t1, r_px * 2 * M_PI / 2048);
  EXPECT_LT(best_t2, r_px * 2 * M_PI / 2048);
}

}  // namespace
}  // namespace rk::target

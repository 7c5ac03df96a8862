// Unit tests of target/silhouette_image.h: exact pixel coverage and the outline of the cylinder on a frame of
// rk-sim theodolite (the simulator gives the truth: pose, boresight and the exact points).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
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

// The straightforward exact coverage the rasteriser shortens (issue 20): the whole polygon clipped to each
// pixel's row slab, then to the pixel, Sutherland–Hodgman in the same order.
void Clip(const std::vector<Eigen::Vector2d>& in, int axis, double v, bool keep_above,
          std::vector<Eigen::Vector2d>* out) {
  out->clear();
  for (std::size_t i = 0, n = in.size(); i < n; ++i) {
    const Eigen::Vector2d& a = in[i];
    const Eigen::Vector2d& b = in[(i + 1) % n];
    const bool ia = keep_above ? a(axis) >= v : a(axis) <= v, ib = keep_above ? b(axis) >= v : b(axis) <= v;
    if (ia) out->push_back(a);
    if (ia != ib) {
      Eigen::Vector2d p = a + (v - a(axis)) / (b(axis) - a(axis)) * (b - a);
      p(axis) = v;
      out->push_back(p);
    }
  }
}

cv::Mat ReferenceCoverage(const std::vector<Eigen::Vector2d>& poly, const cv::Rect& roi) {
  cv::Mat cov(roi.size(), CV_32FC1, cv::Scalar(0));
  std::vector<Eigen::Vector2d> a, band, b, cell;
  for (int i = 0; i < roi.height; ++i) {
    Clip(poly, 1, roi.y + i - 0.5, true, &a);
    Clip(a, 1, roi.y + i + 0.5, false, &band);
    for (int j = 0; band.size() >= 3 && j < roi.width; ++j) {
      Clip(band, 0, roi.x + j - 0.5, true, &b);
      Clip(b, 0, roi.x + j + 0.5, false, &cell);
      if (cell.size() >= 3) cov.at<float>(i, j) = static_cast<float>(std::min(1.0, PolygonArea(cell)));
    }
  }
  return cov;
}

// The rasteriser clips each row from the edges near it and fills whole pixels without clipping: the same
// coverage to the bit as clipping the whole polygon for every pixel, on the cylinder's 4097-vertex outline at
// random sub-pixel offsets and on small polygons (a vertex on a pixel edge, a sliver, one inside a pixel).
TEST(SilhouetteImage, RasteriserEqualsClippingEveryPixel) {
  sim::TheodoliteSimOptions o;
  o.camera.width_px = o.camera.height_px = 640;
  o.camera.principal_point_px = {319.5, 319.5};
  const sim::TheodoliteSimulator sim(o);
  const sim::TheodoliteFrameTruth& f = sim.frames().front();
  const auto outline = SilhouettePolygon(o.camera, f.pose, o.shape, f.boresight_az_rad, f.boresight_el_rad);
  ASSERT_GE(outline.size(), 100u);
  std::vector<std::vector<Eigen::Vector2d>> polys = {
      {{0.0, 0.0}, {9.0, 0.0}, {9.0, 9.0}, {0.0, 9.0}},
      {{3.0, 3.0}, {40.0, 3.4}, {40.0, 3.9}},
      {{5.1, 5.2}, {5.4, 5.25}, {5.3, 5.45}},
      {{10.3, 5.5}, {30.7, 9.9}, {25.1, 28.4}, {8.9, 20.5}},
  };
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> U(-0.5, 0.5);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d d(U(rng), U(rng));
    std::vector<Eigen::Vector2d> moved = outline;
    for (auto& p : moved) p += d;
    polys.push_back(moved);
  }
  int compared = 0, partial = 0;
  for (const auto& poly : polys) {
    const cv::Rect roi = PolygonWindow(poly, 2);
    const cv::Mat fast = RasterizeConvexPolygon(poly, roi), ref = ReferenceCoverage(poly, roi);
    for (int i = 0; i < roi.height; ++i) {
      for (int j = 0; j < roi.width; ++j) {
        ASSERT_EQ(fast.at<float>(i, j), ref.at<float>(i, j)) << "pixel " << roi.x + j << ", " << roi.y + i;
        ++compared;
        partial += ref.at<float>(i, j) > 0.0f && ref.at<float>(i, j) < 1.0f;
      }
    }
  }
  EXPECT_GT(partial, 1000);  // the outline's edges were compared, not only empty and full pixels
  EXPECT_GT(compared, 10000);
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

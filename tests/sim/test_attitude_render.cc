// Rendering of markers (sim/attitude_render.h): a disc's intensity centroid is its centre.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <span>

#include "sim/attitude_render.h"

namespace rk::sim {
namespace {

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

}  // namespace
}  // namespace rk::sim

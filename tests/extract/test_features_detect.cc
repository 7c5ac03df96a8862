// Marker measurement and detection (extract/features_detect.h): accuracy on discs, spots, dark markers and
// ellipses against simulated truth, and full-frame detection.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "extract/features_detect.h"
#include "geo/angles.h"
#include "sim/attitude_render.h"
#include "sim/attitude_scenario.h"
#include "sim/render.h"

namespace rk::extract {
namespace {

cv::Mat Noisy(const cv::Mat& signal, std::uint64_t seed, double background = 20.0) {
  sim::SensorOptions s{background, 2.0, 40.0, 8};
  std::mt19937_64 rng(seed);
  return sim::Digitise(signal, s, rng);
}

struct ErrorStats {
  double bias_x = 0, bias_y = 0, rms = 0, mean_sigma = 0;
  int failures = 0;
};

// Measures a marker rendered by `render(centre, signal)` at random sub-pixel centres.
template <class Render>
ErrorStats Accuracy(Render render, int trials, bool dark = false, double radius = 8.0, double edge = 1.0) {
  ErrorStats st;
  MarkerDetectOptions o;
  o.dark = dark;
  MarkerDetector det(o);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  double sx = 0, sy = 0, s2 = 0, ss = 0;
  int n = 0;
  for (int k = 0; k < trials; ++k) {
    const Eigen::Vector2d c(60.0 + u(rng), 58.0 + u(rng));
    cv::Mat signal = cv::Mat::zeros(120, 120, CV_32FC1);
    render(c, &signal);
    cv::Mat img = Noisy(signal, 1000 + static_cast<std::uint64_t>(k), dark ? 200.0 : 20.0);
    det.SetFrame(img);
    const MarkerMeasurement m = det.Measure(c + Eigen::Vector2d(2.2, -1.6), 6.0, radius, edge);
    if (!m.ok) {
      ++st.failures;
      continue;
    }
    const Eigen::Vector2d e = m.px - c;
    sx += e.x();
    sy += e.y();
    s2 += e.squaredNorm() / 2;
    ss += m.sigma_px;
    ++n;
  }
  st.bias_x = sx / n;
  st.bias_y = sy / n;
  st.rms = std::sqrt(s2 / n);
  st.mean_sigma = ss / n;
  return st;
}

TEST(MarkerMeasure, DiscIsUnbiasedAndItsSigmaIsHonest) {
  // 8 px disc, 120 DN over 20 DN, read 2 DN + shot noise, 200 sub-pixel positions: bias within
  // 4 standard errors of zero, per-axis error ≈ the reported σ (0.6–1.6×: σ from the fit).
  const ErrorStats st = Accuracy(
      [](const Eigen::Vector2d& c, cv::Mat* s) {
        sim::Disc d;
        d.x_px = c.x();
        d.y_px = c.y();
        d.radius_px = 8.0;
        d.amplitude_dn = 120.0;
        sim::AddDiscs(s, std::span<const sim::Disc>(&d, 1));
      },
      120);
  EXPECT_EQ(st.failures, 0);
  EXPECT_LT(st.rms, 0.03);
  EXPECT_LT(std::abs(st.bias_x), 4 * st.rms / std::sqrt(120.0) + 2e-3);
  EXPECT_LT(std::abs(st.bias_y), 4 * st.rms / std::sqrt(120.0) + 2e-3);
  EXPECT_GT(st.mean_sigma / st.rms, 0.6);
  EXPECT_LT(st.mean_sigma / st.rms, 1.6);
}

TEST(MarkerMeasure, GaussianSpotDarkMarkerAndEllipseAreUnbiased) {
  // The fitted profile is only a model: any centrally symmetric marker image gives an unbiased
  // centre. A Gaussian LED spot (σ 1.8 px):
  const ErrorStats spot = Accuracy(
      [](const Eigen::Vector2d& c, cv::Mat* s) {
        sim::Spot sp{c.x(), c.y(), 1.8, 150.0};
        sim::AddSpots(s, std::span<const sim::Spot>(&sp, 1));
      },
      100, false, 1.0, 1.5);
  EXPECT_EQ(spot.failures, 0);
  EXPECT_LT(spot.rms, 0.05);
  EXPECT_LT(std::hypot(spot.bias_x, spot.bias_y), 0.01);
  // A dark disc on a bright background (polarity dark).
  const ErrorStats dark = Accuracy(
      [](const Eigen::Vector2d& c, cv::Mat* s) {
        *s += 150.0;  // a bright surface with a dark (0 DN above background) disc
        sim::Disc d{c.x(), c.y(), 7.0, 0.8, -150.0};
        sim::AddDiscs(s, std::span<const sim::Disc>(&d, 1));
      },
      100, true, 7.0, 0.8);
  EXPECT_EQ(dark.failures, 0);
  EXPECT_LT(dark.rms, 0.03);
  EXPECT_LT(std::hypot(dark.bias_x, dark.bias_y), 0.01);
  // A flat disc seen obliquely: an ellipse 10 × 6 px at 30°, 8×8 sub-sampled.
  const ErrorStats ell = Accuracy(
      [](const Eigen::Vector2d& c, cv::Mat* s) {
        const double ca = std::cos(0.52), sa = std::sin(0.52);
        for (int y = 0; y < s->rows; ++y) {
          for (int x = 0; x < s->cols; ++x) {
            if (std::hypot(x - c.x(), y - c.y()) > 12) continue;
            double cover = 0;
            for (int sy = 0; sy < 8; ++sy) {
              for (int sx = 0; sx < 8; ++sx) {
                const double dx = x - 0.5 + (sx + 0.5) / 8 - c.x(), dy = y - 0.5 + (sy + 0.5) / 8 - c.y();
                const double u = ca * dx + sa * dy, v = -sa * dx + ca * dy;
                cover += (u * u / 100.0 + v * v / 36.0 <= 1.0) ? 1.0 : 0.0;
              }
            }
            s->at<float>(y, x) += static_cast<float>(130.0 * cover / 64.0);
          }
        }
      },
      100, false, 8.0, 0.7);
  EXPECT_EQ(ell.failures, 0);
  EXPECT_LT(std::hypot(ell.bias_x, ell.bias_y), 0.01);
}

TEST(MarkerMeasure, RefusesNothingAndPicksTheNearestOfTwoMarkers) {
  MarkerDetector det;
  cv::Mat signal = cv::Mat::zeros(120, 160, CV_32FC1);
  det.SetFrame(Noisy(signal, 3));
  EXPECT_FALSE(det.Measure({60, 60}, 8, 6, 1).ok);  // empty sky: no marker
  std::vector<sim::Disc> d = {{50.3, 60.2, 6, 0.8, 120}, {75.6, 60.4, 6, 0.8, 120}};
  sim::AddDiscs(&signal, d);
  det.SetFrame(Noisy(signal, 4));
  const MarkerMeasurement a = det.Measure({53, 60}, 20, 6, 0.8);
  const MarkerMeasurement b = det.Measure({72, 61}, 20, 6, 0.8);
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_LT((a.px - Eigen::Vector2d(50.3, 60.2)).norm(), 0.1);
  EXPECT_LT((b.px - Eigen::Vector2d(75.6, 60.4)).norm(), 0.1);
  EXPECT_FALSE(det.Measure({4, 60}, 3, 6, 0.8).ok);  // window cut by the border
}

TEST(MarkerDetect, FindsEveryMarkerOnTheBodyAndNotTheGlint) {
  sim::AttitudeSimOptions o;
  o.duration_s = 0.2;
  o.camera.width_px = 1000;  // small sensor, 40 m: markers ≈ 8 px radius on a 580 px body
  o.camera.height_px = 800;
  o.camera.principal_point_px = {499.5, 399.5};
  o.range_m = 40.0;
  const sim::AttitudeSimulator sim(o);
  cv::Mat signal = sim.RenderSignal(0);
  sim::Spot glint{60.0, 700.0, 0.7, 200.0};  // a sharp glint far from the target
  sim::AddSpots(&signal, std::span<const sim::Spot>(&glint, 1));
  MarkerDetector det;
  det.SetFrame(Noisy(signal, 5));
  const std::vector<MarkerMeasurement> found = det.DetectAll();
  const auto& truth = sim.frame(0);
  for (std::size_t i = 0; i < truth.marker_px.size(); ++i) {
    double best = 1e9;
    for (const auto& m : found) best = std::min(best, (m.px - truth.marker_px[i]).norm());
    EXPECT_LT(best, 0.05) << sim.marker_ids()[i];
  }
  EXPECT_LE(found.size(), truth.marker_px.size() + 1);
}

}  // namespace
}  // namespace rk::extract

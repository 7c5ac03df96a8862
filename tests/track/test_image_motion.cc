// The image motion model shared by rk-extract points and features (track/image_motion.h): velocity from the
// first two measurements after a start, Kalman updates after, restart from the last measurement.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "track/image_motion.h"

namespace rk::track {
namespace {

constexpr double kExactPx = 1e-9;

TEST(ImagePointMotion, TwoMeasurementsGiveTheVelocityWhateverItIs) {
  // 5·10⁴ px/s: far beyond the 200 px/s velocity prior, which a Kalman update would barely move.
  ImagePointMotion m;
  const Eigen::Vector2d v(5.0e4, -3.0e4), z0(100.0, 200.0);
  const Eigen::Matrix2d R = 1e-4 * Eigen::Matrix2d::Identity();
  m.Start(z0, R, 0.0);
  EXPECT_TRUE(m.started());
  EXPECT_FALSE(m.settled());
  m.PredictTo(1e-3);
  EXPECT_NEAR((m.Predicted() - z0).norm(), 0.0, kExactPx) << "before a second measurement: the last position";
  m.Update(z0 + v * 1e-3, R, 1e-3);
  EXPECT_TRUE(m.settled());
  m.PredictTo(2e-3);
  EXPECT_NEAR((m.Predicted() - (z0 + v * 2e-3)).norm(), 0.0, kExactPx);
  // Its σ: the two measurements' errors over the interval, propagated one interval on (≥ √(3R)).
  const Eigen::Matrix2d S = m.InnovationCovariance(Eigen::Matrix2d::Zero());
  EXPECT_GT(S(0, 0), 3 * R(0, 0));
}

TEST(ImagePointMotion, PredictionErrorsMatchTheirCovariance) {
  // Constant velocity with measurement noise: the predictions' NEES (2 dof) over many steps is near 2.
  constexpr int kSteps = 4000;
  constexpr double kDt = 1e-3, kNoisePx = 0.05;
  // χ²₂ has mean 2; the Singer process noise (no acceleration here) makes the σ somewhat conservative, never
  // optimistic.
  constexpr double kNeesLow = 1.2, kNeesHigh = 2.4;
  ImageMotionOptions o;
  o.accel_sigma_px_s2 = 2000.0;
  ImagePointMotion m(o);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, kNoisePx);
  const Eigen::Matrix2d R = kNoisePx * kNoisePx * Eigen::Matrix2d::Identity();
  const auto truth = [](double t) { return Eigen::Vector2d(50.0 + 800.0 * t, 80.0 - 300.0 * t); };
  m.Start(truth(0) + Eigen::Vector2d(n(rng), n(rng)), R, 0.0);
  double nees = 0;
  int count = 0;
  for (int k = 1; k < kSteps; ++k) {
    const double t = k * kDt;
    m.PredictTo(t);
    if (k > 20) {
      const Eigen::Vector2d e = m.Predicted() - truth(t);
      nees += e.dot(m.InnovationCovariance(Eigen::Matrix2d::Zero()).inverse() * e);
      ++count;
    }
    m.Update(truth(t) + Eigen::Vector2d(n(rng), n(rng)), R, t);
  }
  const double mean = nees / count;
  std::printf("prediction NEES %.2f over %d steps\n", mean, count);
  EXPECT_LT(mean, kNeesHigh);
  EXPECT_GT(mean, kNeesLow);
}

TEST(ImagePointMotion, RestartTakesTheVelocityFromTheLastMeasurementOn) {
  ImagePointMotion m;
  const Eigen::Matrix2d R = 1e-4 * Eigen::Matrix2d::Identity();
  m.Start({0, 0}, R, 0.0);
  m.Update({10, 0}, R, 0.01);  // 1000 px/s in x
  m.Update({20, 0}, R, 0.02);
  m.RestartFromLast();         // the target turned: 1000 px/s in y from (20, 0)
  EXPECT_FALSE(m.settled());
  m.Update({20, 10}, R, 0.03);
  m.PredictTo(0.04);
  EXPECT_NEAR(m.Predicted().x(), 20.0, 1e-6);
  EXPECT_NEAR(m.Predicted().y(), 20.0, 1e-6);
}

}  // namespace
}  // namespace rk::track

// The camera clock → host clock mapping of rk-capture's aravis: cameras (capture/camera_clock.h): a camera whose
// crystal runs 40 ppm fast, stamps 20 frames a second; the host sees each frame 2 ms after the exposure plus a
// jitter of 0.3 ms (exponential: the network and the scheduler only ever delay). The mapping must give every
// frame's host time within a fraction of the jitter once it has settled, follow the drift, never step by more
// than a small fraction of a frame period, and start again when the camera's clock goes back.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "capture/camera_clock.h"

namespace rk::capture {
namespace {

constexpr double kRate = 20.0, kDriftPpm = 40.0, kLatencyS = 0.002, kJitterS = 0.0003;
constexpr double kSettledErrorS = 2e-4;  // |mapped − (exposure + mean latency)| after 30 s (jitter 0.3 ms)
constexpr double kDriftToleranceppm = 5.0;
constexpr double kMaxCorrectionS = 2e-4;  // a frame's mapped time against the previous mapping's prediction

TEST(CameraClockMapper, FollowsOffsetAndDriftWithoutSteps) {
  std::mt19937_64 rng(3);
  std::exponential_distribution<double> late(1.0 / kJitterS);
  CameraClockMapper m;
  const std::int64_t camera0_ns = 1795951479123456789LL;  // a camera counting from its own epoch
  const double host0 = 14565.25;
  double worst_settled = 0, worst_step = 0;
  for (int k = 0; k < 600 * static_cast<int>(kRate); ++k) {
    const double exposure_host = host0 + k / kRate;  // truth on the host clock
    const std::int64_t cam_ns = camera0_ns + std::llround(k / kRate * (1.0 + kDriftPpm * 1e-6) * 1e9);
    const double arrival = exposure_host + kLatencyS + late(rng);
    const double before = k > 0 ? m.Map(cam_ns) : 0.0;
    const double mapped = m.Add(cam_ns, arrival);
    if (k > 0) worst_step = std::max(worst_step, std::abs(mapped - before));
    if (k > 30 * kRate) {
      worst_settled = std::max(worst_settled, std::abs(mapped - (exposure_host + kLatencyS + kJitterS)));
    }
  }
  std::printf("settled error %.1f us, largest correction %.1f us, drift %.2f ppm, jitter %.1f us\n",
              1e6 * worst_settled, 1e6 * worst_step, m.drift_ppm(), 1e6 * m.jitter_s());
  EXPECT_LT(worst_settled, kSettledErrorS);
  EXPECT_LT(worst_step, kMaxCorrectionS);
  // The camera's clock runs fast: host = camera / (1 + 40e-6), a drift of −40 ppm.
  EXPECT_NEAR(m.drift_ppm(), -kDriftPpm, kDriftToleranceppm);
}

TEST(CameraClockMapper, StartsAgainWhenTheCameraClockGoesBack) {
  CameraClockMapper m;
  for (int k = 0; k < 100; ++k) m.Add(5'000'000'000LL + k * 50'000'000LL, 100.0 + k * 0.05 + 0.002);
  m.Reset();
  const double t = m.Add(1'000'000LL, 106.002);  // power-cycled camera: its clock near 0
  EXPECT_NEAR(t, 106.002, 1e-9);
  EXPECT_EQ(m.frames(), 1);
}

}  // namespace
}  // namespace rk::capture

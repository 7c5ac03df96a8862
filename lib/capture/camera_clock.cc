// The camera clock → host clock mapping; see camera_clock.h.
#include "capture/camera_clock.h"

#include <algorithm>
#include <cmath>

namespace rk::capture {
namespace {

constexpr double kDriftPriorSigma = 200e-6;   // crystal against host, before any frame says
constexpr double kOffsetWalk = 1e-7;          // s/√s: the offset's random walk (NTP slews, latency changes)
constexpr double kDriftWalk = 1e-8;           // 1/√s: the drift's random walk (temperature)
constexpr double kInitialJitterVar = 1e-6;    // s²: 1 ms until the innovations say more
constexpr double kJitterWeight = 0.02;        // of the latest innovation in the jitter's running mean
constexpr double kInnovationClip = 9.0;       // innovations beyond 3σ enter the jitter's mean as 3σ (a late frame)

}  // namespace

double CameraClockMapper::Add(std::int64_t camera_ns, double host_s) {
  if (n_ == 0) {
    first_ns_ = camera_ns;
    last_c_ = 0.0;
    r_ = kInitialJitterVar;
    x_ << host_s, 0.0;
    P_ << r_, 0.0, 0.0, kDriftPriorSigma * kDriftPriorSigma;
    ++n_;
    return Map(camera_ns);
  }
  const double c = static_cast<double>(camera_ns - first_ns_) * 1e-9;
  const double y = host_s - c;
  // Predict over the camera time since the last frame.
  const double dt = std::max(0.0, c - last_c_);
  last_c_ = c;
  P_(0, 0) += kOffsetWalk * kOffsetWalk * dt;
  P_(1, 1) += kDriftWalk * kDriftWalk * dt;
  // Update with y = a + b (x − x0).
  const Eigen::RowVector2d H(1.0, c);
  const double S = (H * P_ * H.transpose())(0, 0) + r_;
  const Eigen::Vector2d K = P_ * H.transpose() / S;
  const double nu = y - (H * x_)(0, 0);
  x_ += K * nu;
  const Eigen::Matrix2d IKH = Eigen::Matrix2d::Identity() - K * H;
  P_ = IKH * P_ * IKH.transpose() + K * r_ * K.transpose();
  P_ = 0.5 * (P_ + P_.transpose()).eval();
  // The jitter: a running mean of the innovations' squares less the state's part, each clipped at 3σ.
  const double e2 = std::min(nu * nu, kInnovationClip * S);
  r_ = std::max(1e-12, (1.0 - kJitterWeight) * r_ + kJitterWeight * std::max(0.0, e2 - (S - r_)));
  ++n_;
  return Map(camera_ns);
}

double CameraClockMapper::Map(std::int64_t camera_ns) const {
  const double c = static_cast<double>(camera_ns - first_ns_) * 1e-9;
  return x_(0) + (1.0 + x_(1)) * c;
}

double CameraClockMapper::jitter_s() const { return std::sqrt(r_); }

}  // namespace rk::capture

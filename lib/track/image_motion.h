// A point's motion in the image (px), for predicting where a tracker looks next: the Singer filter
// (singer.h, one per image axis) started from two measurements. rk-extract points and rk-extract features
// both predict their search windows with it (one owner of the image motion model).
//
// Start: at a seed, or a restart, the position is known and the velocity is not. A high-speed camera's image
// velocity can be 10⁵ px/s, far beyond any prior, so the second measurement after a start sets the velocity
// from the two ((z₂ − z₁) / Δt, its variance (R₁ + R₂) / Δt²) instead of a Kalman update against a prior;
// later measurements are Kalman updates (Joseph form). A manoeuvre the model did not expect restarts the
// motion from the last two measurements (RestartFromLast).
#pragma once

#include <Eigen/Core>

#include "track/singer.h"

namespace rk::track {

struct ImageMotionOptions {
  double maneuver_time_s = 0.1;        // Singer τ_m (s)
  double accel_sigma_px_s2 = 20000.0;  // Singer σ_m, RMS image acceleration (px/s²)
  double init_vel_sigma_px_s = 200.0;  // velocity σ between a start and the second measurement (px/s)
};

class ImagePointMotion {
 public:
  explicit ImagePointMotion(const ImageMotionOptions& o = {}) : opt_(o), kf_({Axis(o), Axis(o)}) {}

  // (Re)starts at z (covariance R) at time t_s, counted as its first measurement.
  void Start(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, double t_s) {
    kf_.Initialise(z, R, opt_.init_vel_sigma_px_s, opt_.accel_sigma_px_s2);
    t_ = first_t_ = last_t_ = t_s;
    first_z_ = last_z_ = z;
    first_R_ = last_R_ = R;
    updates_ = 1;
  }
  bool started() const { return updates_ > 0; }
  // The velocity comes from measurements (two since the last start).
  bool settled() const { return updates_ >= 2; }

  // Moves the prediction to t_s (nothing when t_s is not later than the filter's time).
  void PredictTo(double t_s) {
    if (t_s > t_) {
      kf_.Predict(t_s - t_);
      t_ = t_s;
    }
  }
  Eigen::Vector2d Predicted() const { return kf_.PredictedMeasurement(); }
  // Covariance of a measurement's innovation (R: the measurement's own; zero for the prediction's).
  Eigen::Matrix2d InnovationCovariance(const Eigen::Matrix2d& R) const { return kf_.InnovationCovariance(R); }
  double Mahalanobis2(const Eigen::Vector2d& z, const Eigen::Matrix2d& R) const { return kf_.Mahalanobis2(z, R); }

  // A measurement z (covariance R) at t_s (predicted there first).
  void Update(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, double t_s) {
    PredictTo(t_s);
    if (updates_ == 1 && t_s > first_t_) {
      const double dt = t_s - first_t_;
      SingerFilter<2>::State x = SingerFilter<2>::State::Zero();
      SingerFilter<2>::Cov P = SingerFilter<2>::Cov::Zero();
      const Eigen::Vector2d v = (z - first_z_) / dt;
      for (int i = 0; i < 2; ++i) {
        x(3 * i) = z(i);
        x(3 * i + 1) = v(i);
        P(3 * i, 3 * i) = R(i, i);
        P(3 * i, 3 * i + 1) = P(3 * i + 1, 3 * i) = R(i, i) / dt;
        P(3 * i + 1, 3 * i + 1) = (R(i, i) + first_R_(i, i)) / (dt * dt);
        P(3 * i + 2, 3 * i + 2) = opt_.accel_sigma_px_s2 * opt_.accel_sigma_px_s2;
      }
      kf_.set_state(x, P);
    } else {
      kf_.Update(z, R);
    }
    ++updates_;
    last_z_ = z;
    last_R_ = R;
    last_t_ = t_s;
  }

  // The motion restarts from the last measurement: the next Update sets the velocity from it.
  void RestartFromLast() {
    updates_ = 1;
    first_z_ = last_z_;
    first_R_ = last_R_;
    first_t_ = last_t_;
  }

 private:
  static SingerAxisOptions Axis(const ImageMotionOptions& o) {
    SingerAxisOptions a;
    a.maneuver_time_s = o.maneuver_time_s;
    a.accel_sigma = o.accel_sigma_px_s2;
    return a;
  }

  ImageMotionOptions opt_;
  SingerFilter<2> kf_;
  double t_ = 0.0, first_t_ = 0.0, last_t_ = 0.0;
  Eigen::Vector2d first_z_{0, 0}, last_z_{0, 0};
  Eigen::Matrix2d first_R_ = Eigen::Matrix2d::Identity(), last_R_ = Eigen::Matrix2d::Identity();
  int updates_ = 0;
};

}  // namespace rk::track

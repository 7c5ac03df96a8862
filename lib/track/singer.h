// Singer-model Kalman filter (R. A. Singer, "Estimating optimal tracking filter
// performance for manned maneuvering targets", IEEE Trans. AES-6(4), 1970), as
// used for beacon prediction in seed 001 §2.2 (Guan et al. 2014, eqs. 5–11).
//
// Model, per axis (N independent axes, e.g. image x and y):
//   state  x = [u, u', u'']ᵀ,  continuous  u''' = −a u'' + w(t),  E[w(t) w(s)] = q δ(t − s),
//   a = 1 / τ_m (maneuver time constant τ_m), q = 2 a σ_m² (σ_m = RMS acceleration).
//   x_{k+1} = Ψ(T) x_k + ζ_k,  ζ_k ~ N(0, Q(T)),  T = t_{k+1} − t_k (any T ≥ 0)
//   Ψ(T) = [[1, T, (aT − 1 + e^{−aT})/a²],
//           [0, 1, (1 − e^{−aT})/a      ],
//           [0, 0, e^{−aT}              ]]
//   (the paper's eq. 9 wrongly squares the two upper entries of the last column.)
//   Q(T) = q ∫₀ᵀ c(s) c(s)ᵀ ds, c(s) = Ψ(s) e₃ — Singer's exact discrete noise; in
//   closed form for aT ≥ kSingerSeriesLimit, else by its power series in aT (the
//   closed form loses all digits for aT ≪ 1 by cancellation).
//   z_k = H x_k + v_k,  v_k ~ N(0, R),  H picks u of each axis.
// Filter (eq. 11, with the identity of the full state size):
//   x_{k+1|k} = Φ x_{k|k},  P_{k+1|k} = Φ P_{k|k} Φᵀ + Q
//   S = H P_{k+1|k} Hᵀ + R,  K = P Hᵀ S⁻¹,  x_{k+1|k+1} = x_{k+1|k} + K (z − H x_{k+1|k})
//   P_{k+1|k+1} = (I − K H) P (I − K H)ᵀ + K R Kᵀ  (Joseph form), then symmetrised.
// Assumptions: axes are uncoupled (Φ, Q block-diagonal); R may be full.
// Fixed-size Eigen matrices: no heap allocation per step.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <string>

namespace rk::track {

// Below this aT the series form of Ψ13 and Q is used.
inline constexpr double kSingerSeriesLimit = 1.0;

// Ψ(T) of one axis; T ≥ 0 (s), a > 0 (1/s).
Eigen::Matrix3d SingerTransition(double T_s, double a_per_s);
// Q(T) of one axis for white-noise intensity q = 2 a σ_m², choosing the
// accurate form; and the two forms separately (for tests).
Eigen::Matrix3d SingerProcessNoise(double T_s, double a_per_s, double q);
Eigen::Matrix3d SingerProcessNoiseClosed(double T_s, double a_per_s, double q);
Eigen::Matrix3d SingerProcessNoiseSeries(double T_s, double a_per_s, double q);

// Ψ(T) and the T-dependent factors of Q(T) for one step, so that a filter run many times over the same times
// with different q (rk-smooth singer's maximum-likelihood choice of σ_m, every column of a series) computes
// them once: Q(q) equals SingerProcessNoise(T, a, q) bit for bit (the same products in the same order).
class SingerStep {
 public:
  SingerStep() = default;
  SingerStep(double T_s, double a_per_s);
  const Eigen::Matrix3d& transition() const { return phi_; }
  Eigen::Matrix3d ProcessNoise(double q) const;

 private:
  double T_s_ = 0.0, a_per_s_ = 1.0;
  bool series_ = true;
  Eigen::Matrix3d phi_ = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d pow_ = Eigen::Matrix3d::Zero(), sum_ = Eigen::Matrix3d::Zero();  // series form: T^k, Horner sum
};

struct SingerAxisOptions {
  double maneuver_time_s = 2.0;  // τ_m = 1/a (s), > 0
  double accel_sigma = 50.0;     // σ_m, RMS acceleration (units/s²), ≥ 0
  bool Check(std::string* why) const;
};

template <int N>
class SingerFilter {
 public:
  static constexpr int kStates = 3 * N;
  using State = Eigen::Matrix<double, kStates, 1>;
  using Cov = Eigen::Matrix<double, kStates, kStates>;
  using Meas = Eigen::Matrix<double, N, 1>;
  using MeasCov = Eigen::Matrix<double, N, N>;

  explicit SingerFilter(const std::array<SingerAxisOptions, N>& axes = {}) : axes_(axes) {
    x_.setZero();
    P_.setIdentity();
  }

  // Starts at position z with covariance R_pos, velocity and acceleration
  // zero-mean with the given standard deviations (per axis).
  void Initialise(const Meas& z, const MeasCov& R_pos, double vel_sigma, double acc_sigma) {
    x_.setZero();
    P_.setZero();
    for (int i = 0; i < N; ++i) {
      x_(3 * i) = z(i);
      for (int j = 0; j < N; ++j) P_(3 * i, 3 * j) = R_pos(i, j);
      P_(3 * i + 1, 3 * i + 1) = vel_sigma * vel_sigma;
      P_(3 * i + 2, 3 * i + 2) = acc_sigma * acc_sigma;
    }
    initialised_ = true;
  }
  bool initialised() const { return initialised_; }

  // Time update over T_s ≥ 0 seconds.
  void Predict(double T_s) {
    Cov Phi = Cov::Zero();
    Cov Q = Cov::Zero();
    for (int i = 0; i < N; ++i) {
      const double a = 1.0 / axes_[i].maneuver_time_s;
      const double q = 2.0 * a * axes_[i].accel_sigma * axes_[i].accel_sigma;
      Phi.template block<3, 3>(3 * i, 3 * i) = SingerTransition(T_s, a);
      Q.template block<3, 3>(3 * i, 3 * i) = SingerProcessNoise(T_s, a, q);
    }
    x_ = Phi * x_;
    P_ = Phi * P_ * Phi.transpose() + Q;
    P_ = 0.5 * (P_ + P_.transpose()).eval();
  }

  // Predicted measurement H x and innovation covariance S = H P Hᵀ + R.
  Meas PredictedMeasurement() const {
    Meas z;
    for (int i = 0; i < N; ++i) z(i) = x_(3 * i);
    return z;
  }
  MeasCov InnovationCovariance(const MeasCov& R) const {
    MeasCov S;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) S(i, j) = P_(3 * i, 3 * j) + R(i, j);
    return S;
  }
  // Squared Mahalanobis distance of z from the prediction (gate: compare with a
  // χ²(N) quantile).
  double Mahalanobis2(const Meas& z, const MeasCov& R) const {
    const Meas nu = z - PredictedMeasurement();
    return nu.dot(InnovationCovariance(R).inverse() * nu);
  }

  // Measurement update, Joseph form.
  void Update(const Meas& z, const MeasCov& R) {
    Eigen::Matrix<double, kStates, N> PHt;
    for (int j = 0; j < N; ++j) PHt.col(j) = P_.col(3 * j);
    const MeasCov S = InnovationCovariance(R);
    const Eigen::Matrix<double, kStates, N> K = PHt * S.inverse();  // N ≤ 4: closed-form inverse
    const Meas nu = z - PredictedMeasurement();
    x_ += K * nu;
    Cov IKH = Cov::Identity();
    for (int j = 0; j < N; ++j) IKH.col(3 * j) -= K.col(j);
    P_ = IKH * P_ * IKH.transpose() + K * R * K.transpose();
    P_ = 0.5 * (P_ + P_.transpose()).eval();
  }

  const State& state() const { return x_; }
  const Cov& covariance() const { return P_; }
  void set_state(const State& x, const Cov& P) {
    x_ = x;
    P_ = P;
    initialised_ = true;
  }
  const std::array<SingerAxisOptions, N>& axes() const { return axes_; }

 private:
  std::array<SingerAxisOptions, N> axes_;
  State x_;
  Cov P_;
  bool initialised_ = false;
};

}  // namespace rk::track

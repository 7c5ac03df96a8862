// Singer-model transition and exact discrete process noise; see singer.h.
//
// Closed form of Q (Singer 1970, with E = e^{−aT}, x = aT):
//   Q11 = q/(2a⁵) [1 − E² + 2x + 2x³/3 − 2x² − 4xE]
//   Q12 = q/(2a⁴) [E² + 1 − 2E + 2xE − 2x + x²]
//   Q13 = q/(2a³) [1 − E² − 2xE]
//   Q22 = q/(2a³) [4E − 3 − E² + 2x]
//   Q23 = q/(2a²) [E² + 1 − 2E]
//   Q33 = q/(2a)  [1 − E²]
// Series form: with c_i(s) = Σ_k (−a)^k s^{k+p_i}/(k+p_i)!, p = (2, 1, 0),
//   Q_ij = q T^{p_i+p_j+1} Σ_n (−x)^n / (n+p_i+p_j+1) · Σ_{k=0..n} 1/((k+p_i)! (n−k+p_j)!)
// which converges for every x and has no cancellation for x < 1.
#include "track/singer.h"

#include <cmath>

#include "io/error.h"

namespace rk::track {
namespace {

constexpr int kSeriesTerms = 28;  // x < 1: the last term is < 2^28/28! ≈ 1e-21 of the first

double Factorial(int n) {
  double f = 1.0;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

}  // namespace

bool SingerAxisOptions::Check(std::string* why) const {
  if (!(maneuver_time_s > 0.0) || !std::isfinite(maneuver_time_s)) {
    if (why) *why = "maneuver time constant must be > 0 s";
    return false;
  }
  if (!(accel_sigma >= 0.0) || !std::isfinite(accel_sigma)) {
    if (why) *why = "acceleration sigma must be >= 0";
    return false;
  }
  return true;
}

Eigen::Matrix3d SingerTransition(double T, double a) {
  RK_CHECK(T >= 0.0 && a > 0.0, "Singer transition needs T >= 0 and a > 0");
  const double x = a * T;
  const double E = std::exp(-x);
  double psi13;
  if (x < kSingerSeriesLimit) {
    // (x − 1 + e^{−x})/a² = T² Σ_k (−x)^k/(k+2)!
    double sum = 0.0, term = 0.5;  // k = 0: 1/2!
    for (int k = 0; k < kSeriesTerms; ++k) {
      sum += term;
      term *= -x / (k + 3);
    }
    psi13 = T * T * sum;
  } else {
    psi13 = (x - 1.0 + E) / (a * a);
  }
  Eigen::Matrix3d psi;
  psi << 1.0, T, psi13,  //
      0.0, 1.0, -std::expm1(-x) / a,  //
      0.0, 0.0, E;
  return psi;
}

Eigen::Matrix3d SingerProcessNoiseClosed(double T, double a, double q) {
  RK_CHECK(T >= 0.0 && a > 0.0, "Singer Q needs T >= 0 and a > 0");
  const double x = a * T;
  const double E = std::exp(-x);
  const double E2 = E * E;
  const double a2 = a * a, a3 = a2 * a, a4 = a3 * a, a5 = a4 * a;
  Eigen::Matrix3d Q;
  Q(0, 0) = q / (2 * a5) * (1 - E2 + 2 * x + 2 * x * x * x / 3 - 2 * x * x - 4 * x * E);
  Q(0, 1) = q / (2 * a4) * (E2 + 1 - 2 * E + 2 * x * E - 2 * x + x * x);
  Q(0, 2) = q / (2 * a3) * (1 - E2 - 2 * x * E);
  Q(1, 1) = q / (2 * a3) * (4 * E - 3 - E2 + 2 * x);
  Q(1, 2) = q / (2 * a2) * (E2 + 1 - 2 * E);
  Q(2, 2) = q / (2 * a) * (1 - E2);
  Q(1, 0) = Q(0, 1);
  Q(2, 0) = Q(0, 2);
  Q(2, 1) = Q(1, 2);
  return Q;
}

// Coefficients Σ_k 1/((k+p_i)! (n−k+p_j)!) / (n+p_i+p_j+1), computed once.
struct SeriesTable {
  double c[3][3][kSeriesTerms];
  SeriesTable() {
    const int p[3] = {2, 1, 0};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int n = 0; n < kSeriesTerms; ++n) {
          double s = 0.0;
          for (int k = 0; k <= n; ++k) s += 1.0 / (Factorial(k + p[i]) * Factorial(n - k + p[j]));
          c[i][j][n] = s / (n + p[i] + p[j] + 1);
        }
  }
};

Eigen::Matrix3d SingerProcessNoiseSeries(double T, double a, double q) {
  RK_CHECK(T >= 0.0 && a > 0.0, "Singer Q needs T >= 0 and a > 0");
  static const SeriesTable table;
  const double x = a * T;
  const int p[3] = {2, 1, 0};
  Eigen::Matrix3d Q;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      // Horner in (−x).
      double sum = 0.0;
      for (int n = kSeriesTerms - 1; n >= 0; --n) sum = sum * (-x) + table.c[i][j][n];
      Q(i, j) = Q(j, i) = q * std::pow(T, p[i] + p[j] + 1) * sum;
    }
  }
  return Q;
}

Eigen::Matrix3d SingerProcessNoise(double T, double a, double q) {
  if (a * T < kSingerSeriesLimit) return SingerProcessNoiseSeries(T, a, q);
  return SingerProcessNoiseClosed(T, a, q);
}

SingerStep::SingerStep(double T, double a)
    : T_s_(T), a_per_s_(a), series_(a * T < kSingerSeriesLimit), phi_(SingerTransition(T, a)) {
  if (!series_) return;
  RK_CHECK(T >= 0.0 && a > 0.0, "Singer Q needs T >= 0 and a > 0");
  static const SeriesTable table;
  const double x = a * T;
  const int p[3] = {2, 1, 0};
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      double sum = 0.0;
      for (int n = kSeriesTerms - 1; n >= 0; --n) sum = sum * (-x) + table.c[i][j][n];
      pow_(i, j) = std::pow(T, p[i] + p[j] + 1);
      sum_(i, j) = sum;
    }
  }
}

Eigen::Matrix3d SingerStep::ProcessNoise(double q) const {
  if (!series_) return SingerProcessNoiseClosed(T_s_, a_per_s_, q);
  Eigen::Matrix3d Q;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) Q(i, j) = Q(j, i) = q * pow_(i, j) * sum_(i, j);  // as SingerProcessNoiseSeries
  }
  return Q;
}

}  // namespace rk::track

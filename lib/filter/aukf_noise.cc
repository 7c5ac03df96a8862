// The AUKF's noise per column: moments of high-order differences, maximum likelihood of the innovations,
// the causal refit schedule (aukf_internal.h).
#include <algorithm>
#include <cmath>

#include "filter/aukf_internal.h"
#include "filter/singer_series.h"
#include "numeric/robust_stats.h"

namespace rk::filter {

bool EstimateColumnNoise(const Series& series, int column, double T, double* sigma, double* q, std::size_t rows) {
  using aukf_detail::Diff;
  const bool angle = series.is_angle[static_cast<std::size_t>(column)];
  const auto& z = series.values;
  const Eigen::Index N = static_cast<Eigen::Index>(std::min(rows, series.rows()));
  // v_h = mean (Δ³_h z)² for lags h = 1, 2, 4, 8; model v_h = a + b h⁵ (a = 20σ², b = 0.55 q T⁵),
  // fitted by least squares weighted by 1/v_h² (each v_h has a relative error ~ √(2/count)).
  constexpr int kLags[] = {1, 2, 4, 8};
  double v[4] = {0, 0, 0, 0}, cnt[4] = {0, 0, 0, 0};
  for (int li = 0; li < 4; ++li) {
    const Eigen::Index h = kLags[li];
    for (Eigen::Index i = 0; i + 3 * h < N; ++i) {
      const double a = z(i, column), b = z(i + h, column), c = z(i + 2 * h, column), d = z(i + 3 * h, column);
      if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d))) continue;
      const double d3 = Diff(d, c, angle) - 2.0 * Diff(c, b, angle) + Diff(b, a, angle);
      v[li] += d3 * d3;
      cnt[li] += 1;
    }
  }
  if (cnt[0] == 0) return false;
  double S00 = 0, S01 = 0, S11 = 0, R0 = 0, R1 = 0;
  for (int li = 0; li < 4; ++li) {
    if (cnt[li] < 3) continue;
    v[li] /= cnt[li];
    if (!(v[li] > 0)) continue;
    const double x = std::pow(static_cast<double>(kLags[li]), 5), w = cnt[li] / (v[li] * v[li]);
    S00 += w;
    S01 += w * x;
    S11 += w * x * x;
    R0 += w * v[li];
    R1 += w * x * v[li];
  }
  double a_fit = v[0] / cnt[0] > 0 ? v[0] : 0.0, b_fit = 0.0;
  const double det = S00 * S11 - S01 * S01;
  if (det > 0) {
    b_fit = std::max(0.0, (S00 * R1 - S01 * R0) / det);
    a_fit = std::max(0.0, v[0] - b_fit);  // keep the lag-1 moment exact: σ² from v₁ minus the jerk part
  }
  const double T5 = std::pow(T, 5);
  *q = b_fit / (aukf_detail::kQCoefficient * T5);
  *sigma = std::sqrt(a_fit / 20.0);
  return true;
}

bool CausalNoiseOptions::Check(std::string* why) const {
  if (first_fit < 4 || dense_until < first_fit || restart_until < 0) {
    *why = "causal noise schedule: need 4 <= first_fit <= dense_until and restart_until >= 0";
    return false;
  }
  return true;
}

bool CausalNoiseOptions::IsRefit(std::size_t rows) const {
  const std::size_t first = static_cast<std::size_t>(first_fit), dense = static_cast<std::size_t>(dense_until);
  if (rows < first) return false;
  if (rows < dense) return true;
  if (rows % dense != 0) return false;
  const std::size_t r = rows / dense;
  return (r & (r - 1)) == 0;  // dense · 2^j
}

std::string NoiseFitName(NoiseFit f) { return f == NoiseFit::kCausal ? "causal" : "file"; }

namespace aukf_detail {

double MedianInterval(const std::vector<double>& t, std::size_t rows) {
  std::vector<double> dt;
  dt.reserve(rows);
  for (std::size_t k = 1; k < rows; ++k) dt.push_back(t[k] - t[k - 1]);
  return numeric::UpperMedian(std::move(dt));
}

void FitNoise(const Series& series, std::size_t rows, const AukfOptions& options, bool est_sigma, bool est_q,
              bool causal, NoiseFitOut* out) {
  const int m = static_cast<int>(series.columns.size());
  const double T = MedianInterval(series.t_s, rows);
  out->interval_s = T;
  const Eigen::MatrixXd& Z = series.values;
  for (int c = 0; c < m; ++c) {
    const std::size_t cu = static_cast<std::size_t>(c);
    const double given_sigma = est_sigma ? 0.0 : options.meas_sigma[options.meas_sigma.size() == 1 ? 0 : cu];
    const double given_q = est_q ? 0.0 : options.q[options.q.size() == 1 ? 0 : cu];
    if (!est_sigma && !est_q) {
      out->sigma[cu] = given_sigma;
      out->q[cu] = given_q;
      out->known[cu] = true;
      continue;
    }
    double sig = 0, qq = 0;
    if (!EstimateColumnNoise(series, c, T, &sig, &qq, rows)) continue;
    if (options.noise_estimator == NoiseEstimator::kMaxLikelihood) {
      // σ: given, or the least motion-contaminated high-order difference estimate; q: maximum likelihood
      // of the innovations with that σ, started from the moments (noise_ml.h).
      double s_ml = given_sigma;
      if (est_sigma) {
        const std::vector<double> col(Z.col(c).data(), Z.col(c).data() + rows);
        // Orders up to 8 when each has ≥ 8 differences per order (72 rows): the smallest over many orders of
        // few differences each is biased low.
        const int max_order = std::clamp(static_cast<int>(rows / 9), 3, 8);
        const double s_diff = NoiseSigmaFromDifferences(col, series.is_angle[cu], 3, max_order);
        if (std::isfinite(s_diff) && s_diff > 0) sig = s_diff;
        s_ml = std::max(sig, 1e-12);
      }
      if (est_q) {
        const double q0 = std::max(qq, 1e-6 * s_ml * s_ml / std::pow(T, 5));
        NoiseMlFit fit;
        NoiseMlOptions ml = options.noise_ml;
        if (causal) ml.burn_in = std::min(ml.burn_in, kCausalBurnIn);
        const bool ok =
            FitWhiteJerkQMl(series.t_s.data(), Z.col(c).data(), rows, series.is_angle[cu], s_ml, q0, ml, &fit);
        out->ml[cu] = fit;
        out->ml_used[cu] = ok;
        // Causal fits start on few samples, where the likelihood of q is flat and an under-estimated q makes the
        // filter over-confident: they take the upper end of q's 95 % likelihood interval (→ q̂ as data grow).
        if (ok) qq = causal ? fit.q_upper : fit.q;
      }
    }
    double s = est_sigma ? sig : given_sigma;
    if (est_sigma) {
      // Noise-free or quantised data: keep R positive (1e-9 of the column's magnitude, at least 1e-12).
      double mag = 0;
      for (std::size_t k = 0; k < rows; ++k) {
        const double z = Z(static_cast<Eigen::Index>(k), c);
        if (std::isfinite(z)) mag = std::max(mag, std::abs(z));
      }
      s = std::max(s, std::max(1e-9 * mag, 1e-12));
    }
    out->sigma[cu] = s;
    // Floor: a filter bandwidth of about 1/(10 T) when the data look noise-only.
    out->q[cu] = est_q ? std::max(qq, 1e-6 * s * s / std::pow(T, 5)) : given_q;
    out->known[cu] = true;
  }
}

NoiseInUse InitialNoise(const Series& series, const AukfOptions& options, const AukfResult& res, bool causal,
                        NoiseFitOut* noise) {
  const std::size_t mu = series.columns.size();
  const double T = res.interval_s;
  noise->sigma.assign(mu, 0.0);
  noise->q.assign(mu, 0.0);
  noise->known.assign(mu, false);
  noise->ml.assign(mu, NoiseMlFit{});
  noise->ml_used.assign(mu, false);
  if (res.meas_sigma_estimated || res.q_estimated) {
    // A column that cannot be estimated even on the whole file is an error (no 4 consecutive values).
    for (int c = 0; c < static_cast<int>(mu); ++c) {
      double sg = 0, qq = 0;
      if (res.meas_sigma_estimated && !EstimateColumnNoise(series, c, T, &sg, &qq)) {
        throw DataError(series.source, 0, 0,
                        "column '" + series.columns[static_cast<std::size_t>(c)] +
                            "': cannot estimate the measurement noise (no 4 consecutive values); give --meas-sigma");
      }
    }
  }
  NoiseInUse use;
  use.sigma.resize(mu);
  use.q.resize(mu);
  use.T = T;
  if (causal) {
    // Provisional noise: the given values, or σ_p with q_p = σ_p²/T⁵ (the means do not depend on the scale).
    constexpr double kProvisionalSigma = 1e-3;  // file units or radians; only its ratio to q matters
    use.T = series.t_s[1] - series.t_s[0];
    for (std::size_t c = 0; c < mu; ++c) {
      use.sigma[c] = res.meas_sigma_estimated ? kProvisionalSigma : options.meas_sigma[options.meas_sigma.size() == 1 ? 0 : c];
      use.q[c] = res.q_estimated ? use.sigma[c] * use.sigma[c] / std::pow(use.T, 5) : options.q[options.q.size() == 1 ? 0 : c];
    }
  } else {
    FitNoise(series, series.rows(), options, res.meas_sigma_estimated, res.q_estimated, false, noise);
    use.sigma = noise->sigma;
    use.q = noise->q;
  }
  return use;
}

}  // namespace aukf_detail
}  // namespace rk::filter

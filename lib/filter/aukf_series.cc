#include "filter/aukf_series.h"

#include "filter/singer_series.h"  // output naming and angle range shared by the rk-smooth subcommands

#include <algorithm>
#include <cmath>
#include <limits>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::filter {

using ukf::MeasMat;
using ukf::MeasVec;
using ukf::SigmaMat;
using ukf::StateMat;
using ukf::StateVec;

bool AukfOptions::Check(std::string* why) const {
  if (!(lead > 0.0 && lead < 1.0)) {
    *why = "--lead must be in (0, 1)";
    return false;
  }
  if (!(kappa > -1.0 && std::isfinite(kappa))) {
    *why = "--kappa must be > -1 (and n + kappa > 0)";
    return false;
  }
  for (double s : meas_sigma) {
    if (!(s > 0.0 && std::isfinite(s))) {
      *why = "--meas-sigma values must be > 0";
      return false;
    }
  }
  for (double v : q) {
    if (!(v >= 0.0 && std::isfinite(v))) {
      *why = "--q values must be >= 0";
      return false;
    }
  }
  if (meas_sigma.size() > static_cast<std::size_t>(ukf::kMaxColumns) ||
      q.size() > static_cast<std::size_t>(ukf::kMaxColumns)) {
    *why = "--meas-sigma/--q: at most 12 values";
    return false;
  }
  return adapt.Check(why);
}

bool ParseNoiseEstimator(const std::string& s, NoiseEstimator* e) {
  if (s == "ml") {
    *e = NoiseEstimator::kMaxLikelihood;
  } else if (s == "moments") {
    *e = NoiseEstimator::kDifferences;
  } else {
    return false;
  }
  return true;
}

const char* NoiseEstimatorName(NoiseEstimator e) { return e == NoiseEstimator::kMaxLikelihood ? "ml" : "moments"; }

Eigen::Matrix3d WhiteJerkQ(double t, double q) {
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
  Eigen::Matrix3d Q;
  Q << t5 / 20, t4 / 8, t3 / 6, t4 / 8, t3 / 3, t2 / 2, t3 / 6, t2 / 2, t;
  return q * Q;
}

ukf::StateMat AukfResult::FilterCovariance(std::size_t node) const {
  const std::size_t packed = static_cast<std::size_t>(n * (n + 1) / 2);
  RK_CHECK((node + 1) * packed <= cov_filter.size(), "covariance not kept");
  StateMat P(n, n);
  const double* p = cov_filter.data() + node * packed;
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      P(i, j) = *p;
      P(j, i) = *p;
      ++p;
    }
  }
  return P;
}

namespace {

constexpr double kQCoefficient = 0.55;  // ∫ B₂(u)² du of the quadratic B-spline: Δ³ of triple-integrated noise

double Diff(double a, double b, bool angle) { return angle ? geo::AngleDiff(a, b) : a - b; }

void Pack(const StateMat& P, std::vector<double>* out) {
  const Eigen::Index n = P.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i; j < n; ++j) out->push_back(P(i, j));
  }
}

void Unpack(const double* p, int n, StateMat* P) {
  P->resize(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      (*P)(i, j) = *p;
      (*P)(j, i) = *p;
      ++p;
    }
  }
}

// Φ(τ) applied in place to every column of X (block-wise, no 18×18 product).
void PropagateSigma(int m, double tau, SigmaMat* X) {
  const double h = 0.5 * tau * tau;
  for (int c = 0; c < m; ++c) {
    const int r = 3 * c;
    X->row(r) += tau * X->row(r + 1) + h * X->row(r + 2);
    X->row(r + 1) += tau * X->row(r + 2);
  }
}

// The time-update machinery shared by the forward pass and the smoother.
struct Model {
  int m = 0, n = 0;
  double kappa = 1.0;
  ukf::SigmaWeights w;
  ukf::AngleRows angles;
  std::vector<double> q;      // per column
  StateVec scale;             // per state: σ, σ/T, σ/T² (repair scale)
  std::vector<bool> is_angle; // per column
  bool block_diagonal = false;  // P block diagonal per column (no adaptation): PredictBlocks
  double p_floor = 1e-12;

  // Process noise of a sub-step of length s: the model's white-jerk Q, or Q_rate·s when adapted.
  void AddQ(double s, const StateMat* Q_rate, StateMat* P) const {
    if (Q_rate) {
      *P += s * *Q_rate;
      return;
    }
    for (int c = 0; c < m; ++c) P->block<3, 3>(3 * c, 3 * c) += WhiteJerkQ(s, q[static_cast<std::size_t>(c)]);
  }

  // Sigma points of (x, P); repairs P in place when it has no Cholesky factor.
  void Sigma(const StateVec& x, StateMat* P, SigmaMat* X, std::size_t* repairs) const {
    if (ukf::SigmaPoints(x, *P, kappa, X)) return;
    ukf::RepairSpd(P, scale, p_floor);
    ++*repairs;
    if (!ukf::SigmaPoints(x, *P, kappa, X)) {
      throw ProcessingError("covariance could not be repaired to positive definite (non-finite values?)");
    }
  }

  // (x, P) at node j → predicted (x⁻, P⁻) over s. Optionally returns the smoother's cross-covariance
  // C = Σ W (X − x)(ΦX − x⁻)ᵀ. With block_diagonal, P is block diagonal (one 3×3 block per column) and the
  // unscented transform runs per column block (PredictBlocks).
  void Predict(const StateVec& x, StateMat* P, double s, const StateMat* Q_rate, StateVec* x_pred, StateMat* P_pred,
               std::size_t* repairs, StateMat* C = nullptr) const {
    if (block_diagonal && !Q_rate && PredictBlocks(x, *P, s, x_pred, P_pred, C)) return;
    SigmaMat X;
    Sigma(x, P, &X, repairs);
    SigmaMat D0;
    if (C) ukf::SigmaResiduals(X, x, angles, &D0);
    PropagateSigma(m, s, &X);
    *x_pred = ukf::SigmaMean(X, w, angles);
    SigmaMat D;
    ukf::SigmaResiduals(X, *x_pred, angles, &D);
    *P_pred = ukf::SigmaCovariance(D, w);
    AddQ(s, Q_rate, P_pred);
    if (C) *C = ukf::SigmaCrossCovariance(D0, D, w);
  }

  // The same transform per column block: with no adaptation the columns are independent (Φ, Q and R are
  // block diagonal and H picks one state per column, so P stays block diagonal), and the unscented
  // transform of the joint state factors into one 3-state transform per column (n = 3, 7 points, weights
  // κ/(3+κ) and 1/(2(3+κ))). For this linear Φ both are exact, so the results agree to rounding (golden
  // test); the cost falls from O(n³) with 2n+1 = 37 points to 6 small blocks. Returns false (nothing
  // written) when a block has no Cholesky factor: the caller then takes the joint path, which repairs P.
  bool PredictBlocks(const StateVec& x, const StateMat& P, double s, StateVec* x_pred, StateMat* P_pred,
                     StateMat* C) const {
    const double k3 = 3.0 + kappa;
    const double w0 = kappa / k3, wi = 1.0 / (2.0 * k3);
    x_pred->resize(n);
    P_pred->setZero(n, n);
    if (C) C->setZero(n, n);
    Eigen::Matrix3d F;
    F << 1, s, 0.5 * s * s, 0, 1, s, 0, 0, 1;
    for (int c = 0; c < m; ++c) {
      const int r = 3 * c;
      const Eigen::Matrix3d Pc = P.block<3, 3>(r, r);
      const Eigen::LLT<Eigen::Matrix3d> llt(k3 * Pc);
      if (llt.info() != Eigen::Success) return false;
      const Eigen::Matrix3d L = llt.matrixL();
      const Eigen::Vector3d xc = x.segment<3>(r);
      Eigen::Matrix<double, 3, 7> X;
      X.col(0) = xc;
      for (int i = 0; i < 3; ++i) {
        X.col(1 + i) = xc + L.col(i);
        X.col(4 + i) = xc - L.col(i);
      }
      const Eigen::Matrix<double, 3, 7> Y = F * X;
      Eigen::Vector3d mean = w0 * Y.col(0) + wi * (Y.rightCols<6>().rowwise().sum());
      const bool angle = is_angle[static_cast<std::size_t>(c)];
      if (angle) {  // wrap-safe mean of the angle row, as ukf::SigmaMean
        double acc = 0.0;
        for (int i = 0; i < 7; ++i) acc += (i == 0 ? w0 : wi) * geo::WrapPi(Y(0, i) - Y(0, 0));
        mean(0) = geo::WrapPi(Y(0, 0) + acc);
      }
      Eigen::Matrix<double, 3, 7> D = Y.colwise() - mean;
      if (angle) {
        for (int i = 0; i < 7; ++i) D(0, i) = geo::WrapPi(D(0, i));
      }
      Eigen::Matrix3d Pp = w0 * D.col(0) * D.col(0).transpose() + wi * (D.rightCols<6>() * D.rightCols<6>().transpose());
      Pp += WhiteJerkQ(s, q[static_cast<std::size_t>(c)]);
      P_pred->block<3, 3>(r, r) = 0.5 * (Pp + Pp.transpose());
      x_pred->segment<3>(r) = mean;
      if (C) {
        Eigen::Matrix<double, 3, 7> D0 = X.colwise() - xc;  // X_0 = x: no wrap needed (residuals of ±L)
        C->block<3, 3>(r, r) = w0 * D0.col(0) * D.col(0).transpose() +
                               wi * (D0.rightCols<6>() * D.rightCols<6>().transpose());
      }
    }
    return true;
  }
};

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

bool EstimateColumnNoise(const Series& series, int column, double T, double* sigma, double* q) {
  const bool angle = series.is_angle[static_cast<std::size_t>(column)];
  const auto& z = series.values;
  const Eigen::Index N = z.rows();
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
  *q = b_fit / (kQCoefficient * T5);
  *sigma = std::sqrt(a_fit / 20.0);
  return true;
}

AukfResult RunAukf(const Series& series, const AukfOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  const int m = static_cast<int>(series.columns.size());
  if (m < 1 || m > ukf::kMaxColumns) throw UsageError("--columns: 1 to 12 columns, got " + std::to_string(m));
  if (options.meas_sigma.size() > 1 && options.meas_sigma.size() != static_cast<std::size_t>(m)) {
    throw UsageError("--meas-sigma: give one value or one per column (" + std::to_string(m) + ")");
  }
  if (options.q.size() > 1 && options.q.size() != static_cast<std::size_t>(m)) {
    throw UsageError("--q: give one value or one per column (" + std::to_string(m) + ")");
  }
  const std::size_t N = series.rows();
  if (N < 3) throw DataError(series.source, 0, 0, "needs at least 3 samples, has " + std::to_string(N));
  const int n = 3 * m;

  AukfResult res;
  res.m = m;
  res.n = n;
  res.samples = N;
  {
    std::vector<double> dt;
    for (std::size_t k = 1; k < N; ++k) dt.push_back(series.t_s[k] - series.t_s[k - 1]);
    res.interval_s = Median(dt);
  }
  const double T = res.interval_s;
  const Eigen::MatrixXd& Z = series.values;

  // Noise per column: given, or estimated from the data.
  res.meas_sigma.assign(static_cast<std::size_t>(m), 0.0);
  res.q.assign(static_cast<std::size_t>(m), 0.0);
  res.meas_sigma_estimated = options.meas_sigma.empty();
  res.q_estimated = options.q.empty();
  if (options.noise_estimator == NoiseEstimator::kMaxLikelihood && (res.meas_sigma_estimated || res.q_estimated)) {
    res.noise_fit.assign(static_cast<std::size_t>(m), NoiseMlFit{});
    res.noise_fit_used.assign(static_cast<std::size_t>(m), false);
  }
  for (int c = 0; c < m; ++c) {
    const std::size_t cu = static_cast<std::size_t>(c);
    double sig = 0, qq = 0;
    bool have = (res.meas_sigma_estimated || res.q_estimated) && EstimateColumnNoise(series, c, T, &sig, &qq);
    if (have && options.noise_estimator == NoiseEstimator::kMaxLikelihood) {
      // σ: given, or the least motion-contaminated high-order difference estimate; q: maximum likelihood
      // of the innovations with that σ, started from the moments (noise_ml.h).
      double s_ml = res.meas_sigma_estimated ? 0.0 : options.meas_sigma[options.meas_sigma.size() == 1 ? 0 : cu];
      if (res.meas_sigma_estimated) {
        const std::vector<double> col(series.values.col(c).data(), series.values.col(c).data() + N);
        const double s_diff = NoiseSigmaFromDifferences(col, series.is_angle[cu]);
        if (std::isfinite(s_diff) && s_diff > 0) sig = s_diff;
        s_ml = std::max(sig, 1e-12);
      }
      if (res.q_estimated) {
        const double q0 = std::max(qq, 1e-6 * s_ml * s_ml / std::pow(T, 5));
        NoiseMlFit fit;
        const bool ok = FitWhiteJerkQMl(series.t_s.data(), series.values.col(c).data(), N, series.is_angle[cu], s_ml,
                                        q0, options.noise_ml, &fit);
        res.noise_fit[cu] = fit;
        res.noise_fit_used[cu] = ok;
        if (ok) qq = fit.q;
      }
    }
    if (res.meas_sigma_estimated && !have) {
      throw DataError(series.source, 0, 0,
                      "column '" + series.columns[cu] +
                          "': cannot estimate the measurement noise (no 4 consecutive values); give --meas-sigma");
    }
    res.meas_sigma[cu] = res.meas_sigma_estimated ? sig : options.meas_sigma[options.meas_sigma.size() == 1 ? 0 : cu];
    if (res.meas_sigma_estimated) {
      // Noise-free or quantised data: keep R positive (1e-9 of the column's magnitude, at least 1e-12).
      double mag = 0;
      for (std::size_t k = 0; k < N; ++k) {
        if (std::isfinite(Z(static_cast<Eigen::Index>(k), c))) mag = std::max(mag, std::abs(Z(static_cast<Eigen::Index>(k), c)));
      }
      res.meas_sigma[cu] = std::max(res.meas_sigma[cu], std::max(1e-9 * mag, 1e-12));
    }
    if (res.q_estimated) {
      // Floor: a filter bandwidth of about 1/(10 T) when the data look noise-only.
      const double floor = 1e-6 * res.meas_sigma[cu] * res.meas_sigma[cu] / std::pow(T, 5);
      res.q[cu] = std::max(have ? qq : 0.0, floor);
    } else {
      res.q[cu] = options.q[options.q.size() == 1 ? 0 : cu];
    }
  }

  Model model;
  model.m = m;
  model.n = n;
  model.kappa = options.kappa;
  if (!(n + options.kappa > 0)) throw UsageError("--kappa: n + kappa must be > 0");
  model.w = ukf::MakeWeights(n, options.kappa);
  model.q = res.q;
  model.is_angle = series.is_angle;
  model.block_diagonal = options.adapt.mode == AdaptMode::kNone && !options.joint_transform;
  model.scale.resize(n);
  for (int c = 0; c < m; ++c) {
    const double s = res.meas_sigma[static_cast<std::size_t>(c)];
    model.scale(3 * c) = s;
    model.scale(3 * c + 1) = s / T;
    model.scale(3 * c + 2) = s / (T * T);
    if (series.is_angle[static_cast<std::size_t>(c)]) model.angles.Add(3 * c);
  }

  // Initial state from the first two values of each column.
  StateVec x = StateVec::Zero(n);
  StateMat P = StateMat::Zero(n, n);
  for (int c = 0; c < m; ++c) {
    const std::size_t cu = static_cast<std::size_t>(c);
    const bool angle = series.is_angle[cu];
    std::vector<std::size_t> first;
    for (std::size_t k = 0; k < N && first.size() < 3; ++k) {
      if (std::isfinite(Z(static_cast<Eigen::Index>(k), c))) first.push_back(k);
    }
    if (first.size() < 2) {
      throw DataError(series.source, 0, 0, "column '" + series.columns[cu] + "' has fewer than 2 values");
    }
    const auto zi = Z(static_cast<Eigen::Index>(first[0]), c), zj = Z(static_cast<Eigen::Index>(first[1]), c);
    const double dt = series.t_s[first[1]] - series.t_s[first[0]];
    const double v = Diff(zj, zi, angle) / dt;
    double a3 = 0;
    if (first.size() == 3) {
      const double dt2 = series.t_s[first[2]] - series.t_s[first[1]];
      const double v2 = Diff(Z(static_cast<Eigen::Index>(first[2]), c), zj, angle) / dt2;
      a3 = (v2 - v) / (0.5 * (dt + dt2));
    }
    const double s2 = res.meas_sigma[cu] * res.meas_sigma[cu];
    const int r = 3 * c;
    x(r) = zi - v * (series.t_s[first[0]] - series.t_s[0]);
    if (angle) x(r) = geo::WrapPi(x(r));
    x(r + 1) = v;
    x(r + 2) = 0;
    P(r, r) = s2;
    P(r, r + 1) = P(r + 1, r) = -s2 / dt;
    P(r + 1, r + 1) = 2 * s2 / (dt * dt);
    P(r + 2, r + 2) = 600 * s2 / (dt * dt * dt * dt) + a3 * a3;
  }

  MeasMat R0 = MeasMat::Zero(m, m);
  for (int c = 0; c < m; ++c) R0(c, c) = res.meas_sigma[static_cast<std::size_t>(c)] * res.meas_sigma[static_cast<std::size_t>(c)];
  MeasMat R = R0;
  MeasVec r_scale(m);
  for (int c = 0; c < m; ++c) r_scale(c) = res.meas_sigma[static_cast<std::size_t>(c)];
  InnovationCovariance innov;
  innov.Reset(m, options.adapt);
  StateMat Q_rate;  // adapted process noise per unit time
  bool q_adapted = false;

  const std::size_t J = 2 * N - 1;
  const bool keep_cov = options.keep_covariance || options.smooth;
  const std::size_t packed = static_cast<std::size_t>(n * (n + 1) / 2);
  if (keep_cov) res.cov_filter.reserve(J * packed);
  // Adapted Q per interval for the smoother (only when Q is adapted and smoothing).
  const bool store_q = options.smooth && AdaptsQ(options.adapt.mode);
  std::vector<double> q_store;            // packed Q_rate per sample interval
  std::vector<char> q_store_used;         // 1 if the interval used an adapted Q
  res.t_s.reserve(J);
  res.x_filter.resize(n, static_cast<Eigen::Index>(J));
  res.sd_filter.resize(n, static_cast<Eigen::Index>(J));

  auto store = [&](double t, bool mid, int sample, AukfStatus st, const StateVec& xs, const StateMat& Ps) {
    const Eigen::Index j = static_cast<Eigen::Index>(res.t_s.size());
    res.t_s.push_back(t);
    res.is_mid.push_back(mid);
    res.sample.push_back(sample);
    res.status.push_back(st);
    res.x_filter.col(j) = xs;
    res.sd_filter.col(j) = Ps.diagonal().cwiseMax(0.0).cwiseSqrt();
    if (keep_cov) Pack(Ps, &res.cov_filter);
  };
  auto row_status = [&](std::size_t k) {
    for (int c = 0; c < m; ++c) {
      if (std::isfinite(Z(static_cast<Eigen::Index>(k), c))) return AukfStatus::kOk;
    }
    return AukfStatus::kPredicted;
  };

  StateVec x_mid, x_pred;
  StateMat P_mid, P_pred;
  const AukfStatus st0 = row_status(0);
  for (std::size_t k = 1; k < N; ++k) {
    const double tau = series.t_s[k] - series.t_s[k - 1];
    const double s1 = options.lead * tau, s2 = tau - s1;
    const StateMat* Qr = q_adapted ? &Q_rate : nullptr;
    if (store_q) {
      q_store_used.push_back(q_adapted ? 1 : 0);
      if (q_adapted) Pack(Q_rate, &q_store);
    }
    // Half step 1 (may repair P of node k−1 in place; the node is stored after that).
    model.Predict(x, &P, s1, Qr, &x_mid, &P_mid, &res.p_repairs);
    if (k == 1) store(series.t_s[0], false, 0, st0, x, P);
    else store(series.t_s[k - 1], false, static_cast<int>(k - 1), row_status(k - 1), x, P);
    // Half step 2.
    model.Predict(x_mid, &P_mid, s2, Qr, &x_pred, &P_pred, &res.p_repairs);
    store(series.t_s[k - 1] + s1, true, static_cast<int>(k - 1), AukfStatus::kOk, x_mid, P_mid);

    // Measurement update with the measured columns.
    int avail[ukf::kMaxColumns];
    int ma = 0;
    for (int c = 0; c < m; ++c) {
      if (std::isfinite(Z(static_cast<Eigen::Index>(k), c))) avail[ma++] = c;
    }
    x = x_pred;
    P = P_pred;
    if (ma == 0) {
      ++res.skipped_updates;
      continue;
    }
    ++res.updates;
    if (ma < m) ++res.partial_updates;
    MeasMat S(ma, ma);
    ukf::GainMat Pxy(n, ma);
    MeasVec d(ma);
    for (int a = 0; a < ma; ++a) {
      const int ca = avail[a], ra = 3 * ca;
      d(a) = Diff(Z(static_cast<Eigen::Index>(k), ca), x_pred(ra), series.is_angle[static_cast<std::size_t>(ca)]);
      Pxy.col(a) = P_pred.col(ra);
      for (int b = 0; b < ma; ++b) S(a, b) = P_pred(ra, 3 * avail[b]) + R(ca, avail[b]);
    }
    ukf::Symmetrise(&S);
    Eigen::LLT<MeasMat> llt(S);
    if (llt.info() != Eigen::Success) {
      MeasVec sc(ma);
      for (int a = 0; a < ma; ++a) sc(a) = r_scale(avail[a]);
      ukf::RepairSpd(&S, sc, options.adapt.r_floor);
      ++res.p_repairs;
      llt.compute(S);
      if (llt.info() != Eigen::Success) throw ProcessingError("innovation covariance is not positive definite");
    }
    // K = Pxy S⁻¹  ⇔  Kᵀ = S⁻¹ Pxyᵀ
    ukf::GainMat K = llt.solve(Pxy.transpose()).transpose();
    res.nis_sum += d.dot(llt.solve(d));
    res.nis_dof += static_cast<std::size_t>(ma);
    x.noalias() += K * d;
    ukf::WrapAngles(model.angles, &x);
    P.noalias() -= K * S * K.transpose();
    ukf::Symmetrise(&P);

    // Adaptation (rows with every column only).
    if (options.adapt.mode != AdaptMode::kNone) {
      if (ma < m) {
        ++res.adapt_skipped;
      } else {
        MeasMat HPH(m, m);
        for (int a = 0; a < m; ++a) {
          for (int b = 0; b < m; ++b) HPH(a, b) = P_pred(3 * a, 3 * b);
        }
        innov.Add(d, HPH);
        if (innov.Ready()) {
          ++res.adapt_steps;
          if (AdaptsR(options.adapt.mode)) {
            MeasMat Rn(m, m);
            for (int a = 0; a < m; ++a) {
              for (int b = 0; b < m; ++b) Rn(a, b) = innov.C()(a, b) - innov.HPH()(a, b);
            }
            if (ukf::RepairSpd(&Rn, r_scale, options.adapt.r_floor, options.adapt.r_ceiling)) ++res.r_repairs;
            R = Rn;
          }
          if (AdaptsQ(options.adapt.mode)) {
            StateMat Qn = K * innov.C() * K.transpose();
            if (ukf::RepairSpd(&Qn, model.scale, options.adapt.q_floor, options.adapt.q_ceiling)) ++res.q_repairs;
            Q_rate = Qn / tau;
            q_adapted = true;
          }
        }
      }
    }
  }
  store(series.t_s[N - 1], false, static_cast<int>(N - 1), row_status(N - 1), x, P);

  res.final_R = R;
  res.final_Q_adapted = q_adapted;
  if (q_adapted) {
    res.final_Q = Q_rate * T;
  } else {
    res.final_Q = StateMat::Zero(n, n);
    model.AddQ(T, nullptr, &res.final_Q);
  }

  if (options.smooth) {
    res.x_smooth.resize(n, static_cast<Eigen::Index>(J));
    res.sd_smooth.resize(n, static_cast<Eigen::Index>(J));
    StateVec xs = res.x_filter.col(static_cast<Eigen::Index>(J - 1));
    StateMat Ps;
    Unpack(res.cov_filter.data() + (J - 1) * packed, n, &Ps);
    res.x_smooth.col(static_cast<Eigen::Index>(J - 1)) = xs;
    res.sd_smooth.col(static_cast<Eigen::Index>(J - 1)) = Ps.diagonal().cwiseMax(0.0).cwiseSqrt();
    std::size_t smoother_repairs = 0;
    std::vector<std::size_t> q_offset;  // packed offset of each interval's adapted Q
    if (store_q) {
      std::size_t off = 0;
      for (char u : q_store_used) {
        q_offset.push_back(off);
        if (u) off += packed;
      }
    }
    StateMat Qr_k;
    for (std::size_t jj = J - 1; jj-- > 0;) {
      const StateVec xf = res.x_filter.col(static_cast<Eigen::Index>(jj));
      StateMat Pf;
      Unpack(res.cov_filter.data() + jj * packed, n, &Pf);
      const double s = res.t_s[jj + 1] - res.t_s[jj];
      const std::size_t interval = jj / 2;  // nodes 2i (sample i) and 2i+1 (mid) lie in interval i → i+1
      const StateMat* Qr = nullptr;
      if (store_q && q_store_used[interval]) {
        Unpack(q_store.data() + q_offset[interval], n, &Qr_k);
        Qr = &Qr_k;
      }
      StateVec xp;
      StateMat Pp;
      StateMat C;
      model.Predict(xf, &Pf, s, Qr, &xp, &Pp, &smoother_repairs, &C);
      Eigen::LLT<StateMat> llt(Pp);
      if (llt.info() != Eigen::Success) {
        ukf::RepairSpd(&Pp, model.scale, model.p_floor);
        ++smoother_repairs;
        llt.compute(Pp);
      }
      const StateMat G = llt.solve(C.transpose()).transpose();
      StateVec diff = xs - xp;
      ukf::WrapAngles(model.angles, &diff);
      StateVec xs_new = xf + G * diff;
      ukf::WrapAngles(model.angles, &xs_new);
      StateMat Ps_new = Pf + G * (Ps - Pp) * G.transpose();
      ukf::Symmetrise(&Ps_new);
      xs = xs_new;
      Ps = Ps_new;
      res.x_smooth.col(static_cast<Eigen::Index>(jj)) = xs;
      res.sd_smooth.col(static_cast<Eigen::Index>(jj)) = Ps.diagonal().cwiseMax(0.0).cwiseSqrt();
    }
    res.p_repairs += smoother_repairs;
    if (!options.keep_covariance) {
      res.cov_filter.clear();
      res.cov_filter.shrink_to_fit();
    }
  }
  return res;
}

std::string RateColumnName(const std::string& column) {
  const auto u = column.rfind('_');
  if (u == std::string::npos || u == 0 || u + 1 == column.size()) return column + "_rate_per_s";
  return column.substr(0, u) + "_rate_" + column.substr(u + 1) + "_s";
}

std::string AccelColumnName(const std::string& column) {
  const auto u = column.rfind('_');
  if (u == std::string::npos || u == 0 || u + 1 == column.size()) return column + "_accel_per_s2";
  return column.substr(0, u) + "_accel_" + column.substr(u + 1) + "_s2";
}

io::CsvWriter AukfCsv(const Series& series, const AukfResult& result, const AukfOutputOptions& out) {
  const int m = result.m;
  std::vector<std::string> header = {"t_s", "kind"};
  for (const auto& c : series.columns) header.push_back(c);
  header.push_back("status");
  if (out.derivatives) {
    for (const auto& c : series.columns) {
      header.push_back(RateColumnName(c));
      header.push_back(AccelColumnName(c));
    }
  }
  if (out.sigmas) {
    for (const auto& c : series.columns) header.push_back(SingerSigmaColumnName(c));
  }
  // Output range of each angle column, shared with `singer` (AngleColumnIs360): [0, 360) for
  // azimuth/yaw-like names or when some input value exceeds 180°, else (−180, 180].
  std::vector<bool> wrap360(static_cast<std::size_t>(m), false);
  for (int c = 0; c < m; ++c) {
    if (!series.is_angle[static_cast<std::size_t>(c)]) continue;
    std::vector<double> v(series.values.col(c).data(), series.values.col(c).data() + series.values.rows());
    wrap360[static_cast<std::size_t>(c)] = AngleColumnIs360(series.columns[static_cast<std::size_t>(c)], v);
  }
  io::CsvWriter w(header);
  auto write_row = [&](std::size_t j, const char* kind, const Eigen::MatrixXd& X, const Eigen::MatrixXd& SD) {
    const Eigen::Index jc = static_cast<Eigen::Index>(j);
    w.Add(result.t_s[j], out.decimals).Add(kind);
    for (int c = 0; c < m; ++c) {
      double v = X(3 * c, jc);
      if (series.is_angle[static_cast<std::size_t>(c)]) {
        v = geo::RadToDeg(v);
        v = wrap360[static_cast<std::size_t>(c)] ? geo::WrapDeg360(v) : geo::WrapDeg180(v);
      }
      w.Add(v, out.decimals);
    }
    w.Add(result.status[j] == AukfStatus::kOk ? "ok" : "predicted");
    if (out.derivatives) {
      for (int c = 0; c < m; ++c) {
        const double f = series.is_angle[static_cast<std::size_t>(c)] ? geo::RadToDeg(1.0) : 1.0;
        w.Add(f * X(3 * c + 1, jc), out.decimals).Add(f * X(3 * c + 2, jc), out.decimals);
      }
    }
    if (out.sigmas) {
      for (int c = 0; c < m; ++c) {
        const double f = series.is_angle[static_cast<std::size_t>(c)] ? geo::RadToDeg(1.0) : 1.0;
        w.Add(f * SD(3 * c, jc), out.decimals);
      }
    }
    w.EndRow();
  };
  const bool smoothed = result.x_smooth.cols() == static_cast<Eigen::Index>(result.t_s.size());
  for (std::size_t j = 0; j < result.t_s.size(); ++j) {
    write_row(j, result.is_mid[j] ? "prediction" : "estimate", result.x_filter, result.sd_filter);
    if (smoothed) write_row(j, "smoothed", result.x_smooth, result.sd_smooth);
  }
  return w;
}

io::Json AukfReportJson(const Series& series, const AukfOptions& options, const AukfResult& result) {
  auto matrix = [](const auto& A) {
    io::Json rows = io::Json::array();
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      io::Json row = io::Json::array();
      for (Eigen::Index j = 0; j < A.cols(); ++j) row.push_back(A(i, j));
      rows.push_back(row);
    }
    return rows;
  };
  io::Json cols = io::Json::array();
  for (int c = 0; c < result.m; ++c) {
    const std::size_t cu = static_cast<std::size_t>(c);
    const bool angle = series.is_angle[cu];
    const double f = angle ? geo::RadToDeg(1.0) : 1.0;
    io::Json col = {{"name", series.columns[cu]},
                    {"angle", angle},
                    {"meas_sigma", f * result.meas_sigma[cu]},
                    {"q", f * f * result.q[cu]},
                    {"unit", angle ? "deg" : "file unit"}};
    if (cu < result.noise_fit.size() && result.noise_fit[cu].evaluations > 0) {
      const NoiseMlFit& fit = result.noise_fit[cu];
      col["noise_ml"] = {{"used", static_cast<bool>(result.noise_fit_used[cu])},
                         {"nll_per_innovation", fit.nll},
                         {"innovations", fit.innovations},
                         {"evaluations", fit.evaluations},
                         {"on_search_bound", fit.on_bound}};
    }
    cols.push_back(col);
  }
  io::Json j;
  j["options"] = {{"lead", options.lead},
                  {"kappa", options.kappa},
                  {"adapt", AdaptModeName(options.adapt.mode)},
                  {"memory", options.adapt.memory == AdaptMemory::kWindow ? "window" : "fading"},
                  {"window", options.adapt.window},
                  {"fading", options.adapt.fading},
                  {"r_floor", options.adapt.r_floor},
                  {"q_floor", options.adapt.q_floor},
                  {"r_ceiling", options.adapt.r_ceiling},
                  {"q_ceiling", options.adapt.q_ceiling},
                  {"smooth", options.smooth},
                  {"meas_sigma_estimated", result.meas_sigma_estimated},
                  {"q_estimated", result.q_estimated},
                  {"noise_estimate", NoiseEstimatorName(options.noise_estimator)},
                  {"process_model", "white jerk, Q(tau) = q [[tau^5/20, tau^4/8, tau^3/6], [tau^4/8, tau^3/3, "
                                    "tau^2/2], [tau^3/6, tau^2/2, tau]] per column"},
                  {"columns", cols}};
  j["counts"] = {{"samples", result.samples},
                 {"nodes", result.t_s.size()},
                 {"updates", result.updates},
                 {"partial_updates", result.partial_updates},
                 {"skipped_updates", result.skipped_updates},
                 {"adapt_steps", result.adapt_steps},
                 {"adapt_skipped_partial_rows", result.adapt_skipped},
                 {"repairs_q", result.q_repairs},
                 {"repairs_r", result.r_repairs},
                 {"repairs_p", result.p_repairs}};
  j["interval_s"] = result.interval_s;
  j["nis_mean"] = result.NisMean();
  j["nis_mean_per_dof"] = result.nis_dof ? result.nis_sum / static_cast<double>(result.nis_dof) : 0.0;
  j["final_R"] = matrix(result.final_R);
  j["final_Q"] = matrix(result.final_Q);
  j["final_Q_adapted"] = result.final_Q_adapted;
  j["final_noise_units"] =
      "SI and radians; state order [p, p', p''] per column in --columns order; final_Q is the process noise of "
      "one median interval interval_s";
  return j;
}

}  // namespace rk::filter

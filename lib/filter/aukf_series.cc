#include "filter/aukf_series.h"

#include "filter/singer_series.h"  // output naming and angle range shared by the rk-smooth subcommands

#include <algorithm>
#include <cmath>
#include <limits>

#include "geo/angles.h"
#include "io/error.h"
#include "numeric/robust_stats.h"

namespace rk::filter {

using ukf::MeasMat;
using ukf::MeasVec;
using ukf::SigmaMat;
using ukf::StateMat;
using ukf::StateVec;

const io::OptionTable<AukfOptions>& AukfOptions::Table() {
  using O = AukfOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--lead", &O::lead, "", io::Bounds::Open(0.0, 1.0),
                "Fraction of each interval at which the prediction is output, in (0, 1)")
          .Flag("--smooth", &O::smooth, "Add 'smoothed' rows (unscented RTS) at sample and mid-times")
          .Sub(&O::adapt, AdaptiveNoiseOptions::Table())
          .Choice("--noise-estimate", &O::noise_estimator,
                  {NoiseEstimator::kMaxLikelihood, NoiseEstimator::kDifferences}, NoiseEstimatorName,
                  "How --meas-sigma/--q not given are estimated per column: ml (sigma from high-order differences, "
                  "q by maximum likelihood of the innovations) or moments (third differences at lags 1-8 only)")
          .Choice("--noise-fit", &O::noise_fit, {NoiseFit::kCausal, NoiseFit::kFile}, NoiseFitName,
                  "Data the fitted noise of the estimate/prediction rows may use: causal (the rows up to each "
                  "time, refitted as the file goes: no row depends on a later sample) or file (the whole file, "
                  "the old default: earlier rows then depend on later samples)")
          .Choice("--smooth-noise-fit", &O::smooth_noise_fit, {NoiseFit::kCausal, NoiseFit::kFile}, NoiseFitName,
                  "Noise fit behind the 'smoothed' rows: file (an extra forward pass with the whole-file fit) or "
                  "causal (smooth the causal pass)")
          // n + kappa > 0 for every n >= 1 columns' 3n states.
          .Real("--kappa", &O::kappa, "", io::Bounds{.lo = -1.0, .lo_open = true, .finite = true},
                "Sigma-point parameter kappa: W0 = kappa/(n+kappa)");
  return table;
}

const io::OptionTable<AukfOutputOptions>& AukfOutputOptions::Table() {
  static const io::OptionTable<AukfOutputOptions> table =
      io::OptionTable<AukfOutputOptions>()
          .Flag("--derivatives", &AukfOutputOptions::derivatives,
                "Add <base>_rate_<unit>_s and <base>_accel_<unit>_s2 columns (e.g. yaw_rate_deg_s)")
          .Flag("--sigmas", &AukfOutputOptions::sigmas,
                "Add <base>_sigma_<unit> columns (1-sigma of each value, file units)");
  return table;
}

bool AukfOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
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
  return adapt.Check(why) && causal.Check(why);
}

std::string NoiseEstimatorName(NoiseEstimator e) { return e == NoiseEstimator::kMaxLikelihood ? "ml" : "moments"; }

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

}  // namespace

bool EstimateColumnNoise(const Series& series, int column, double T, double* sigma, double* q, std::size_t rows) {
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
  *q = b_fit / (kQCoefficient * T5);
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

namespace {

// Median sample interval of the rows [0, rows) (rows ≥ 2).
double MedianInterval(const std::vector<double>& t, std::size_t rows) {
  std::vector<double> dt;
  dt.reserve(rows);
  for (std::size_t k = 1; k < rows; ++k) dt.push_back(t[k] - t[k - 1]);
  return numeric::UpperMedian(std::move(dt));
}

// σ and q of every column not given, fitted on the rows [0, rows); given values are copied. `known[c]` is
// set when column c has its noise (given, or estimated now). Columns that cannot be estimated yet (no 4
// consecutive values) keep their previous entries.
struct NoiseFitOut {
  std::vector<double> sigma, q;
  std::vector<bool> known;
  std::vector<NoiseMlFit> ml;
  std::vector<bool> ml_used;
  double interval_s = 0.0;
};

constexpr int kCausalBurnIn = 3;  // innovations left out by a causal ML fit (its start is diffuse in 3 states)

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

struct Counters {
  std::size_t updates = 0, partial_updates = 0, skipped_updates = 0, adapt_steps = 0, adapt_skipped = 0;
  std::size_t q_repairs = 0, r_repairs = 0, p_repairs = 0;
  double nis_sum = 0.0;
  std::size_t nis_dof = 0;
};

// The forward cycle (prediction to the lead time, second half step, update) over the rows of a series,
// restartable from row 0 so that the state can be recomputed with new noise.
class Forward {
 public:
  Forward(const Series& series, const AukfOptions& options, Model* model)
      : s_(series), o_(options), model_(model), m_(model->m), n_(model->n) {
    initialised_.assign(static_cast<std::size_t>(m_), false);
    first_row_.assign(static_cast<std::size_t>(m_), series.rows());
    sigma_.assign(static_cast<std::size_t>(m_), 0.0);
    R0_ = MeasMat::Zero(m_, m_);
    r_scale_.resize(m_);
  }

  // Noise from now on: σ (initial R) and q per column; T scales the repairs and the diffuse start.
  void SetNoise(const std::vector<double>& sigma, const std::vector<double>& q, double T) {
    sigma_ = sigma;
    T_ = T;
    model_->q = q;
    for (int c = 0; c < m_; ++c) {
      const double sc = sigma[static_cast<std::size_t>(c)];
      model_->scale(3 * c) = sc;
      model_->scale(3 * c + 1) = sc / T;
      model_->scale(3 * c + 2) = sc / (T * T);
      R0_(c, c) = sc * sc;
      r_scale_(c) = sc;
    }
    if (!(AdaptsR(o_.adapt.mode) && r_adapted_)) R_ = R0_;
  }

  // State at row 0: columns measured there start at their value, the others wait for their first value.
  void Start() {
    x_ = StateVec::Zero(n_);
    P_ = StateMat::Zero(n_, n_);
    std::fill(initialised_.begin(), initialised_.end(), false);
    for (int c = 0; c < m_; ++c) InitColumn(c, 0);
    R_ = R0_;
    r_adapted_ = false;
    q_adapted_ = false;
    innov_.Reset(m_, o_.adapt);
  }

  // Interval t_{k−1} → t_k: x_mid, P_mid at the lead time, then x, P updated with row k.
  void Step(std::size_t k, Counters* cnt) {
    const double tau = s_.t_s[k] - s_.t_s[k - 1];
    const double s1 = o_.lead * tau, s2 = tau - s1;
    const StateMat* Qr = q_adapted_ ? &Q_rate_ : nullptr;
    model_->Predict(x_, &P_, s1, Qr, &x_mid_, &P_mid_, &cnt->p_repairs);
    model_->Predict(x_mid_, &P_mid_, s2, Qr, &x_, &P_, &cnt->p_repairs);
    const Eigen::MatrixXd& Z = s_.values;
    const Eigen::Index row = static_cast<Eigen::Index>(k);
    int avail[ukf::kMaxColumns];
    int ma = 0, measured = 0;
    for (int c = 0; c < m_; ++c) {
      if (!std::isfinite(Z(row, c))) continue;
      ++measured;
      if (initialised_[static_cast<std::size_t>(c)]) {
        avail[ma++] = c;
      } else {
        InitColumn(c, k);
      }
    }
    if (measured == 0) {
      ++cnt->skipped_updates;
      return;
    }
    ++cnt->updates;
    if (measured < m_) ++cnt->partial_updates;
    if (ma == 0) return;
    const StateVec x_pred = x_;
    const StateMat P_pred = P_;
    MeasMat S(ma, ma);
    ukf::GainMat Pxy(n_, ma);
    MeasVec d(ma);
    for (int a = 0; a < ma; ++a) {
      const int ca = avail[a], ra = 3 * ca;
      d(a) = Diff(Z(row, ca), x_pred(ra), s_.is_angle[static_cast<std::size_t>(ca)]);
      Pxy.col(a) = P_pred.col(ra);
      for (int b = 0; b < ma; ++b) S(a, b) = P_pred(ra, 3 * avail[b]) + R_(ca, avail[b]);
    }
    ukf::Symmetrise(&S);
    Eigen::LLT<MeasMat> llt(S);
    if (llt.info() != Eigen::Success) {
      MeasVec sc(ma);
      for (int a = 0; a < ma; ++a) sc(a) = r_scale_(avail[a]);
      ukf::RepairSpd(&S, sc, o_.adapt.r_floor);
      ++cnt->p_repairs;
      llt.compute(S);
      if (llt.info() != Eigen::Success) throw ProcessingError("innovation covariance is not positive definite");
    }
    // K = Pxy S⁻¹  ⇔  Kᵀ = S⁻¹ Pxyᵀ
    const ukf::GainMat K = llt.solve(Pxy.transpose()).transpose();
    cnt->nis_sum += d.dot(llt.solve(d));
    cnt->nis_dof += static_cast<std::size_t>(ma);
    x_.noalias() += K * d;
    ukf::WrapAngles(model_->angles, &x_);
    P_.noalias() -= K * S * K.transpose();
    ukf::Symmetrise(&P_);
    if (o_.adapt.mode != AdaptMode::kNone) Adapt(ma, d, P_pred, K, tau, cnt);
  }

  const StateVec& x() const { return x_; }
  const StateMat& P() const { return P_; }
  const StateVec& x_mid() const { return x_mid_; }
  const StateMat& P_mid() const { return P_mid_; }
  const MeasMat& R() const { return R_; }
  bool q_adapted() const { return q_adapted_; }
  const StateMat& Q_rate() const { return Q_rate_; }
  const std::vector<std::size_t>& first_row() const { return first_row_; }

 private:
  // Column c starts at its value of row k (a placeholder at the row-0 start when it has none there):
  // x = [z, 0, 0], P = diag(σ², (30σ/T)², (100σ/T²)²), no correlation with the other columns.
  void InitColumn(int c, std::size_t k) {
    const std::size_t cu = static_cast<std::size_t>(c);
    const int r = 3 * c;
    const double z = s_.values(static_cast<Eigen::Index>(k), c);
    const bool have = std::isfinite(z);
    x_.segment(r, 3).setZero();
    if (have) {
      x_(r) = s_.is_angle[cu] ? geo::WrapPi(z) : z;
      initialised_[cu] = true;
      first_row_[cu] = std::min(first_row_[cu], k);
    }
    P_.middleRows(r, 3).setZero();
    P_.middleCols(r, 3).setZero();
    const double sg = sigma_[cu];
    P_(r, r) = sg * sg;
    P_(r + 1, r + 1) = std::pow(kDiffuseRate * sg / T_, 2);
    P_(r + 2, r + 2) = std::pow(kDiffuseAccel * sg / (T_ * T_), 2);
  }

  // Adaptation (rows with every column only).
  void Adapt(int ma, const MeasVec& d, const StateMat& P_pred, const ukf::GainMat& K, double tau, Counters* cnt) {
    if (ma < m_) {
      ++cnt->adapt_skipped;
      return;
    }
    MeasMat HPH(m_, m_);
    for (int a = 0; a < m_; ++a) {
      for (int b = 0; b < m_; ++b) HPH(a, b) = P_pred(3 * a, 3 * b);
    }
    innov_.Add(d, HPH);
    if (!innov_.Ready()) return;
    ++cnt->adapt_steps;
    if (AdaptsR(o_.adapt.mode)) {
      MeasMat Rn(m_, m_);
      for (int a = 0; a < m_; ++a) {
        for (int b = 0; b < m_; ++b) Rn(a, b) = innov_.C()(a, b) - innov_.HPH()(a, b);
      }
      if (ukf::RepairSpd(&Rn, r_scale_, o_.adapt.r_floor, o_.adapt.r_ceiling)) ++cnt->r_repairs;
      R_ = Rn;
      r_adapted_ = true;
    }
    if (AdaptsQ(o_.adapt.mode)) {
      StateMat Qn = K * innov_.C() * K.transpose();
      if (ukf::RepairSpd(&Qn, model_->scale, o_.adapt.q_floor, o_.adapt.q_ceiling)) ++cnt->q_repairs;
      Q_rate_ = Qn / tau;
      q_adapted_ = true;
    }
  }

  static constexpr double kDiffuseRate = 30.0;    // prior 1σ of p' in σ/T
  static constexpr double kDiffuseAccel = 100.0;  // prior 1σ of p'' in σ/T²

  const Series& s_;
  const AukfOptions& o_;
  Model* model_;
  int m_, n_;
  std::vector<bool> initialised_;
  std::vector<std::size_t> first_row_;
  std::vector<double> sigma_;
  double T_ = 1.0;
  StateVec x_, x_mid_;
  StateMat P_, P_mid_;
  MeasMat R0_, R_;
  MeasVec r_scale_;
  InnovationCovariance innov_;
  StateMat Q_rate_;
  bool q_adapted_ = false, r_adapted_ = false;
};

// ---- RunAukf in stages: check the input, choose the noise, run the forward filter (with the causal
// refits), collect its figures, smooth (RTS over the stored nodes, or from a second forward pass).

// The options and the series fit together: usage errors (exit 2) and data errors (exit 3).
void CheckAukfInput(const Series& series, const AukfOptions& options) {
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
  if (N < 3) throw TooFewSamplesError(series.source, "needs at least 3 samples, has " + std::to_string(N));
  if (!(m * 3 + options.kappa > 0)) throw UsageError("--kappa: n + kappa must be > 0");
}

// Every column has at least 2 values.
void CheckColumnValues(const Series& series) {
  const Eigen::MatrixXd& Z = series.values;
  for (int c = 0; c < static_cast<int>(series.columns.size()); ++c) {
    std::size_t values = 0;
    for (std::size_t k = 0; k < series.rows(); ++k) values += std::isfinite(Z(static_cast<Eigen::Index>(k), c)) ? 1 : 0;
    if (values < 2) {
      throw DataError(series.source, 0, 0, "column '" + series.columns[static_cast<std::size_t>(c)] + "' has fewer than 2 values");
    }
  }
}

// The noise in use per column (provisional until its first fit in causal mode) and its interval.
struct NoiseInUse {
  std::vector<double> sigma, q;
  double T = 0.0;
};

// Noise per column: given, or fitted (on the whole file, or on the rows up to each refit). Fills *noise
// with the whole-file fit (not causal); throws when a column cannot be estimated even on the whole file.
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

// The model of the series' columns (white jerk per column, angle rows wrapped).
void InitModel(const Series& series, const AukfOptions& options, Model* model) {
  const int m = static_cast<int>(series.columns.size());
  const int n = 3 * m;
  model->m = m;
  model->n = n;
  model->kappa = options.kappa;
  model->w = ukf::MakeWeights(n, options.kappa);
  model->is_angle = series.is_angle;
  model->block_diagonal = options.adapt.mode == AdaptMode::kNone && !options.joint_transform;
  model->scale.resize(n);
  for (int c = 0; c < m; ++c) {
    if (series.is_angle[static_cast<std::size_t>(c)]) model->angles.Add(3 * c);
  }
}

// Per-interval noise for the smoother: adapted Q, or the q of a causal refit schedule.
struct IntervalNoise {
  bool store_q = false;               // adapted Q per interval
  bool store_model_q = false;         // the model's q per interval
  std::vector<double> q_store;        // packed Q_rate per sample interval
  std::vector<char> q_store_used;     // 1 if the interval used an adapted Q
  std::vector<double> model_q_store;  // m per sample interval
};

// The forward pass over every row: the filtered nodes (sample 0, then mid-interval and sample for each
// interval) into the result, with the noise refits of the causal schedule.
class ForwardPass {
 public:
  ForwardPass(const Series& series, const AukfOptions& options, bool causal, bool keep_cov, Model* model,
              Forward* fwd, NoiseFitOut* noise, NoiseInUse* use, IntervalNoise* intervals, AukfResult* res)
      : series_(series), options_(options), causal_(causal), keep_cov_(keep_cov), model_(model), fwd_(fwd),
        noise_(noise), use_(use), intervals_(intervals), res_(res) {}

  void Run() {
    const std::size_t N = series_.rows();
    MaybeRefit(1);
    Store(series_.t_s[0], false, 0, fwd_->x(), fwd_->P());
    for (std::size_t k = 1; k < N; ++k) {
      if (intervals_->store_q) {
        intervals_->q_store_used.push_back(fwd_->q_adapted() ? 1 : 0);
        if (fwd_->q_adapted()) Pack(fwd_->Q_rate(), &intervals_->q_store);
      }
      if (intervals_->store_model_q) {
        intervals_->model_q_store.insert(intervals_->model_q_store.end(), model_->q.begin(), model_->q.end());
      }
      fwd_->Step(k, &cnt_);
      Store(series_.t_s[k - 1] + options_.lead * (series_.t_s[k] - series_.t_s[k - 1]), true, k - 1, fwd_->x_mid(),
            fwd_->P_mid());
      MaybeRefit(k + 1);
      Store(series_.t_s[k], false, k, fwd_->x(), fwd_->P());
    }
  }
  const Counters& counters() const { return cnt_; }

 private:
  AukfStatus RowStatus(std::size_t k) const {
    for (int c = 0; c < res_->m; ++c) {
      if (std::isfinite(series_.values(static_cast<Eigen::Index>(k), c))) return AukfStatus::kOk;
    }
    return AukfStatus::kPredicted;
  }

  void Store(double t, bool mid, std::size_t sample, const StateVec& xs, const StateMat& Ps) {
    const Eigen::Index j = static_cast<Eigen::Index>(res_->t_s.size());
    res_->t_s.push_back(t);
    res_->is_mid.push_back(mid);
    res_->sample.push_back(static_cast<int>(sample));
    res_->status.push_back(mid ? AukfStatus::kOk : RowStatus(sample));
    res_->x_filter.col(j) = xs;
    res_->sd_filter.col(j) = Ps.diagonal().cwiseMax(0.0).cwiseSqrt();
    if (keep_cov_) Pack(Ps, &res_->cov_filter);
  }

  // After the update of row k − 1 (rows 0..k−1 in): refit on those rows when the schedule says so.
  void MaybeRefit(std::size_t rows) {
    if (!causal_ || !options_.causal.IsRefit(rows)) return;
    FitNoise(series_, rows, options_, res_->meas_sigma_estimated, res_->q_estimated, true, noise_);
    bool any = false;
    for (std::size_t c = 0; c < series_.columns.size(); ++c) {
      if (!noise_->known[c]) continue;
      any = true;
      use_->sigma[c] = noise_->sigma[c];
      use_->q[c] = noise_->q[c];
      res_->noise_known_row[c] = std::min(res_->noise_known_row[c], rows - 1);
    }
    if (!any) return;
    use_->T = noise_->interval_s;
    fwd_->SetNoise(use_->sigma, use_->q, use_->T);
    AukfResult::NoiseRefit rf;
    rf.rows = rows;
    rf.restarted = rows <= static_cast<std::size_t>(options_.causal.restart_until);
    rf.meas_sigma = use_->sigma;
    rf.q = use_->q;
    if (rf.restarted) {
      // Re-run the filter over the rows so far with the new noise (no output; repairs are counted).
      Counters replay;
      fwd_->Start();
      for (std::size_t k = 1; k < rows; ++k) fwd_->Step(k, &replay);
      cnt_.p_repairs += replay.p_repairs;
      cnt_.q_repairs += replay.q_repairs;
      cnt_.r_repairs += replay.r_repairs;
    }
    res_->noise_refits.push_back(std::move(rf));
  }

  const Series& series_;
  const AukfOptions& options_;
  const bool causal_, keep_cov_;
  Model* model_;
  Forward* fwd_;
  NoiseFitOut* noise_;
  NoiseInUse* use_;
  IntervalNoise* intervals_;
  AukfResult* res_;
  Counters cnt_;
};

// The forward pass's counters, noise and final R and Q into the result.
void CollectForward(const Counters& cnt, const Forward& fwd, const NoiseFitOut& noise, const NoiseInUse& use,
                    const AukfOptions& options, const Model& model, AukfResult* res) {
  res->first_row = fwd.first_row();
  res->updates = cnt.updates;
  res->partial_updates = cnt.partial_updates;
  res->skipped_updates = cnt.skipped_updates;
  res->adapt_steps = cnt.adapt_steps;
  res->adapt_skipped = cnt.adapt_skipped;
  res->q_repairs = cnt.q_repairs;
  res->r_repairs = cnt.r_repairs;
  res->p_repairs = cnt.p_repairs;
  res->nis_sum = cnt.nis_sum;
  res->nis_dof = cnt.nis_dof;
  res->meas_sigma = use.sigma;
  res->q = use.q;
  const bool estimated = res->meas_sigma_estimated || res->q_estimated;
  if (estimated && options.noise_estimator == NoiseEstimator::kMaxLikelihood) {
    res->noise_fit = noise.ml;
    res->noise_fit_used = noise.ml_used;
  }
  const double T = res->interval_s;
  res->final_R = fwd.R();
  res->final_Q_adapted = fwd.q_adapted();
  if (fwd.q_adapted()) {
    res->final_Q = fwd.Q_rate() * T;
  } else {
    res->final_Q = StateMat::Zero(res->n, res->n);
    model.AddQ(T, nullptr, &res->final_Q);
  }
}

// Rauch–Tung–Striebel over the stored filter nodes (cov_filter kept), backwards from the last node.
void RtsSmooth(const AukfOptions& options, const IntervalNoise& intervals, Model* model, AukfResult* res) {
  const int m = res->m;
  const int n = res->n;
  const std::size_t mu = static_cast<std::size_t>(m);
  const std::size_t J = res->t_s.size();
  const std::size_t packed = static_cast<std::size_t>(n * (n + 1) / 2);
  res->x_smooth.resize(n, static_cast<Eigen::Index>(J));
  res->sd_smooth.resize(n, static_cast<Eigen::Index>(J));
  StateVec xs = res->x_filter.col(static_cast<Eigen::Index>(J - 1));
  StateMat Ps;
  Unpack(res->cov_filter.data() + (J - 1) * packed, n, &Ps);
  res->x_smooth.col(static_cast<Eigen::Index>(J - 1)) = xs;
  res->sd_smooth.col(static_cast<Eigen::Index>(J - 1)) = Ps.diagonal().cwiseMax(0.0).cwiseSqrt();
  std::size_t smoother_repairs = 0;
  std::vector<std::size_t> q_offset;  // packed offset of each interval's adapted Q
  if (intervals.store_q) {
    std::size_t off = 0;
    for (char u : intervals.q_store_used) {
      q_offset.push_back(off);
      if (u) off += packed;
    }
  }
  StateMat Qr_k;
  for (std::size_t jj = J - 1; jj-- > 0;) {
    const StateVec xf = res->x_filter.col(static_cast<Eigen::Index>(jj));
    StateMat Pf;
    Unpack(res->cov_filter.data() + jj * packed, n, &Pf);
    const double s = res->t_s[jj + 1] - res->t_s[jj];
    const std::size_t interval = jj / 2;  // nodes 2i (sample i) and 2i+1 (mid) lie in interval i → i+1
    const StateMat* Qr = nullptr;
    if (intervals.store_q && intervals.q_store_used[interval]) {
      Unpack(intervals.q_store.data() + q_offset[interval], n, &Qr_k);
      Qr = &Qr_k;
    }
    if (intervals.store_model_q) {
      std::copy_n(intervals.model_q_store.begin() + static_cast<std::ptrdiff_t>(interval * mu), mu, model->q.begin());
    }
    StateVec xp;
    StateMat Pp;
    StateMat C;
    model->Predict(xf, &Pf, s, Qr, &xp, &Pp, &smoother_repairs, &C);
    Eigen::LLT<StateMat> llt(Pp);
    if (llt.info() != Eigen::Success) {
      ukf::RepairSpd(&Pp, model->scale, model->p_floor);
      ++smoother_repairs;
      llt.compute(Pp);
    }
    StateMat G = llt.solve(C.transpose()).transpose();
    // A column that starts at node jj + 1 was not predicted from node jj: nothing flows back to it.
    for (int c = 0; c < m; ++c) {
      const std::size_t f = res->first_row[static_cast<std::size_t>(c)];
      if (f > 0 && jj + 1 == 2 * f) G.middleRows(3 * c, 3).setZero();
    }
    StateVec diff = xs - xp;
    ukf::WrapAngles(model->angles, &diff);
    StateVec xs_new = xf + G * diff;
    ukf::WrapAngles(model->angles, &xs_new);
    StateMat Ps_new = Pf + G * (Ps - Pp) * G.transpose();
    ukf::Symmetrise(&Ps_new);
    xs = xs_new;
    Ps = Ps_new;
    res->x_smooth.col(static_cast<Eigen::Index>(jj)) = xs;
    res->sd_smooth.col(static_cast<Eigen::Index>(jj)) = Ps.diagonal().cwiseMax(0.0).cwiseSqrt();
  }
  res->p_repairs += smoother_repairs;
  if (!options.keep_covariance) {
    res->cov_filter.clear();
    res->cov_filter.shrink_to_fit();
  }
}

}  // namespace

AukfResult RunAukf(const Series& series, const AukfOptions& options) {
  CheckAukfInput(series, options);
  const int m = static_cast<int>(series.columns.size());
  const int n = 3 * m;
  const std::size_t N = series.rows();

  AukfResult res;
  res.m = m;
  res.n = n;
  res.samples = N;
  res.interval_s = MedianInterval(series.t_s, N);
  CheckColumnValues(series);

  res.meas_sigma_estimated = options.meas_sigma.empty();
  res.q_estimated = options.q.empty();
  const bool estimated = res.meas_sigma_estimated || res.q_estimated;
  const bool causal = estimated && options.noise_fit == NoiseFit::kCausal;
  NoiseFitOut noise;
  NoiseInUse use = InitialNoise(series, options, res, causal, &noise);
  res.noise_known_row.assign(static_cast<std::size_t>(m), causal ? N : 0);

  Model model;
  InitModel(series, options, &model);
  Forward fwd(series, options, &model);
  fwd.SetNoise(use.sigma, use.q, use.T);
  fwd.Start();

  const std::size_t J = 2 * N - 1;
  const bool smooth_here = options.smooth && (!estimated || options.smooth_noise_fit == options.noise_fit);
  const bool keep_cov = options.keep_covariance || smooth_here;
  const std::size_t packed = static_cast<std::size_t>(n * (n + 1) / 2);
  if (keep_cov) res.cov_filter.reserve(J * packed);
  IntervalNoise intervals;
  intervals.store_q = smooth_here && AdaptsQ(options.adapt.mode);
  intervals.store_model_q = smooth_here && causal;
  res.t_s.reserve(J);
  res.x_filter.resize(n, static_cast<Eigen::Index>(J));
  res.sd_filter.resize(n, static_cast<Eigen::Index>(J));

  ForwardPass pass(series, options, causal, keep_cov, &model, &fwd, &noise, &use, &intervals, &res);
  pass.Run();
  CollectForward(pass.counters(), fwd, noise, use, options, model, &res);

  if (options.smooth && !smooth_here) {
    // Smoothed rows from a forward pass with the other noise fit (they may use every sample).
    AukfOptions o = options;
    o.noise_fit = options.smooth_noise_fit;
    o.keep_covariance = false;
    AukfResult r = RunAukf(series, o);
    res.x_smooth = std::move(r.x_smooth);
    res.sd_smooth = std::move(r.sd_smooth);
    res.smooth_meas_sigma = r.meas_sigma;
    res.smooth_q = r.q;
    res.p_repairs += r.p_repairs;
    return res;
  }
  if (smooth_here) RtsSmooth(options, intervals, &model, &res);
  return res;
}

}  // namespace rk::filter

// The AUKF's forward filter over the rows of a series (aukf_internal.h): prediction to the lead time, the second
// half step, the update, the adaptation of R and Q, and the causal noise refits.
#include <algorithm>
#include <cmath>

#include "filter/aukf_internal.h"

namespace rk::filter::aukf_detail {
namespace {

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

}  // namespace

void RunForward(const Series& series, const AukfOptions& options, bool causal, bool keep_cov, Model* model,
                NoiseFitOut* noise, NoiseInUse* use, IntervalNoise* intervals, AukfResult* res) {
  Forward fwd(series, options, model);
  fwd.SetNoise(use->sigma, use->q, use->T);
  fwd.Start();
  ForwardPass pass(series, options, causal, keep_cov, model, &fwd, noise, use, intervals, res);
  pass.Run();
  CollectForward(pass.counters(), fwd, *noise, *use, options, *model, res);
}

}  // namespace rk::filter::aukf_detail

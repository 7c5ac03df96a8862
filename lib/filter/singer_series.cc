// Singer-model filter and RTS smoother over a Series; see singer_series.h.
#include "filter/singer_series.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geo/angles.h"
#include "io/error.h"
#include "io/json_util.h"
#include "io/run_summary.h"
#include "numeric/robust_stats.h"
#include "track/singer.h"

namespace rk::filter {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Floor of σ_z relative to the data scale, so that S > 0 even for noise-free data.
constexpr double kMeasSigmaFloorRel = 1e-9;
constexpr double kMeasSigmaFloorAbs = 1e-12;

double Binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

template <typename T>
T PerColumn(const std::vector<T>& v, std::size_t c) {
  return v.size() == 1 ? v[0] : v[c];
}

// Counts of a column's forward pass.
struct ForwardCounts {
  double nis_sum = 0.0, nll = 0.0;  // Σ ν²/S, Σ (ln S + ν²/S) / 2 over the updates after the first
  std::size_t nis_count = 0, updates = 0, missing = 0, first_row = 0;
};

// One row r of a column's forward pass, from the state after row r − 1 (`step`: Ψ and Q's factors from
// row r − 1 to r; unused at the column's first value): the start at the first value, else the prediction,
// then the update with z (NaN = no measurement). Stores the predicted state in x_pred/P_pred and counts in
// `counts` when given. Returns false while the column has no estimate (before its first value). The one copy
// of the forward arithmetic: RunSingerSeries and every block SingerSmoother recomputes run it.
bool ForwardRow(const SingerColumnModel& m, double z, const track::SingerStep& step, std::size_t r, SingerState* s,
                ForwardCounts* counts, Eigen::Vector3d* x_pred, Eigen::Matrix3d* P_pred) {
  const bool have = std::isfinite(z);
  bool first = false;
  if (!s->started) {
    if (!have) return false;
    s->started = true;
    first = true;
    s->x << z, 0.0, 0.0;
    s->P.setZero();
    s->P(0, 0) = m.R;
    s->P(1, 1) = m.vel_sigma * m.vel_sigma;
    s->P(2, 2) = m.accel_sigma * m.accel_sigma;
    if (counts) {
      counts->first_row = r;
      ++counts->updates;
    }
  } else {
    const Eigen::Matrix3d& Phi = step.transition();
    s->x = Phi * s->x;
    s->P = Phi * s->P * Phi.transpose() + step.ProcessNoise(m.q);
    s->P = 0.5 * (s->P + s->P.transpose()).eval();
  }
  if (x_pred) {
    *x_pred = s->x;
    *P_pred = s->P;
  }
  if (first) return true;
  if (have) {
    const double nu = m.angle ? geo::WrapPi(z - s->x(0)) : z - s->x(0);
    const double S = s->P(0, 0) + m.R;
    const Eigen::Vector3d K = s->P.col(0) / S;
    s->x += K * nu;
    Eigen::Matrix3d IKH = Eigen::Matrix3d::Identity();
    IKH.col(0) -= K;
    s->P = IKH * s->P * IKH.transpose() + (K * K.transpose()) * m.R;
    s->P = 0.5 * (s->P + s->P.transpose()).eval();
    if (counts) {
      counts->nis_sum += nu * nu / S;
      counts->nll += 0.5 * (std::log(S) + nu * nu / S);
      ++counts->nis_count;
      ++counts->updates;
    }
  } else if (counts) {
    ++counts->missing;
  }
  return true;
}

void FillStats(const ForwardCounts& c, SingerColumnStats* st) {
  st->updates = c.updates;
  st->missing = c.missing;
  st->first_row = c.first_row;
  st->nis_count = c.nis_count;
  st->nis_mean = c.nis_count ? c.nis_sum / static_cast<double>(c.nis_count) : kNaN;
}

// One RTS step of `tr` at index i from index i + 1 (Φ: the transition from row i to row i + 1):
//   C = P_f Φᵀ P_p⁻¹  ⇔  Cᵀ = P_p⁻¹ Φ P_f (P symmetric). The one copy of the backward arithmetic.
void RtsStep(const Eigen::Matrix3d& Phi, std::size_t i, SingerTrack* tr) {
  const Eigen::Matrix3d Ct = tr->P_pred[i + 1].ldlt().solve(Phi * tr->P_filt[i]);
  const Eigen::Matrix3d C = Ct.transpose();
  tr->x_smooth[i] = tr->x_filt[i] + C * (tr->x_smooth[i + 1] - tr->x_pred[i + 1]);
  Eigen::Matrix3d Ps = tr->P_filt[i] + C * (tr->P_smooth[i + 1] - tr->P_pred[i + 1]) * Ct;
  tr->P_smooth[i] = 0.5 * (Ps + Ps.transpose());
}

// Kalman forward pass of one column over all rows (values z, steps[r] from row r − 1 to r); fills `tr`
// (x/P pred/filt) and `st` (counts, NIS) when given. Returns the negative log-likelihood of the innovations
// after the first update, Σ (ln S + ν²/S) / 2.
double ForwardPass(const SingerColumnModel& m, const double* z, std::size_t n,
                   const std::vector<track::SingerStep>& steps, SingerTrack* tr, SingerColumnStats* st) {
  if (tr) {
    tr->x_pred.assign(n, Eigen::Vector3d::Zero());
    tr->x_filt.assign(n, Eigen::Vector3d::Zero());
    tr->P_pred.assign(n, Eigen::Matrix3d::Zero());
    tr->P_filt.assign(n, Eigen::Matrix3d::Zero());
  }
  SingerState s;
  ForwardCounts counts;
  for (std::size_t r = 0; r < n; ++r) {
    if (!ForwardRow(m, z[r], steps[r], r, &s, &counts, tr ? &tr->x_pred[r] : nullptr,
                    tr ? &tr->P_pred[r] : nullptr)) {
      continue;
    }
    if (tr) {
      tr->x_filt[r] = s.x;
      tr->P_filt[r] = s.P;
    }
  }
  if (st) FillStats(counts, st);
  return counts.nll;
}

// options.Check and the lengths of the per-column lists; UsageError.
void CheckRun(const Series& series, const SingerSeriesOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  const std::size_t nc = series.columns.size();
  auto check_len = [&](std::size_t len, const char* what) {
    if (len > 1 && len != nc) {
      throw UsageError(std::string(what) + ": give one value or one per column (" + std::to_string(nc) +
                       "), got " + std::to_string(len));
    }
  };
  check_len(options.accel_sigma.size(), "--accel-sigma");
  check_len(options.meas_sigma.size(), "--meas-sigma");
}

// The σ_m a column tries: one (given, or the unit default) or the maximum-likelihood grid, each as a
// model; `fallback` is the one kept when no candidate's likelihood is below +∞ (the unit default).
struct Candidates {
  std::vector<SingerColumnModel> models;
  std::size_t fallback = 0;
};

// Column c's model: σ_z (given, or estimated from the data; into st), the velocity prior and the σ_m
// candidates. Throws UsageError for a unit without a default σ_m and no --accel-sigma.
Candidates PrepareColumn(const Series& series, std::size_t c, const SingerSeriesOptions& options, double a,
                         SingerColumnStats* st) {
  const std::size_t n = series.rows();
  const bool angle = series.is_angle[c];
  const std::span<const double> z(series.values.col(static_cast<Eigen::Index>(c)).data(), n);
  double accel_sigma = options.accel_sigma.empty() ? DefaultAccelSigma(series.columns[c])
                                                   : PerColumn(options.accel_sigma, c);
  if (!std::isfinite(accel_sigma)) {
    throw UsageError("--accel-sigma is needed for column '" + series.columns[c] +
                     "' (no default for its unit; defaults exist for _m, _deg and _px)");
  }
  // Scale of the data: for the σ_z floor and the velocity prior.
  double max_rate = 0.0, scale = 0.0;
  std::size_t prev = n;
  for (std::size_t r = 0; r < n; ++r) {
    if (!std::isfinite(z[r])) continue;
    scale = std::max(scale, std::abs(z[r]));
    if (prev < n) {
      const double dz = angle ? geo::WrapPi(z[r] - z[prev]) : z[r] - z[prev];
      max_rate = std::max(max_rate, std::abs(dz) / (series.t_s[r] - series.t_s[prev]));
    }
    prev = r;
  }
  if (options.meas_sigma.empty()) {
    double s = EstimateNoiseSigma(z, angle);
    if (!std::isfinite(s)) s = 0.0;
    st->meas_sigma = std::max(s, kMeasSigmaFloorRel * scale + kMeasSigmaFloorAbs);
    st->meas_sigma_estimated = true;
  } else {
    st->meas_sigma = PerColumn(options.meas_sigma, c);
  }
  SingerColumnModel m;
  m.angle = angle;
  m.a = a;
  m.R = st->meas_sigma * st->meas_sigma;
  m.vel_sigma = std::max(2.0 * max_rate, 10.0 * st->meas_sigma);
  Candidates out;
  auto add = [&](double sigma) {
    m.accel_sigma = sigma;
    m.q = 2.0 * a * sigma * sigma;
    out.models.push_back(m);
  };
  if (options.accel_sigma.empty() && options.auto_accel_sigma) {
    // σ_m chosen by maximum likelihood over a grid around the unit default.
    const double center = accel_sigma;
    for (int k = kAutoAccelGridLow; k <= kAutoAccelGridHigh; ++k) add(center * std::pow(2.0, 0.5 * k));
    out.fallback = static_cast<std::size_t>(-kAutoAccelGridLow);  // k = 0: the default itself
    st->accel_sigma_selected = true;
  } else {
    add(accel_sigma);
  }
  return out;
}

// The candidate of least negative log-likelihood (the first of equals), else the fallback.
std::size_t ChooseCandidate(const std::vector<double>& nll, std::size_t fallback) {
  if (nll.size() == 1) return 0;
  double best = std::numeric_limits<double>::infinity();
  std::size_t chosen = fallback;
  for (std::size_t i = 0; i < nll.size(); ++i) {
    if (nll[i] < best) {
      best = nll[i];
      chosen = i;
    }
  }
  return chosen;
}

// Rows [offset, ...) of one column's stored estimates: a whole run's (offset 0) or one block's.
struct TrackView {
  const SingerTrack& tr;
  std::size_t offset;
  const SingerColumnStats& st;
  bool smoothed;

  bool At(std::size_t row, Eigen::Vector3d* x, Eigen::Matrix3d* P) const {
    if (st.updates == 0 || row < st.first_row) return false;
    const std::size_t i = row - offset;
    *x = smoothed ? tr.x_smooth[i] : tr.x_filt[i];
    *P = smoothed ? tr.P_smooth[i] : tr.P_filt[i];
    return true;
  }
};

// The row an estimate at t starts from: the first row with a value when t is at or before it, else the
// last row k with t_k ≤ t.
std::size_t EvaluationRowOf(const std::vector<double>& ts, std::size_t first, double t) {
  if (t <= ts[first]) return first;
  return static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin()) - 1;
}

// EvaluateSinger on the rows `v` holds (row k of EvaluationRowOf, and k + 1 between rows when smoothed).
void EvaluateOn(const TrackView& v, const std::vector<double>& ts, double t, Eigen::Vector3d* x_out,
                Eigen::Matrix3d* P_out) {
  RK_CHECK(v.st.updates > 0, "EvaluateSinger on a column without measurements");
  const double a = v.tr.a_per_s;
  const std::size_t first = v.st.first_row;
  const std::size_t n = ts.size();
  Eigen::Vector3d x;
  Eigen::Matrix3d P;
  const auto at = [&](std::size_t row) { RK_CHECK(v.At(row, &x, &P), "no estimate at a row after the first"); };
  if (t <= ts[first]) {
    at(first);
    const double tau = ts[first] - t;
    if (tau > 0.0) {  // backward prediction
      const Eigen::Matrix3d Phi_inv = track::SingerTransition(tau, a).inverse();
      x = Phi_inv * x;
      P = Phi_inv * P * Phi_inv.transpose() + track::SingerProcessNoise(tau, a, v.tr.q);
    }
  } else {
    const std::size_t k = EvaluationRowOf(ts, first, t);
    const double tau = t - ts[k];
    if (tau == 0.0) {
      at(k);
    } else if (k + 1 >= n || !v.smoothed) {
      // After the last row (or filter only): predict forward from row k.
      at(k);
      const Eigen::Matrix3d Phi = track::SingerTransition(tau, a);
      x = Phi * x;
      P = Phi * P * Phi.transpose() + track::SingerProcessNoise(tau, a, v.tr.q);
    } else {
      // Inserted step at t between rows k and k+1, then one RTS step from k+1.
      const std::size_t i = k - v.offset;
      const Eigen::Matrix3d Phi1 = track::SingerTransition(tau, a);
      const Eigen::Matrix3d Phi2 = track::SingerTransition(ts[k + 1] - t, a);
      const Eigen::Vector3d xp = Phi1 * v.tr.x_filt[i];
      Eigen::Matrix3d Pp = Phi1 * v.tr.P_filt[i] * Phi1.transpose() + track::SingerProcessNoise(tau, a, v.tr.q);
      Pp = 0.5 * (Pp + Pp.transpose()).eval();
      const Eigen::Matrix3d Ct = v.tr.P_pred[i + 1].ldlt().solve(Phi2 * Pp);
      x = xp + Ct.transpose() * (v.tr.x_smooth[i + 1] - v.tr.x_pred[i + 1]);
      P = Pp + Ct.transpose() * (v.tr.P_smooth[i + 1] - v.tr.P_pred[i + 1]) * Ct;
    }
  }
  *x_out = x;
  *P_out = 0.5 * (P + P.transpose());
}

}  // namespace

const io::OptionTable<SingerSeriesOptions>& SingerSeriesOptions::Table() {
  static const io::OptionTable<SingerSeriesOptions> table = io::OptionTable<SingerSeriesOptions>().Real(
      "--maneuver-time", &SingerSeriesOptions::maneuver_time_s, "s", io::Bounds::Positive(),
      "Singer maneuver time constant tau_m (s), > 0");
  return table;
}

bool SingerSeriesOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!Table().Check(*this, why)) return false;
  for (double s : accel_sigma) {
    if (!(s >= 0.0) || !std::isfinite(s)) return fail("--accel-sigma values must be >= 0");
  }
  for (double s : meas_sigma) {
    if (!(s > 0.0) || !std::isfinite(s)) return fail("--meas-sigma values must be > 0");
  }
  return true;
}

double DefaultAccelSigma(const std::string& column) {
  std::string base, unit;
  if (!SplitUnit(column, &base, &unit)) return kNaN;
  if (unit == "m") return kDefaultAccelSigmaMps2;
  if (unit == "deg") return geo::DegToRad(kDefaultAccelSigmaDegS2);
  if (unit == "px") return kDefaultAccelSigmaPxS2;
  return kNaN;
}

std::string SingerRowStatusName(SingerRowStatus s) {
  switch (s) {
    case SingerRowStatus::kOk: return "ok";
    case SingerRowStatus::kPredicted: return "predicted";
    case SingerRowStatus::kLost: return "lost";
  }
  return "lost";
}

bool SingerSeriesResult::At(std::size_t column, std::size_t row, Eigen::Vector3d* x, Eigen::Matrix3d* P) const {
  return TrackView{tracks[column], 0, stats[column], smoothed}.At(row, x, P);
}

SingerRowStatus SingerRowStatusAt(const Series& series, const std::vector<SingerColumnStats>& stats,
                                  std::size_t row) {
  bool measured = false, estimated = false;
  for (std::size_t c = 0; c < stats.size(); ++c) {
    if (std::isfinite(series.values(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(c)))) measured = true;
    if (stats[c].updates > 0 && row >= stats[c].first_row) estimated = true;
  }
  if (measured) return SingerRowStatus::kOk;
  return estimated ? SingerRowStatus::kPredicted : SingerRowStatus::kLost;
}

double EstimateNoiseSigma(std::span<const double> values, bool angle, int order) {
  std::vector<double> v;
  for (double x : values) {
    if (!std::isfinite(x)) continue;
    if (angle && !v.empty()) x = v.back() + geo::WrapPi(x - v.back());
    v.push_back(x);
  }
  if (static_cast<int>(v.size()) < order + 3) return kNaN;
  for (int k = 0; k < order; ++k) {
    for (std::size_t i = 0; i + 1 < v.size() - static_cast<std::size_t>(k); ++i) v[i] = v[i + 1] - v[i];
  }
  v.resize(v.size() - static_cast<std::size_t>(order));
  const double mad = numeric::MedianAndMad(std::move(v)).mad;
  return 1.482602218505602 * mad / std::sqrt(Binomial(2 * order, order));
}

double NoiseSigmaFromDifferences(const std::vector<double>& values, bool angle, int min_order, int max_order,
                                 int* order_used) {
  std::vector<double> v;
  for (double x : values) {
    if (!std::isfinite(x)) continue;
    if (angle && !v.empty()) x = v.back() + geo::WrapPi(x - v.back());
    v.push_back(x);
  }
  double best = kNaN;
  for (int k = 1; k <= max_order && static_cast<int>(v.size()) >= k + 3; ++k) {
    for (std::size_t i = 0; i + 1 < v.size() - static_cast<std::size_t>(k - 1); ++i) v[i] = v[i + 1] - v[i];
    if (k < min_order) continue;
    const std::size_t count = v.size() - static_cast<std::size_t>(k);
    std::vector<double> d(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(count));
    const numeric::MedianMad mm = numeric::MedianAndMad(d);
    const double med = mm.median;
    const double mad = 1.482602218505602 * mm.mad;
    // RMS of the differences within 4 robust σ of their median: efficient like an RMS, robust like the MAD.
    double sum = 0.0;
    std::size_t used = 0;
    for (double x : d) {
      if (std::abs(x - med) <= 4.0 * mad) {
        sum += x * x;
        ++used;
      }
    }
    if (used == 0) continue;
    const double s = std::sqrt(sum / static_cast<double>(used) / Binomial(2 * k, k));
    if (!(s >= best)) {
      best = s;
      if (order_used) *order_used = k;
    }
  }
  return best;
}

SingerSeriesResult RunSingerSeries(const Series& series, const SingerSeriesOptions& options) {
  CheckRun(series, options);
  const std::size_t nc = series.columns.size();
  const std::size_t n = series.rows();
  SingerSeriesResult res;
  res.rows = n;
  res.smoothed = options.smooth;
  res.tracks.resize(nc);
  res.stats.resize(nc);
  const double a = 1.0 / options.maneuver_time_s;
  // Ψ and Q's factors of every step, once for all columns and all candidate σ_m.
  std::vector<track::SingerStep> steps(n);
  for (std::size_t r = 1; r < n; ++r) steps[r] = track::SingerStep(series.t_s[r] - series.t_s[r - 1], a);

  for (std::size_t c = 0; c < nc; ++c) {
    SingerColumnStats& st = res.stats[c];
    SingerTrack& tr = res.tracks[c];
    const double* z = series.values.col(static_cast<Eigen::Index>(c)).data();
    const Candidates cand = PrepareColumn(series, c, options, a, &st);
    std::vector<double> nll;
    if (cand.models.size() > 1) {
      for (const SingerColumnModel& m : cand.models) nll.push_back(ForwardPass(m, z, n, steps, nullptr, nullptr));
    } else {
      nll.push_back(0.0);
    }
    const SingerColumnModel& m = cand.models[ChooseCandidate(nll, cand.fallback)];
    st.accel_sigma = m.accel_sigma;
    tr.a_per_s = a;
    tr.q = m.q;
    ForwardPass(m, z, n, steps, &tr, &st);
    // Backward pass.
    if (options.smooth && st.updates > 0) {
      tr.x_smooth = tr.x_filt;
      tr.P_smooth = tr.P_filt;
      for (std::size_t r = n - 1; r-- > st.first_row;) RtsStep(steps[r + 1].transition(), r, &tr);
    }
  }

  res.status.resize(n, SingerRowStatus::kLost);
  for (std::size_t r = 0; r < n; ++r) {
    res.status[r] = SingerRowStatusAt(series, res.stats, r);
    switch (res.status[r]) {
      case SingerRowStatus::kOk: ++res.rows_ok; break;
      case SingerRowStatus::kPredicted: ++res.rows_predicted; break;
      case SingerRowStatus::kLost: ++res.rows_lost; break;
    }
  }
  return res;
}

void EvaluateSinger(const SingerSeriesResult& result, const Series& series, std::size_t column, double t,
                    Eigen::Vector3d* x_out, Eigen::Matrix3d* P_out) {
  EvaluateOn(TrackView{result.tracks[column], 0, result.stats[column], result.smoothed}, series.t_s, t, x_out,
             P_out);
}

// ---- SingerSmoother ----

SingerSmoother::SingerSmoother(const Series& series, const SingerSeriesOptions& options, std::size_t block_rows)
    : series_(series), block_rows_(block_rows) {
  RK_CHECK(block_rows >= 1, "SingerSmoother needs blocks of at least one row");
  CheckRun(series, options);
  const std::size_t nc = series.columns.size();
  const std::size_t n = series.rows();
  summary_.rows = n;
  summary_.smoothed = options.smooth;
  summary_.stats.resize(nc);
  columns_.resize(nc);
  const double a = 1.0 / options.maneuver_time_s;
  std::vector<std::vector<SingerColumnModel>> candidates(nc);
  std::vector<std::size_t> fallback(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    Candidates cand = PrepareColumn(series, c, options, a, &summary_.stats[c]);
    candidates[c] = std::move(cand.models);
    fallback[c] = cand.fallback;
  }
  Forward(candidates, fallback);
  for (std::size_t r = 0; r < n; ++r) {
    switch (RowStatus(r)) {
      case SingerRowStatus::kOk: ++summary_.rows_ok; break;
      case SingerRowStatus::kPredicted: ++summary_.rows_predicted; break;
      case SingerRowStatus::kLost: ++summary_.rows_lost; break;
    }
  }
  if (options.smooth) SmoothBlockEnds();
}

// Every candidate σ_m of every column in one pass over the rows (each candidate's arithmetic is that of its
// own ForwardPass, row by row); Ψ and Q's factors computed once a row for all of them. Keeps each candidate's
// state at every block start, then the chosen candidate's counts and block starts.
void SingerSmoother::Forward(const std::vector<std::vector<SingerColumnModel>>& candidates,
                             const std::vector<std::size_t>& fallback) {
  struct Run {
    SingerState s;
    ForwardCounts counts;
    std::vector<SingerState> start;
  };
  const std::size_t n = series_.rows(), nc = columns_.size(), nb = blocks();
  std::vector<std::vector<Run>> runs(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    runs[c].resize(candidates[c].size());
    for (Run& run : runs[c]) run.start.resize(nb);
  }
  const double a = candidates.empty() || candidates[0].empty() ? 1.0 : candidates[0][0].a;
  track::SingerStep step;
  for (std::size_t r = 0; r < n; ++r) {
    if (r > 0) step = track::SingerStep(series_.t_s[r] - series_.t_s[r - 1], a);
    const bool block_start = r % block_rows_ == 0;
    for (std::size_t c = 0; c < nc; ++c) {
      const double z = series_.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
      for (std::size_t k = 0; k < runs[c].size(); ++k) {
        Run& run = runs[c][k];
        if (block_start) run.start[r / block_rows_] = run.s;
        ForwardRow(candidates[c][k], z, step, r, &run.s, &run.counts, nullptr, nullptr);
      }
    }
  }
  for (std::size_t c = 0; c < nc; ++c) {
    std::vector<double> nll;
    for (const Run& run : runs[c]) nll.push_back(run.counts.nll);
    const std::size_t k = ChooseCandidate(nll, fallback[c]);
    columns_[c].model = candidates[c][k];
    columns_[c].start = std::move(runs[c][k].start);
    FillStats(runs[c][k].counts, &summary_.stats[c]);
    summary_.stats[c].accel_sigma = candidates[c][k].accel_sigma;
    runs[c].clear();
  }
}

SingerBlock SingerSmoother::NewBlock() const {
  SingerBlock block;
  block.smoothed_ = summary_.smoothed;
  block.stats_ = &summary_.stats;
  block.tracks_.resize(columns_.size());
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    SingerTrack& tr = block.tracks_[c];
    const std::size_t m = block_rows_ + 1;
    tr.x_pred.assign(m, Eigen::Vector3d::Zero());
    tr.x_filt.assign(m, Eigen::Vector3d::Zero());
    tr.P_pred.assign(m, Eigen::Matrix3d::Zero());
    tr.P_filt.assign(m, Eigen::Matrix3d::Zero());
    if (summary_.smoothed) {
      tr.x_smooth.assign(m, Eigen::Vector3d::Zero());
      tr.P_smooth.assign(m, Eigen::Matrix3d::Zero());
    }
    tr.a_per_s = columns_[c].model.a;
    tr.q = columns_[c].model.q;
  }
  return block;
}

// steps[i]: Ψ and Q's factors from row begin + i − 1 to begin + i, for i = 0 .. end − begin (row end when
// end < rows); the default (unused) step for row 0.
void SingerSmoother::BlockSteps(std::size_t b, std::vector<track::SingerStep>* steps) const {
  const std::size_t n = series_.rows(), begin = b * block_rows_, end = std::min(n, begin + block_rows_);
  const double a = columns_.empty() ? 1.0 : columns_[0].model.a;
  const std::size_t last = std::min(end, n - 1);
  steps->resize(last - begin + 1);
  for (std::size_t r = begin; r <= last; ++r) {
    (*steps)[r - begin] = r == 0 ? track::SingerStep() : track::SingerStep(series_.t_s[r] - series_.t_s[r - 1], a);
  }
}

// The forward pass over block b again from its checkpoint, into block->tracks_[column], with row end's
// prediction. False when the column has no estimate in the block (nothing recomputed).
bool SingerSmoother::Recompute(std::size_t b, std::size_t column, const std::vector<track::SingerStep>& steps,
                               SingerBlock* block) const {
  const std::size_t n = series_.rows(), begin = b * block_rows_, end = std::min(n, begin + block_rows_);
  const SingerColumnStats& st = summary_.stats[column];
  if (st.updates == 0 || end <= st.first_row) return false;
  const Column& col = columns_[column];
  SingerTrack& tr = block->tracks_[column];
  const double* z = series_.values.col(static_cast<Eigen::Index>(column)).data();
  SingerState s = b > 0 ? col.start[b] : SingerState{};
  for (std::size_t r = begin; r < end; ++r) {
    const std::size_t i = r - begin;
    if (!ForwardRow(col.model, z[r], steps[i], r, &s, nullptr, &tr.x_pred[i], &tr.P_pred[i])) continue;
    tr.x_filt[i] = s.x;
    tr.P_filt[i] = s.P;
  }
  if (end < n) {  // the prediction into row end: the time update alone (no measurement given)
    const std::size_t i = end - begin;
    ForwardRow(col.model, kNaN, steps[i], end, &s, nullptr, &tr.x_pred[i], &tr.P_pred[i]);
  }
  return true;
}

// The RTS pass over block b of a recomputed column, from the smoothed state of row end (the first sweep's,
// or at the last row the filtered state) down to the block's first row or the column's first row.
void SingerSmoother::Smooth(std::size_t b, std::size_t column, const std::vector<track::SingerStep>& steps,
                            SingerBlock* block) const {
  const std::size_t n = series_.rows(), begin = b * block_rows_, end = std::min(n, begin + block_rows_);
  SingerTrack& tr = block->tracks_[column];
  const std::size_t top = end == n ? n - 1 : end;
  if (end == n) {
    tr.x_smooth[top - begin] = tr.x_filt[top - begin];
    tr.P_smooth[top - begin] = tr.P_filt[top - begin];
  } else {
    const SingerState& e = columns_[column].smooth_end[b];
    RK_CHECK(e.started, "smoothed state of a block's end missing");
    tr.x_smooth[top - begin] = e.x;
    tr.P_smooth[top - begin] = e.P;
  }
  const std::size_t lo = std::max(begin, summary_.stats[column].first_row);
  for (std::size_t r = top; r-- > lo;) RtsStep(steps[r + 1 - begin].transition(), r - begin, &tr);
}

void SingerSmoother::SmoothBlockEnds() {
  const std::size_t nb = blocks();
  for (Column& col : columns_) col.smooth_end.assign(nb, SingerState{});
  SingerBlock block = NewBlock();
  std::vector<track::SingerStep> steps;
  for (std::size_t b = nb; b-- > 1;) {
    BlockSteps(b, &steps);
    const std::size_t begin = b * block_rows_;
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (!Recompute(b, c, steps, &block)) continue;
      Smooth(b, c, steps, &block);
      if (begin < summary_.stats[c].first_row) continue;  // no estimate at the block's first row
      SingerState& e = columns_[c].smooth_end[b - 1];
      e.x = block.tracks_[c].x_smooth[0];
      e.P = block.tracks_[c].P_smooth[0];
      e.started = true;
    }
  }
}

void SingerSmoother::ForEachBlock(const std::function<void(const SingerBlock&)>& visit) const {
  const std::size_t n = series_.rows(), nb = blocks();
  SingerBlock block = NewBlock();
  std::vector<track::SingerStep> steps;
  for (std::size_t b = 0; b < nb; ++b) {
    block.begin_ = b * block_rows_;
    block.end_ = std::min(n, block.begin_ + block_rows_);
    BlockSteps(b, &steps);
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (Recompute(b, c, steps, &block) && summary_.smoothed) Smooth(b, c, steps, &block);
    }
    visit(block);
  }
}

std::size_t SingerSmoother::EvaluationRow(std::size_t column, double t_s) const {
  RK_CHECK(summary_.stats[column].updates > 0, "EvaluateSinger on a column without measurements");
  return EvaluationRowOf(series_.t_s, summary_.stats[column].first_row, t_s);
}

void SingerSmoother::Evaluate(const SingerBlock& block, std::size_t column, double t_s, Eigen::Vector3d* x,
                              Eigen::Matrix3d* P) const {
  const std::size_t row = EvaluationRow(column, t_s);
  RK_CHECK(row >= block.begin() && row < block.end(), "SingerSmoother::Evaluate outside its block");
  EvaluateOn(TrackView{block.tracks_[column], block.begin(), summary_.stats[column], summary_.smoothed},
             series_.t_s, t_s, x, P);
}

bool SingerBlock::At(std::size_t column, std::size_t row, Eigen::Vector3d* x, Eigen::Matrix3d* P) const {
  RK_CHECK(row >= begin_ && row < end_, "SingerBlock::At outside its block");
  return TrackView{tracks_[column], begin_, (*stats_)[column], smoothed_}.At(row, x, P);
}

std::size_t MaskByStatus(const io::CsvTable& table, Series* series, std::size_t min_samples) {
  const int c_status = table.Column("status");
  std::size_t masked = 0;
  const auto nc = series->values.cols();
  if (c_status >= 0) {
    for (std::size_t r = 0; r < table.rows(); ++r) {
      const std::string_view s = table.Cell(r, c_status);
      bool measurement = true;
      if (s.empty() || s == "ok" || s == "reacquired") {
        measurement = true;
      } else if (s == "predicted" || s == "lost" || s == "invalid") {
        measurement = false;
      } else {
        bool numeric = true;
        for (char ch : s) numeric = numeric && ((ch >= '0' && ch <= '9') || ch == '-' || ch == '+');
        if (!numeric) {
          throw table.CellError(r, c_status,
                                "unknown status '" + std::string(s) +
                                    "' (expected a device code, or ok, reacquired, predicted, lost, invalid)");
        }
        measurement = table.Int(r, c_status) == 0;
      }
      if (measurement) continue;
      bool had = false;
      for (Eigen::Index c = 0; c < nc; ++c) {
        double& v = series->values(static_cast<Eigen::Index>(r), c);
        if (std::isfinite(v)) had = true;
        v = kNaN;
      }
      if (had) ++masked;
    }
  }
  std::size_t with_value = 0;
  for (Eigen::Index r = 0; r < series->values.rows(); ++r) {
    bool any = false;
    for (Eigen::Index c = 0; c < nc; ++c) any = any || std::isfinite(series->values(r, c));
    if (any) ++with_value;
  }
  if (with_value < min_samples) {
    throw TooFewSamplesError(table.name(),
                    "needs at least " + std::to_string(min_samples) + " samples with values (status ok), has " +
                        std::to_string(with_value));
  }
  return masked;
}

std::vector<double> ColumnUnitsToInternal(const std::vector<double>& values, const Series& series,
                                          const std::string& option) {
  const std::size_t nc = series.columns.size();
  if (values.empty()) return values;
  if (values.size() != 1 && values.size() != nc) {
    throw UsageError(option + ": give one value or one per column (" + std::to_string(nc) + "), got " +
                     std::to_string(values.size()));
  }
  std::vector<double> out(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const double v = values.size() == 1 ? values[0] : values[c];
    out[c] = series.is_angle[c] ? geo::DegToRad(v) : v;
  }
  return out;
}

bool AngleColumnIs360(const std::string& column, std::span<const double> values_rad) {
  if (column.rfind("az", 0) == 0 || column.rfind("yaw", 0) == 0) return true;
  bool negative = false, above = false;
  for (double v : values_rad) {
    if (!std::isfinite(v)) continue;
    negative = negative || v < 0.0;
    above = above || v > geo::kPi;
  }
  return above && !negative;
}

std::vector<bool> AngleColumnsIn360(const Series& series) {
  std::vector<bool> is360(series.columns.size(), false);
  for (std::size_t c = 0; c < series.columns.size(); ++c) {
    if (!series.is_angle[c]) continue;
    const Eigen::Index col = static_cast<Eigen::Index>(c);
    is360[c] = AngleColumnIs360(series.columns[c], std::span<const double>(series.values.col(col).data(),
                                                                           series.rows()));
  }
  return is360;
}

nlohmann::json SingerSeriesSummary::ColumnsJson(const Series& series, bool counts) const {
  io::Json j = io::Json::object();
  for (std::size_t c = 0; c < stats.size(); ++c) {
    const SingerColumnStats& st = stats[c];
    const double u = series.is_angle[c] ? geo::RadToDeg(1.0) : 1.0;
    io::Json col = {{"updates", st.updates},
                    {"meas_sigma", st.meas_sigma * u},
                    {"meas_sigma_estimated", st.meas_sigma_estimated},
                    {"accel_sigma", st.accel_sigma * u},
                    {"nis_mean", std::isfinite(st.nis_mean) ? io::Json(st.nis_mean) : io::Json(nullptr)}};
    if (counts) {
      col["missing"] = st.missing;
      col["nis_count"] = st.nis_count;
    }
    j[series.columns[c]] = col;
  }
  return j;
}

nlohmann::json SingerSeriesSummary::SummaryJson(const Series& series) const {
  const io::Json columns = ColumnsJson(series, false);
  io::Json nis = io::Json::object();
  for (const auto& [name, col] : columns.items()) nis[name] = col["nis_mean"];
  return {{"nis_mean", nis}, {"rows_lost", rows_lost}};
}

nlohmann::json SingerSeriesSummary::ToJson(const Series& series, double maneuver_time_s) const {
  io::Json j;
  j["smoothed"] = smoothed;
  j["maneuver_time_s"] = maneuver_time_s;
  j["rows"] = rows;
  j["rows_ok"] = rows_ok;
  j["rows_predicted"] = rows_predicted;
  j["rows_lost"] = rows_lost;
  j["columns"] = ColumnsJson(series, true);
  j["summary"] = SummaryJson(series);
  return j;
}

}  // namespace rk::filter

namespace rk::filter {

io::RunSummary SingerSeriesSummary::Summary(const Series& series, double maneuver_time_s) const {
  io::RunSummary s;
  s.CountRows(RowStatus::kOk, rows_ok);
  s.CountRows(RowStatus::kPredicted, rows_predicted);
  s.CountRows(RowStatus::kLost, rows_lost);
  if (rows_lost > 0) {
    s.Flag("rows_lost", std::to_string(rows_lost) + " of " + std::to_string(rows) +
                            " rows before any column's first value have no estimate (status lost)");
  }
  if (rows > 0) {
    s.AddFigure("rows ok", static_cast<double>(rows_ok) / static_cast<double>(rows), "fraction",
                std::to_string(rows_ok) + " of " + std::to_string(rows));
  }
  s.details = ToJson(series, maneuver_time_s);
  return s;
}

}  // namespace rk::filter

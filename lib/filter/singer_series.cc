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

struct ForwardInput {
  const std::vector<double>* t_s;
  const std::vector<double>* z;  // NaN = no measurement
  bool angle;
  double a, R, vel_sigma;
  const std::vector<track::SingerStep>* steps;  // [r]: the step from row r − 1 to r (shared by all passes)
};

// Kalman forward pass of one column; fills `tr` (x/P pred/filt) and `st` (counts, NIS) when
// given. Returns the negative log-likelihood of the innovations after the first update,
// Σ (ln S + ν²/S) / 2.
double ForwardPass(const ForwardInput& in, double accel_sigma, SingerTrack* tr, SingerColumnStats* st) {
  const std::vector<double>& z = *in.z;
  const std::size_t n = z.size();
  const double q = 2.0 * in.a * accel_sigma * accel_sigma;
  if (tr) {
    tr->x_pred.assign(n, Eigen::Vector3d::Zero());
    tr->x_filt.assign(n, Eigen::Vector3d::Zero());
    tr->P_pred.assign(n, Eigen::Matrix3d::Zero());
    tr->P_filt.assign(n, Eigen::Matrix3d::Zero());
  }
  bool started = false;
  double nis_sum = 0.0, nll = 0.0;
  std::size_t nis_count = 0, updates = 0, missing = 0, first_row = 0;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  for (std::size_t r = 0; r < n; ++r) {
    const bool have = std::isfinite(z[r]);
    if (!started) {
      if (!have) continue;
      started = true;
      first_row = r;
      x << z[r], 0.0, 0.0;
      P.setZero();
      P(0, 0) = in.R;
      P(1, 1) = in.vel_sigma * in.vel_sigma;
      P(2, 2) = accel_sigma * accel_sigma;
      ++updates;
    } else {
      const track::SingerStep& step = (*in.steps)[r];
      const Eigen::Matrix3d& Phi = step.transition();
      x = Phi * x;
      P = Phi * P * Phi.transpose() + step.ProcessNoise(q);
      P = 0.5 * (P + P.transpose()).eval();
    }
    if (tr) {
      tr->x_pred[r] = x;
      tr->P_pred[r] = P;
    }
    if (r != first_row) {
      if (have) {
        const double nu = in.angle ? geo::WrapPi(z[r] - x(0)) : z[r] - x(0);
        const double S = P(0, 0) + in.R;
        const Eigen::Vector3d K = P.col(0) / S;
        x += K * nu;
        Eigen::Matrix3d IKH = Eigen::Matrix3d::Identity();
        IKH.col(0) -= K;
        P = IKH * P * IKH.transpose() + (K * K.transpose()) * in.R;
        P = 0.5 * (P + P.transpose()).eval();
        nis_sum += nu * nu / S;
        nll += 0.5 * (std::log(S) + nu * nu / S);
        ++nis_count;
        ++updates;
      } else {
        ++missing;
      }
    }
    if (tr) {
      tr->x_filt[r] = x;
      tr->P_filt[r] = P;
    }
  }
  if (st) {
    st->updates = updates;
    st->missing = missing;
    st->first_row = first_row;
    st->nis_count = nis_count;
    st->nis_mean = nis_count ? nis_sum / static_cast<double>(nis_count) : kNaN;
  }
  return nll;
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
  const SingerTrack& tr = tracks[column];
  if (stats[column].updates == 0 || row < stats[column].first_row) return false;
  if (smoothed) {
    *x = tr.x_smooth[row];
    *P = tr.P_smooth[row];
  } else {
    *x = tr.x_filt[row];
    *P = tr.P_filt[row];
  }
  return true;
}

double EstimateNoiseSigma(const std::vector<double>& values, bool angle, int order) {
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
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  const std::size_t nc = series.columns.size();
  const std::size_t n = series.rows();
  auto check_len = [&](std::size_t len, const char* what) {
    if (len > 1 && len != nc) {
      throw UsageError(std::string(what) + ": give one value or one per column (" + std::to_string(nc) +
                       "), got " + std::to_string(len));
    }
  };
  check_len(options.accel_sigma.size(), "--accel-sigma");
  check_len(options.meas_sigma.size(), "--meas-sigma");

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
    const auto col = static_cast<Eigen::Index>(c);
    const bool angle = series.is_angle[c];
    SingerColumnStats& st = res.stats[c];
    SingerTrack& tr = res.tracks[c];
    std::vector<double> z(n);
    for (std::size_t r = 0; r < n; ++r) z[r] = series.values(static_cast<Eigen::Index>(r), col);

    double accel_sigma = options.accel_sigma.empty() ? DefaultAccelSigma(series.columns[c])
                                                     : PerColumn(options.accel_sigma, c);
    if (!std::isfinite(accel_sigma)) {
      throw UsageError("--accel-sigma is needed for column '" + series.columns[c] +
                       "' (no default for its unit; defaults exist for _m, _deg and _px)");
    }
    // Scale of the data: for the σ_z floor and the velocity prior.
    double max_rate = 0.0, scale = 0.0;
    {
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
    }
    if (options.meas_sigma.empty()) {
      double s = EstimateNoiseSigma(z, angle);
      if (!std::isfinite(s)) s = 0.0;
      st.meas_sigma = std::max(s, kMeasSigmaFloorRel * scale + kMeasSigmaFloorAbs);
      st.meas_sigma_estimated = true;
    } else {
      st.meas_sigma = PerColumn(options.meas_sigma, c);
    }
    const double R = st.meas_sigma * st.meas_sigma;
    tr.a_per_s = a;
    const double vel_sigma = std::max(2.0 * max_rate, 10.0 * st.meas_sigma);

    // σ_m: given, or chosen by maximum likelihood over a grid around the unit default.
    const ForwardInput in{&series.t_s, &z, angle, a, R, vel_sigma, &steps};
    if (options.accel_sigma.empty() && options.auto_accel_sigma) {
      double best = std::numeric_limits<double>::infinity();
      const double center = accel_sigma;
      for (int k = kAutoAccelGridLow; k <= kAutoAccelGridHigh; ++k) {
        const double cand = center * std::pow(2.0, 0.5 * k);
        const double nll = ForwardPass(in, cand, nullptr, nullptr);
        if (nll < best) {
          best = nll;
          accel_sigma = cand;
        }
      }
      st.accel_sigma_selected = true;
    }
    st.accel_sigma = accel_sigma;
    tr.q = 2.0 * a * accel_sigma * accel_sigma;
    ForwardPass(in, accel_sigma, &tr, &st);
    const bool started = st.updates > 0;

    // Backward pass.
    if (options.smooth && started) {
      tr.x_smooth = tr.x_filt;
      tr.P_smooth = tr.P_filt;
      for (std::size_t r = n - 1; r-- > st.first_row;) {
        const Eigen::Matrix3d& Phi = steps[r + 1].transition();
        // C = P_f Φᵀ P_p⁻¹  ⇔  Cᵀ = P_p⁻¹ Φ P_f (P symmetric).
        const Eigen::Matrix3d Ct = tr.P_pred[r + 1].ldlt().solve(Phi * tr.P_filt[r]);
        const Eigen::Matrix3d C = Ct.transpose();
        tr.x_smooth[r] = tr.x_filt[r] + C * (tr.x_smooth[r + 1] - tr.x_pred[r + 1]);
        Eigen::Matrix3d Ps = tr.P_filt[r] + C * (tr.P_smooth[r + 1] - tr.P_pred[r + 1]) * Ct;
        tr.P_smooth[r] = 0.5 * (Ps + Ps.transpose());
      }
    }
  }

  res.status.resize(n, SingerRowStatus::kLost);
  for (std::size_t r = 0; r < n; ++r) {
    bool measured = false, estimated = false;
    for (std::size_t c = 0; c < nc; ++c) {
      if (std::isfinite(series.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)))) measured = true;
      if (res.stats[c].updates > 0 && r >= res.stats[c].first_row) estimated = true;
    }
    if (measured) {
      res.status[r] = SingerRowStatus::kOk;
      ++res.rows_ok;
    } else if (estimated) {
      res.status[r] = SingerRowStatus::kPredicted;
      ++res.rows_predicted;
    } else {
      ++res.rows_lost;
    }
  }
  return res;
}

void EvaluateSinger(const SingerSeriesResult& result, const Series& series, std::size_t column, double t,
                    Eigen::Vector3d* x_out, Eigen::Matrix3d* P_out) {
  const SingerTrack& tr = result.tracks[column];
  const SingerColumnStats& st = result.stats[column];
  RK_CHECK(st.updates > 0, "EvaluateSinger on a column without measurements");
  const double a = tr.a_per_s;
  const auto& ts = series.t_s;
  const std::size_t first = st.first_row;
  const std::size_t n = ts.size();
  Eigen::Vector3d x;
  Eigen::Matrix3d P;
  if (t <= ts[first]) {
    result.At(column, first, &x, &P);
    const double tau = ts[first] - t;
    if (tau > 0.0) {  // backward prediction
      const Eigen::Matrix3d Phi_inv = track::SingerTransition(tau, a).inverse();
      x = Phi_inv * x;
      P = Phi_inv * P * Phi_inv.transpose() + track::SingerProcessNoise(tau, a, tr.q);
    }
  } else {
    // Last row k with t_k ≤ t.
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin()) - 1;
    const double tau = t - ts[k];
    if (tau == 0.0) {
      result.At(column, k, &x, &P);
    } else if (k + 1 >= n || !result.smoothed) {
      // After the last row (or filter only): predict forward from row k.
      result.At(column, k, &x, &P);
      const Eigen::Matrix3d Phi = track::SingerTransition(tau, a);
      x = Phi * x;
      P = Phi * P * Phi.transpose() + track::SingerProcessNoise(tau, a, tr.q);
    } else {
      // Inserted step at t between rows k and k+1, then one RTS step from k+1.
      const Eigen::Matrix3d Phi1 = track::SingerTransition(tau, a);
      const Eigen::Matrix3d Phi2 = track::SingerTransition(ts[k + 1] - t, a);
      const Eigen::Vector3d xp = Phi1 * tr.x_filt[k];
      Eigen::Matrix3d Pp = Phi1 * tr.P_filt[k] * Phi1.transpose() + track::SingerProcessNoise(tau, a, tr.q);
      Pp = 0.5 * (Pp + Pp.transpose()).eval();
      const Eigen::Matrix3d Ct = tr.P_pred[k + 1].ldlt().solve(Phi2 * Pp);
      x = xp + Ct.transpose() * (tr.x_smooth[k + 1] - tr.x_pred[k + 1]);
      P = Pp + Ct.transpose() * (tr.P_smooth[k + 1] - tr.P_pred[k + 1]) * Ct;
    }
  }
  *x_out = x;
  *P_out = 0.5 * (P + P.transpose());
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

bool AngleColumnIs360(const std::string& column, const std::vector<double>& values_rad) {
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
    const std::vector<double> v(series.values.col(col).data(), series.values.col(col).data() + series.values.rows());
    is360[c] = AngleColumnIs360(series.columns[c], v);
  }
  return is360;
}

nlohmann::json SingerSeriesResult::ColumnsJson(const Series& series, bool counts) const {
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

nlohmann::json SingerSeriesResult::SummaryJson(const Series& series) const {
  const io::Json columns = ColumnsJson(series, false);
  io::Json nis = io::Json::object();
  for (const auto& [name, col] : columns.items()) nis[name] = col["nis_mean"];
  return {{"nis_mean", nis}, {"rows_lost", rows_lost}};
}

nlohmann::json SingerSeriesResult::ToJson(const Series& series, double maneuver_time_s) const {
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

// Time-series interpolation with gaps; method notes in interp.h.
#include "track/interp.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geo/angles.h"

namespace rk::track {

// Relative slack on max_gap_s: logged times such as 0.7 and 0.8 differ by
// 0.10000000000000009 in binary, which must count as a 0.1 s interval.
constexpr double kGapSlack = 1e-9;

bool ParseInterpMethod(const std::string& name, InterpMethod* method) {
  if (name == "linear") {
    *method = InterpMethod::kLinear;
  } else if (name == "cubic") {
    *method = InterpMethod::kCubic;
  } else if (name == "local-quadratic") {
    *method = InterpMethod::kLocalQuadratic;
  } else if (name == "local-cubic") {
    *method = InterpMethod::kLocalCubic;
  } else {
    return false;
  }
  return true;
}

std::string InterpMethodName(InterpMethod method) {
  switch (method) {
    case InterpMethod::kLinear:
      return "linear";
    case InterpMethod::kCubic:
      return "cubic";
    case InterpMethod::kLocalQuadratic:
      return "local-quadratic";
    case InterpMethod::kLocalCubic:
      return "local-cubic";
  }
  return "?";
}

std::string InterpStatusName(InterpStatus status) {
  switch (status) {
    case InterpStatus::kOk:
      return "ok";
    case InterpStatus::kOutside:
      return "outside";
    case InterpStatus::kGap:
      return "gap";
    case InterpStatus::kUnusable:
      return "unusable";
  }
  return "?";
}

bool InterpOptions::Check(std::string* why) const {
  if (!(max_gap_s > 0.0)) {
    *why = "maximum gap must be > 0 s (got " + std::to_string(max_gap_s) + ")";
    return false;
  }
  if (window < 2 || window > 50) {
    *why = "local fit window must be in [2, 50] samples per side (got " + std::to_string(window) + ")";
    return false;
  }
  return true;
}

std::vector<std::optional<double>> UnwrapAngles(const std::vector<std::optional<double>>& values_rad) {
  std::vector<std::optional<double>> out(values_rad.size());
  std::optional<double> prev;
  for (std::size_t i = 0; i < values_rad.size(); ++i) {
    if (!values_rad[i] || !std::isfinite(*values_rad[i])) continue;
    double v = *values_rad[i];
    if (prev) v = *prev + geo::WrapPi(v - *prev);
    out[i] = v;
    prev = v;
  }
  return out;
}

std::size_t MergeDuplicateTimes(std::vector<double>* t_s, std::vector<std::optional<double>>* values) {
  if (t_s->size() != values->size()) throw std::invalid_argument("MergeDuplicateTimes: sizes differ");
  // Nothing to merge (the usual log): no copy of a long log.
  if (std::adjacent_find(t_s->begin(), t_s->end()) == t_s->end()) return 0;
  std::vector<double> t_out;
  std::vector<std::optional<double>> v_out;
  std::size_t i = 0;
  while (i < t_s->size()) {
    std::size_t j = i;
    double sum = 0.0;
    int n = 0;
    while (j < t_s->size() && (*t_s)[j] == (*t_s)[i]) {
      if ((*values)[j] && std::isfinite(*(*values)[j])) {
        sum += *(*values)[j];
        ++n;
      }
      ++j;
    }
    t_out.push_back((*t_s)[i]);
    v_out.push_back(n > 0 ? std::optional<double>(sum / n) : std::nullopt);
    i = j;
  }
  std::size_t removed = t_s->size() - t_out.size();
  *t_s = std::move(t_out);
  *values = std::move(v_out);
  return removed;
}

TimeSeriesInterpolator::TimeSeriesInterpolator(std::vector<double> t_s,
                                               const std::vector<std::optional<double>>& values,
                                               const InterpOptions& options)
    : opt_(options), n_samples_(t_s.size()) {
  std::string why;
  if (!opt_.Check(&why)) throw std::invalid_argument("interpolation options: " + why);
  if (values.size() != t_s.size())
    throw std::invalid_argument("interpolation: times and values differ in length");
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    if (!std::isfinite(t_s[i]))
      throw std::invalid_argument("interpolation: time " + std::to_string(i) + " not finite");
    if (i > 0 && !(t_s[i] > t_s[i - 1])) {
      throw std::invalid_argument("interpolation: times not strictly increasing at sample " +
                                  std::to_string(i));
    }
  }
  // Unwrapped angles are a new vector; other values are read where they are (no copy of a long log).
  std::vector<std::optional<double>> unwrapped;
  if (opt_.angle) unwrapped = UnwrapAngles(values);
  const std::vector<std::optional<double>>& v = opt_.angle ? unwrapped : values;
  std::size_t usable = 0;
  for (const std::optional<double>& x : v) usable += x && std::isfinite(*x) ? 1 : 0;
  t_.reserve(usable);
  v_.reserve(usable);
  link_.reserve(usable);
  segment_of_.reserve(usable);
  bool unusable_between = false;
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    if (!v[i] || !std::isfinite(*v[i])) {
      unusable_between = true;
      continue;
    }
    if (!t_.empty()) {
      InterpStatus link = InterpStatus::kOk;
      if (unusable_between) {
        link = InterpStatus::kUnusable;
      } else if (t_s[i] - t_.back() > opt_.max_gap_s * (1.0 + kGapSlack)) {
        link = InterpStatus::kGap;
      }
      link_.push_back(link);
      if (link != InterpStatus::kOk) {
        segment_end_.push_back(t_.size() - 1);
        segment_begin_.push_back(t_.size());
      }
    } else {
      segment_begin_.push_back(0);
    }
    segment_of_.push_back(segment_begin_.size() - 1);
    t_.push_back(t_s[i]);
    v_.push_back(*v[i]);
    unusable_between = false;
  }
  if (!t_.empty()) segment_end_.push_back(t_.size() - 1);
}

double TimeSeriesInterpolator::first_time() const { return t_.empty() ? std::nan("") : t_.front(); }
double TimeSeriesInterpolator::last_time() const { return t_.empty() ? std::nan("") : t_.back(); }

std::optional<std::pair<double, double>> TimeSeriesInterpolator::Bracket(double t) const {
  if (t_.size() < 2 || !std::isfinite(t) || t < t_.front() || t > t_.back()) return std::nullopt;
  std::size_t k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  if (k + 1 >= t_.size()) k = t_.size() - 2;
  return std::make_pair(t_[k], t_[k + 1]);
}

InterpValue TimeSeriesInterpolator::At(double t) const {
  InterpValue out;
  if (t_.empty() || !std::isfinite(t) || t < t_.front() || t > t_.back()) return out;  // kOutside
  // k: last usable sample with t_k <= t.
  std::size_t k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  const std::size_t seg = segment_of_[k];
  const std::size_t s0 = segment_begin_[seg], s1 = segment_end_[seg];
  if (t == t_[k]) {
    if (s0 == s1) {  // an isolated sample answers only its own time
      out.status = InterpStatus::kOk;
      out.value = v_[k];
      return out;
    }
    if (k == s1) k = s1 - 1;  // evaluate on the segment's last interval
  } else if (link_[k] != InterpStatus::kOk) {
    out.status = link_[k];
    return out;
  }
  out.status = InterpStatus::kOk;
  switch (opt_.method) {
    case InterpMethod::kLinear:
      out.value = Linear(k, t);
      break;
    case InterpMethod::kCubic:
      out.value = Lagrange(s0, s1, k, t);
      break;
    case InterpMethod::kLocalQuadratic:
      out.value = LocalPolynomial(s0, s1, k, t, 2);
      break;
    case InterpMethod::kLocalCubic:
      out.value = LocalPolynomial(s0, s1, k, t, 3);
      break;
  }
  return out;
}

double TimeSeriesInterpolator::Linear(std::size_t k, double t) const {
  const double u = (t - t_[k]) / (t_[k + 1] - t_[k]);
  return v_[k] + (v_[k + 1] - v_[k]) * u;
}

// Index window [lo, hi] of `want_lo`..`want_hi` shifted inward into [s0, s1].
static void ClampWindow(std::ptrdiff_t want_lo, std::ptrdiff_t want_hi, std::size_t s0, std::size_t s1,
                        std::size_t* lo, std::size_t* hi) {
  const auto a = static_cast<std::ptrdiff_t>(s0), b = static_cast<std::ptrdiff_t>(s1);
  if (want_lo < a) {
    want_hi += a - want_lo;
    want_lo = a;
  }
  if (want_hi > b) {
    want_lo -= want_hi - b;
    want_hi = b;
  }
  *lo = static_cast<std::size_t>(std::max(want_lo, a));
  *hi = static_cast<std::size_t>(want_hi);
}

double TimeSeriesInterpolator::Lagrange(std::size_t s0, std::size_t s1, std::size_t k, double t) const {
  std::size_t lo = 0, hi = 0;
  ClampWindow(static_cast<std::ptrdiff_t>(k) - 1, static_cast<std::ptrdiff_t>(k) + 2, s0, s1, &lo, &hi);
  double sum = 0.0;
  for (std::size_t i = lo; i <= hi; ++i) {
    double w = 1.0;
    for (std::size_t j = lo; j <= hi; ++j) {
      if (j != i) w *= (t - t_[j]) / (t_[i] - t_[j]);
    }
    sum += w * v_[i];
  }
  return sum;
}

double TimeSeriesInterpolator::LocalPolynomial(std::size_t s0, std::size_t s1, std::size_t k, double t,
                                               int max_degree) const {
  std::size_t lo = 0, hi = 0;
  const auto w = static_cast<std::ptrdiff_t>(opt_.window);
  ClampWindow(static_cast<std::ptrdiff_t>(k) + 1 - w, static_cast<std::ptrdiff_t>(k) + w, s0, s1, &lo, &hi);
  const std::size_t m = hi - lo + 1;
  const int degree = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(max_degree), m - 1));
  // Centred and scaled abscissa keeps the normal equations well conditioned.
  const double scale = std::max(t_[hi] - t_[lo], 1e-300);
  Eigen::MatrixXd a(m, degree + 1);
  Eigen::VectorXd y(m);
  for (std::size_t i = 0; i < m; ++i) {
    const double tau = (t_[lo + i] - t) / scale;
    double p = 1.0;
    for (int d = 0; d <= degree; ++d) {
      a(static_cast<Eigen::Index>(i), d) = p;
      p *= tau;
    }
    // Subtract the interval's left value to keep the fit in small numbers.
    y(static_cast<Eigen::Index>(i)) = v_[lo + i] - v_[k];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(y);
  return v_[k] + c(0);
}

}  // namespace rk::track

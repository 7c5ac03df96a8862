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

namespace {

std::vector<double> NanForMissing(const std::vector<std::optional<double>>& values) {
  std::vector<double> out(values.size(), std::nan(""));
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i]) out[i] = *values[i];
  }
  return out;
}

std::vector<std::optional<double>> MissingForNan(const std::vector<double>& values) {
  std::vector<std::optional<double>> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isfinite(values[i])) out[i] = values[i];
  }
  return out;
}

}  // namespace

void UnwrapAnglesInPlace(std::vector<double>* values_rad) {
  std::optional<double> prev;
  for (double& x : *values_rad) {
    if (!std::isfinite(x)) continue;
    if (prev) x = *prev + geo::WrapPi(x - *prev);
    prev = x;
  }
}

std::vector<std::optional<double>> UnwrapAngles(const std::vector<std::optional<double>>& values_rad) {
  std::vector<double> v = NanForMissing(values_rad);
  UnwrapAnglesInPlace(&v);
  return MissingForNan(v);
}

std::size_t MergeDuplicateTimes(std::vector<double>* t_s, const std::vector<std::vector<double>*>& columns) {
  for (const std::vector<double>* c : columns) {
    if (c->size() != t_s->size()) throw std::invalid_argument("MergeDuplicateTimes: sizes differ");
  }
  // Nothing to merge (the usual log): nothing moved.
  if (std::adjacent_find(t_s->begin(), t_s->end()) == t_s->end()) return 0;
  std::vector<double>& t = *t_s;
  std::size_t out = 0, i = 0;
  while (i < t.size()) {
    std::size_t j = i;
    while (j < t.size() && t[j] == t[i]) ++j;
    for (std::vector<double>* c : columns) {
      double sum = 0.0;
      int n = 0;
      for (std::size_t k = i; k < j; ++k) {
        if (std::isfinite((*c)[k])) {
          sum += (*c)[k];
          ++n;
        }
      }
      (*c)[out] = n > 0 ? sum / n : std::nan("");
    }
    t[out] = t[i];
    ++out;
    i = j;
  }
  const std::size_t removed = t.size() - out;
  t.resize(out);
  t.shrink_to_fit();
  for (std::vector<double>* c : columns) {
    c->resize(out);
    c->shrink_to_fit();
  }
  return removed;
}

std::size_t MergeDuplicateTimes(std::vector<double>* t_s, std::vector<std::optional<double>>* values) {
  if (t_s->size() != values->size()) throw std::invalid_argument("MergeDuplicateTimes: sizes differ");
  if (std::adjacent_find(t_s->begin(), t_s->end()) == t_s->end()) return 0;
  std::vector<double> v = NanForMissing(*values);
  const std::size_t removed = MergeDuplicateTimes(t_s, std::vector<std::vector<double>*>{&v});
  *values = MissingForNan(v);
  return removed;
}

TimeSeriesInterpolator::TimeSeriesInterpolator(std::vector<double> t_s,
                                               const std::vector<std::optional<double>>& values,
                                               const InterpOptions& options)
    : TimeSeriesInterpolator(std::make_shared<const std::vector<double>>(std::move(t_s)),
                             NanForMissing(values),  // a length that differs is refused below
                             options) {}

TimeSeriesInterpolator::TimeSeriesInterpolator(std::shared_ptr<const std::vector<double>> t_s,
                                               std::vector<double> values, const InterpOptions& options)
    : opt_(options), n_samples_(t_s->size()) {
  std::string why;
  if (!opt_.Check(&why)) throw std::invalid_argument("interpolation options: " + why);
  const std::vector<double>& t = *t_s;
  if (values.size() != t.size()) throw std::invalid_argument("interpolation: times and values differ in length");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i])) throw std::invalid_argument("interpolation: time " + std::to_string(i) + " not finite");
    if (i > 0 && !(t[i] > t[i - 1])) {
      throw std::invalid_argument("interpolation: times not strictly increasing at sample " + std::to_string(i));
    }
  }
  if (opt_.angle) UnwrapAnglesInPlace(&values);
  std::size_t usable = 0;
  for (const double x : values) usable += std::isfinite(x) ? 1 : 0;
  // One pass over the samples: the usable ones kept (in place; the times as they are, shared, when every
  // sample is usable) and the segments found: a break where an unusable sample lies between two usable
  // ones, or where they are further apart than max_gap_s.
  const bool all_usable = usable == values.size();
  std::shared_ptr<std::vector<double>> kept;
  if (!all_usable) {
    kept = std::make_shared<std::vector<double>>();
    kept->reserve(usable);
  }
  std::size_t n = 0, prev = 0;  // usable samples so far, index of the last one
  bool unusable_between = false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(values[i])) {
      unusable_between = true;
      continue;
    }
    if (n == 0) {
      segment_begin_.push_back(0);
    } else {
      InterpStatus link = InterpStatus::kOk;
      if (unusable_between) {
        link = InterpStatus::kUnusable;
      } else if (t[i] - t[prev] > opt_.max_gap_s * (1.0 + kGapSlack)) {
        link = InterpStatus::kGap;
      }
      if (link != InterpStatus::kOk) {
        segment_end_.push_back(n - 1);
        segment_break_.push_back(link);
        segment_begin_.push_back(n);
      }
    }
    if (!all_usable) {
      kept->push_back(t[i]);
      values[n] = values[i];
    }
    unusable_between = false;
    prev = i;
    ++n;
  }
  if (n > 0) {
    segment_end_.push_back(n - 1);
    segment_break_.push_back(InterpStatus::kOutside);  // after the last segment: nothing follows
  }
  if (all_usable) {
    times_ = std::move(t_s);
  } else {
    values.resize(n);
    values.shrink_to_fit();
    times_ = std::move(kept);
  }
  v_ = std::move(values);
}

std::size_t TimeSeriesInterpolator::HeldBytes() const {
  return (times_ ? times_->capacity() * sizeof(double) : 0) + v_.capacity() * sizeof(double) +
         (segment_begin_.capacity() + segment_end_.capacity()) * sizeof(std::size_t) + segment_break_.capacity();
}

double TimeSeriesInterpolator::first_time() const { return v_.empty() ? std::nan("") : times_->front(); }
double TimeSeriesInterpolator::last_time() const { return v_.empty() ? std::nan("") : times_->back(); }

std::optional<std::pair<double, double>> TimeSeriesInterpolator::Bracket(double t) const {
  if (v_.empty()) return std::nullopt;
  const std::vector<double>& t_ = *times_;
  if (t_.size() < 2 || !std::isfinite(t) || t < t_.front() || t > t_.back()) return std::nullopt;
  std::size_t k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  if (k + 1 >= t_.size()) k = t_.size() - 2;
  return std::make_pair(t_[k], t_[k + 1]);
}

InterpValue TimeSeriesInterpolator::At(double t) const {
  InterpValue out;
  if (v_.empty()) return out;  // kOutside
  const std::vector<double>& t_ = *times_;
  if (t_.empty() || !std::isfinite(t) || t < t_.front() || t > t_.back()) return out;  // kOutside
  // k: last usable sample with t_k <= t.
  std::size_t k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  const std::size_t seg =
      static_cast<std::size_t>(std::upper_bound(segment_begin_.begin(), segment_begin_.end(), k) - segment_begin_.begin()) - 1;
  const std::size_t s0 = segment_begin_[seg], s1 = segment_end_[seg];
  if (t == t_[k]) {
    if (s0 == s1) {  // an isolated sample answers only its own time
      out.status = InterpStatus::kOk;
      out.value = v_[k];
      return out;
    }
    if (k == s1) k = s1 - 1;  // evaluate on the segment's last interval
  } else if (k == s1) {  // t lies between this segment's last sample and the next segment
    out.status = segment_break_[seg];
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
  const std::vector<double>& t_ = *times_;
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
  const std::vector<double>& t_ = *times_;
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
  const std::vector<double>& t_ = *times_;
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

// Error statistics; definitions in stats.h.
#include "analysis/stats.h"

#include <algorithm>
#include <cmath>

namespace rk::analysis {

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double h = (static_cast<double>(values.size()) - 1.0) * std::clamp(p, 0.0, 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

std::optional<ErrorStats> ComputeErrorStats(const std::vector<double>& errors) {
  if (errors.empty()) return std::nullopt;
  ErrorStats s;
  s.n = errors.size();
  s.max = *std::max_element(errors.begin(), errors.end());
  s.min = *std::min_element(errors.begin(), errors.end());
  double sum = 0.0, sum_sq = 0.0;
  for (double e : errors) {
    sum += e;
    sum_sq += e * e;
  }
  const double n = static_cast<double>(s.n);
  s.mean = sum / n;
  s.rms = std::sqrt(sum_sq / n);
  if (s.n >= 2) {
    double ss = 0.0;  // two-pass: no cancellation for a large mean
    for (double e : errors) ss += (e - s.mean) * (e - s.mean);
    s.std = std::sqrt(ss / (n - 1.0));
  } else {
    s.std = std::nan("");
  }
  std::vector<double> abs_e(errors.size());
  std::transform(errors.begin(), errors.end(), abs_e.begin(), [](double e) { return std::abs(e); });
  s.p95_abs = Percentile(std::move(abs_e), 0.95);
  return s;
}

}  // namespace rk::analysis

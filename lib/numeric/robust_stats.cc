#include "numeric/robust_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rk::numeric {
namespace {

double MedianInPlace(std::span<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m), v.end());
  double med = v[m];
  // The lower middle value is the largest of the ones nth_element put before v[m].
  if (v.size() % 2 == 0)
    med = 0.5 * (med + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m)));
  return med;
}

// Median, then the same median of |x − median| (overwrites v with the absolute deviations).
MedianMad MedianAndMadInPlace(std::span<double> v, double (*median)(std::span<double>)) {
  MedianMad out;
  out.median = median(v);
  for (double& x : v) x = std::abs(x - out.median);
  out.mad = median(v);
  return out;
}

}  // namespace

double Median(std::vector<double> values) { return MedianInPlace(values); }

MedianMad MedianAndMad(std::vector<double> values) { return MedianAndMadInPlace(values, MedianInPlace); }

double UpperMedianInPlace(std::span<double> values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

MedianMad UpperMedianAndMadInPlace(std::span<double> values) {
  return MedianAndMadInPlace(values, UpperMedianInPlace);
}

}  // namespace rk::numeric

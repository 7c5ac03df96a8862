// Summary statistics of an error series (rk-analyze compare; seed 000 Table 1
// reports max / min / mean / std of errors the same way).
//   mean = Σe/n;  std = sqrt(Σ(e − mean)² / (n − 1))  (sample standard
//   deviation, undefined for n < 2 → NaN);  rms = sqrt(Σe²/n);
//   p95_abs = 95th percentile of |e| by linear interpolation between order
//   statistics (Hyndman & Fan 1996 type 7, the default of R, NumPy and
//   Excel PERCENTILE.INC): with sorted x_0..x_{n−1}, h = (n − 1)·p,
//   P = x_⌊h⌋ + (h − ⌊h⌋)(x_⌊h⌋+1 − x_⌊h⌋).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace rk::analysis {

struct ErrorStats {
  std::size_t n = 0;
  double max = 0.0, min = 0.0, mean = 0.0;
  double std = 0.0;  // NaN when n < 2
  double rms = 0.0;
  double p95_abs = 0.0;
};

// nullopt for an empty series. Values must be finite.
std::optional<ErrorStats> ComputeErrorStats(const std::vector<double>& errors);

// Type-7 percentile of `values` (any order), p in [0, 1]; NaN if empty.
double Percentile(std::vector<double> values, double p);

}  // namespace rk::analysis

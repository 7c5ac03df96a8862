// Golden-section search for the minimum of a function unimodal on a bracket: the one implementation behind
// every "grid, then golden section in the best cell" minimisation (filter/noise_ml.cc's process-noise level,
// registration/radar_model.cc's closest approach of two 2-D plots' arcs).
#pragma once

#include <cmath>

namespace rk::numeric {

// Narrows [lo, hi] around the minimum of f until it is no wider than `tolerance` or after `max_iterations`
// narrowings, whichever comes first, and returns the bracket's middle. Two evaluations to start, one per
// narrowing; *evaluations (when given) is increased by their number.
template <class F>
double GoldenSectionMinimum(F&& f, double lo, double hi, double tolerance, int max_iterations,
                            int* evaluations = nullptr) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
  double fc = f(c), fd = f(d);
  int n = 2;
  for (int it = 0; it < max_iterations && hi - lo > tolerance; ++it) {
    if (fc < fd) {
      hi = d;
      d = c;
      fd = fc;
      c = hi - g * (hi - lo);
      fc = f(c);
    } else {
      lo = c;
      c = d;
      fc = fd;
      d = lo + g * (hi - lo);
      fd = f(d);
    }
    ++n;
  }
  if (evaluations != nullptr) *evaluations += n;
  return 0.5 * (lo + hi);
}

}  // namespace rk::numeric

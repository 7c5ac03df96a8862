// Helpers shared by lib/intersect's files (one definition for the module's unity batches).
#pragma once

#include <limits>
#include <utility>
#include <vector>

#include "numeric/robust_stats.h"

namespace rk::intersect::internal {

// numeric::UpperMedian (element n/2 of the sorted values), NaN for no values (a figure with nothing behind it).
inline double UpperMedianOrNaN(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  return numeric::UpperMedian(std::move(values));
}

}  // namespace rk::intersect::internal

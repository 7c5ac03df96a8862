// Medians and the median absolute deviation (MAD), the robust level and scale estimates of rangekit.
//   Median:       the middle value; for an even count the mean of the two middle ones. NaN if empty.
//   UpperMedian:  element n/2 of the sorted values (the upper of the two middle ones for an even count):
//                 always one of the samples, one selection instead of two. 0 if empty.
//   MAD:          the median (same convention) of |x − median|; × 1.4826 estimates σ of Gaussian data.
// The *InPlace forms reorder their argument (no copy: for per-frame work buffers); the MAD forms
// overwrite it with the absolute deviations.
#pragma once

#include <span>
#include <vector>

namespace rk::numeric {

struct MedianMad {
  double median = 0.0;
  double mad = 0.0;
};

double Median(std::vector<double> values);
MedianMad MedianAndMad(std::vector<double> values);

double UpperMedianInPlace(std::span<double> values);
inline double UpperMedian(std::vector<double> values) { return UpperMedianInPlace(values); }
MedianMad UpperMedianAndMadInPlace(std::span<double> values);

}  // namespace rk::numeric

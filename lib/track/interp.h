// Interpolation of a sampled time series to arbitrary query times, with gaps.
//
// Used for the turret log (50 Hz boresight angles → frame times), the laser
// range log (5 Hz → frame times, seed 001: "interpolate range to frame
// times") and for reference series in rk-analyze compare.
//
// Samples (t_i, v_i) have strictly increasing t_i; v_i may be missing (an
// unusable sample, e.g. a rangefinder device-error row). The usable samples
// are split into segments: two consecutive usable samples belong to the same
// segment when t_{k+1} − t_k ≤ max_gap_s AND no unusable sample lies between
// them. A query time t is answered only inside a segment (no extrapolation,
// never across a gap): t in [t_first, t_last] of one segment. Otherwise the
// status says why (outside the series, gap too long, unusable sample between).
//
// Methods (all evaluated with samples of the query's own segment only):
//   linear           v(t) = v_k + (v_{k+1} − v_k)(t − t_k)/(t_{k+1} − t_k).
//                    Exact for degree ≤ 1; error ≈ h² |v''| / 8.
//   cubic            4-point Lagrange interpolation through t_{k−1..k+2}
//                    (the stencil is shifted inward at segment ends; with
//                    fewer than 4 samples the degree drops). Passes through
//                    every sample; exact for degree ≤ 3; error ≈ 3h⁴|v''''|/128
//                    at mid-interval; white noise gain ≤ 1.
//   local-quadratic  least-squares quadratic fit over the 2·window samples
//                    nearest the interval that contains t (window per side,
//                    shifted inward at segment ends), evaluated at t. Does not
//                    pass through the samples: it averages white measurement
//                    noise (gain ≈ 0.5 for window 3) at the price of a bias
//                    ∝ h³|v'''| (the fit is exact for degree ≤ 2).
//                    Savitzky & Golay 1964 generalised to arbitrary t.
//   local-cubic      the same with a cubic: exact for degree ≤ 3, less noise
//                    reduction than local-quadratic for the same window.
// Angle series (options.angle): the values are first unwrapped (consecutive
// usable differences brought into (−π, π]) and interpolated on the unwrapped
// sequence; the returned value is unwrapped too — the caller wraps it
// (geo::WrapTwoPi for azimuth, geo::WrapPi for signed angles).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rk::track {

enum class InterpMethod { kLinear, kCubic, kLocalQuadratic, kLocalCubic };

// "linear" | "cubic" | "local-quadratic" | "local-cubic"; false if unknown.
bool ParseInterpMethod(const std::string& name, InterpMethod* method);
std::string InterpMethodName(InterpMethod method);

struct InterpOptions {
  InterpMethod method = InterpMethod::kLinear;
  // Longest interval (s) between consecutive usable samples that may be
  // interpolated across (with a 1e-9 relative slack for decimal time stamps);
  // > 0, +inf = no limit.
  double max_gap_s = std::numeric_limits<double>::infinity();
  // local-quadratic / local-cubic: number of samples used on each side of the query
  // interval (total 2·window), [2, 50].
  int window = 3;
  // Values are angles (radians): interpolate on the unwrapped sequence.
  bool angle = false;

  bool Check(std::string* why) const;
};

enum class InterpStatus : std::uint8_t {
  kOk,        // value available
  kOutside,   // t before the first or after the last usable sample
  kGap,       // neighbouring usable samples further apart than max_gap_s
  kUnusable,  // an unusable sample (device error, empty value) lies between the neighbours
};
std::string InterpStatusName(InterpStatus status);

struct InterpValue {
  InterpStatus status = InterpStatus::kOutside;
  double value = 0.0;  // valid when status == kOk (unwrapped for angle series)
  bool ok() const { return status == InterpStatus::kOk; }
};

class TimeSeriesInterpolator {
 public:
  // t_s strictly increasing and finite (std::invalid_argument otherwise, with
  // the index of the first offending sample); values.size() == t_s.size();
  // nullopt (or a non-finite value) = unusable sample.
  TimeSeriesInterpolator(std::vector<double> t_s, const std::vector<std::optional<double>>& values,
                         const InterpOptions& options);
  // The same with NaN (or any non-finite value) for an unusable sample, taking the values over. The times
  // are shared, not copied, when every value is usable: two axes of one long log (a turret's azimuth and
  // elevation) then hold one vector of times between them (memory: 8 bytes a sample for the times plus 8
  // a sample for each axis's values).
  TimeSeriesInterpolator(std::shared_ptr<const std::vector<double>> t_s, std::vector<double> values,
                         const InterpOptions& options);

  InterpValue At(double t_s) const;
  // The usable samples' times t_k <= t_s <= t_k+1 around t_s (the interval At interpolates on), or nullopt
  // outside the samples.
  std::optional<std::pair<double, double>> Bracket(double t_s) const;

  std::size_t samples() const { return n_samples_; }
  std::size_t usable_samples() const { return v_.size(); }
  std::size_t segments() const { return segment_begin_.size(); }
  // Time span of the usable samples (NaN when there are none).
  double first_time() const;
  double last_time() const;
  const InterpOptions& options() const { return opt_; }
  // Bytes held for the samples (times counted in full even when shared).
  std::size_t HeldBytes() const;

 private:
  // Interpolates inside segment [s0, s1] (indices into t_/v_), t in [t_[k], t_[k+1]].
  double Linear(std::size_t k, double t) const;
  double Lagrange(std::size_t s0, std::size_t s1, std::size_t k, double t) const;
  double LocalPolynomial(std::size_t s0, std::size_t s1, std::size_t k, double t, int degree) const;

  InterpOptions opt_;
  std::size_t n_samples_ = 0;
  std::shared_ptr<const std::vector<double>> times_;  // times of the usable samples (maybe shared)
  std::vector<double> v_;                             // values of the usable samples
  // Segments: inclusive index ranges of usable samples, and why segment s ends (kGap or kUnusable: the
  // status of the interval from its last sample to the next segment's first).
  std::vector<std::size_t> segment_begin_, segment_end_;
  std::vector<InterpStatus> segment_break_;
};

// Unwraps an angle sequence (radians) over its usable values: each usable
// value is shifted by a multiple of 2π so that it differs from the previous
// usable value by at most π. Missing values stay missing.
std::vector<std::optional<double>> UnwrapAngles(const std::vector<std::optional<double>>& values_rad);
// The same in place, NaN (any non-finite value) = missing.
void UnwrapAnglesInPlace(std::vector<double>* values_rad);

// Merges samples with identical times (a log may repeat a time stamp): the
// usable values at one time are averaged (angles: on the unwrapped sequence;
// call UnwrapAngles first), a time with no usable value stays unusable.
// t_s must be non-decreasing. Returns the number of samples removed.
std::size_t MergeDuplicateTimes(std::vector<double>* t_s, std::vector<std::optional<double>>* values);
// The same for several value columns of one log at once, in place (no copy of a long log), NaN (any
// non-finite value) = unusable; each column's usable values at a time are averaged, NaN if there are none.
std::size_t MergeDuplicateTimes(std::vector<double>* t_s, const std::vector<std::vector<double>*>& columns);

}  // namespace rk::track

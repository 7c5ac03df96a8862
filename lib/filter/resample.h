// Resampling of a Series to target times (rk-smooth resample; seed 001: the 5 Hz range
// log brought to the 20 Hz frame times).
//
// Methods, per column, on the column's usable samples only (missing or status-masked rows
// are simply absent):
//   linear  straight line between the two neighbouring samples (track::TimeSeriesInterpolator).
//   cubic   4-point Lagrange through t_{k−1..k+2} (track::TimeSeriesInterpolator); passes
//           through every sample, so it keeps all of the measurement noise.
//   kalman  the Singer-model RTS smoother of singer_series.h run over the input and
//           evaluated at the target times as inserted no-measurement steps (the optimal
//           interpolating smoother under the model; it averages the noise). Block by block
//           (SingerSmoother): memory independent of the input's length, besides the Series.
// Angles (`_deg` columns) are interpolated on the unwrapped sequence and wrapped on output.
// Gap limit: a target time between two usable samples further apart than max_gap_s gets no
// value (status lost, reason gap). Default max_gap_s = kDefaultGapFactor × the median
// interval of the input rows (so one missing sample is bridged, two are not).
// Extrapolation: a target time before the first / after the last usable sample of a column
// gets a value only within margin_s of it (linear/cubic: the straight line through the two
// outermost samples; kalman: the Singer prediction); beyond, no value (status invalid,
// reason outside). A target time equal to a sample time is inside.
// Row status: ok when every column has a value; otherwise that of the first column
// without one (lost/gap or invalid/outside), the other columns' values still given.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "filter/series.h"
#include "filter/singer_series.h"

namespace rk::filter {

inline constexpr double kDefaultGapFactor = 2.5;

enum class ResampleMethod { kLinear, kCubic, kKalman };
bool ParseResampleMethod(const std::string& name, ResampleMethod* method);  // "linear" | "cubic" | "kalman"
std::string ResampleMethodName(ResampleMethod method);

struct ResampleOptions {
  ResampleMethod method = ResampleMethod::kKalman;
  double max_gap_s = 0.0;  // > 0; 0 = default (kDefaultGapFactor × median input interval)
  double margin_s = 0.0;   // ≥ 0: extrapolation allowed beyond the first/last usable sample
  SingerSeriesOptions singer;  // kalman only

  // The options, one line each (docs/architecture.md "Adding an option"): --method, --max-gap, --margin,
  // --maneuver-time (of `singer`, with the help text of resample).
  static const io::OptionTable<ResampleOptions>& Table();
  // Table().Check, then singer's list rules.
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
};

enum class ResampleReason { kNone, kGap, kOutside };
std::string ResampleReasonName(ResampleReason r);  // "", "gap", "outside"

struct ResampleResult {
  std::vector<double> t_s;                // target times
  std::vector<std::vector<double>> values;  // [column][target], internal units, NaN = none
  std::vector<std::vector<double>> sigmas;  // kalman only: 1σ of each value, else NaN
  std::vector<ResampleReason> reason;     // per target (row)
  double max_gap_s = 0.0;                 // used
  double median_interval_s = 0.0;         // of the input rows
  std::size_t rows = 0, rows_ok = 0, rows_gap = 0, rows_outside = 0, rows_extrapolated = 0;
  SingerSeriesSummary singer;             // kalman only: the smoother run (noise figures, NIS)

  // rk-smooth resample's report body (docs/rk-smooth-singer-resample.md "Report"): method, max_gap_s,
  // margin_s, median_interval_s, input_rows, the row counts, with kalman maneuver_time_s and columns, and
  // the "summary" rk-run copies: {rows_ok, rows_gap, rows_outside} (+ nis_mean per column with kalman).
  nlohmann::json ToJson(const Series& series, const ResampleOptions& options) const;
  // The run's summary (io/run_summary.h): rows ok / lost (gap) / invalid (outside), a report-only warning
  // for target times without a value, the share ok as headline, ToJson as details.
  io::RunSummary Summary(const Series& series, const ResampleOptions& options) const;
};

// target_t_s must be non-decreasing and finite (RK_CHECK). Throws UsageError for bad options.
ResampleResult Resample(const Series& series, const std::vector<double>& target_t_s, const ResampleOptions& options);

// Times t0, t0 + 1/rate, ... ≤ t1 (+1e-9 s slack). Throws UsageError if rate ≤ 0, t1 < t0
// or more than kMaxRateTargets times.
inline constexpr double kMaxRateTargets = 1e8;
std::vector<double> TimesAtRate(double t0_s, double t1_s, double rate_hz);

}  // namespace rk::filter

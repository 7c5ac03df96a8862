// Estimate vs reference comparison (rk-analyze compare, SPEC.md §1.1).
//
// For each requested column C and each estimate row i with time t_i:
//   e_i = est_C(t_i) − ref_C(t_i)
// where ref_C(t) is the reference column interpolated at t (linear by
// default, or 4-point cubic; track::TimeSeriesInterpolator) with no
// extrapolation beyond the reference's time span, and reference rows with
// an empty C break the interpolation interval (a gap). Angle columns (name
// ending `_deg`) are interpolated on their unwrapped sequence (359.9 → 0.1 is
// a 0.2° step) and their errors wrapped to (−180, 180]. Rows are cut to
// after_s ≤ t ≤ before_s when given (transients). Each skipped row is counted
// with its reason. Statistics per column: analysis::ComputeErrorStats.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/options.h"
#include "analysis/stats.h"
#include "io/csv.h"
#include "io/run_summary.h"
#include "io/json_util.h"
#include "track/interp.h"

namespace rk::analysis {

struct CompareOptions {
  std::vector<std::string> columns;                           // non-empty, no duplicates
  std::optional<double> after_s;                              // keep estimate rows with t_s >= after_s
  std::optional<double> before_s;                             // keep estimate rows with t_s <= before_s
  track::InterpMethod interp = track::InterpMethod::kLinear;  // linear | cubic
  // Longest reference interval (s) interpolated across; +inf = no limit
  // (empty reference values break intervals regardless).
  double max_gap_s = std::numeric_limits<double>::infinity();
  bool arcsec = false;  // statistics of `_deg` columns in arc-seconds

  // --arcsec, --interp, --max-gap, described once (io::OptionTable); the lists and optional times are the app's.
  static const io::OptionTable<CompareOptions>& Table();
  bool Check(std::string* why) const;
};

// True for columns in degrees (name ends `_deg`).
bool IsAngleColumn(const std::string& column);

struct ColumnComparison {
  std::string column;
  bool angle = false;
  std::string unit;    // of the statistics: "deg", "arcsec", "m", "s", "px", "mm", "mps" or "" (unknown)
  double scale = 1.0;  // statistics = scale × errors in file units
  std::optional<ErrorStats> stats;  // in `unit`; nullopt when n = 0
  std::size_t skipped_estimate_empty = 0;
  std::size_t skipped_reference_outside = 0;  // time outside the reference's span
  std::size_t skipped_reference_gap = 0;      // gap / empty reference value around the time
  std::size_t skipped_time_window = 0;        // cut by after_s / before_s
  std::vector<std::optional<double>> errors;  // per estimate row, file units (degrees for angles)
};

struct CompareResult {
  std::vector<double> t_s;  // estimate row times
  std::vector<ColumnComparison> columns;
  std::size_t estimate_rows = 0, reference_rows = 0;
  std::size_t reference_duplicate_times = 0;
};

// Throws DataError (a column missing names file and header line; bad numbers
// and backwards time name file:line:col), UsageError for bad options.
CompareResult Compare(const io::CsvTable& estimate, const io::CsvTable& reference,
                      const CompareOptions& options);
// The cells Compare needs of every row of either file (io::CsvReadOptions::rule, --bad-rows skip):
// t_s non-decreasing, each of `columns` empty or a number.
io::CsvRowRule CompareRowRule(const std::vector<std::string>& columns);
// The run's summary (io/run_summary.h): a warning per column without a comparable row (on stderr), the RMS
// error of each column as headline (in its statistics unit). `details` is left empty: the report is the
// comparison document rk-analyze compare writes.
io::RunSummary CompareSummary(const CompareResult& result);

// {"<C>": {"n","max","min","mean","std","rms","p95_abs","unit","n_skipped":{...}}}
// (statistics null when n = 0; std null when n < 2).
io::Json ColumnsToJson(const CompareResult& result);
// t_s + one column err_<C> per column (estimate − reference, file units;
// empty where not computed). Every estimate row is written.
io::CsvWriter ErrorsCsv(const CompareResult& result);
// Fixed-width human-readable table.
std::string FormatTable(const CompareResult& result);

}  // namespace rk::analysis

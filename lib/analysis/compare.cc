// Estimate vs reference comparison; method in compare.h.
#include "analysis/compare.h"

#include <cmath>
#include <cstdio>
#include <set>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::analysis {

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string UnitOf(const std::string& column) {
  for (const char* u : {"deg", "mps", "mm", "px", "m", "s"}) {
    if (EndsWith(column, std::string("_") + u)) return u;
  }
  return "";
}

io::Json NumberOrNull(double v) { return std::isfinite(v) ? io::Json(v) : io::Json(nullptr); }

}  // namespace

bool IsAngleColumn(const std::string& column) { return EndsWith(column, "_deg"); }

const io::OptionTable<CompareOptions>& CompareOptions::Table() {
  using O = CompareOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Flag("--arcsec", &O::arcsec, "Statistics of _deg columns in arc-seconds (\"unit\": \"arcsec\")")
          .Choice("--interp", &O::interp, {track::InterpMethod::kLinear, track::InterpMethod::kCubic},
                  track::InterpMethodName, "Reference interpolation: linear or cubic (4-point Lagrange)")
          .Real("--max-gap", &O::max_gap_s, "s", io::Bounds::Positive(),
                "Longest reference interval (s) interpolated across (default: no limit; empty reference values "
                "always break the interval)");
  return table;
}

bool CompareOptions::Check(std::string* why) const {
  if (columns.empty()) {
    *why = "--columns needs at least one column name";
    return false;
  }
  std::set<std::string> seen;
  for (const auto& c : columns) {
    if (c.empty()) {
      *why = "--columns has an empty column name";
      return false;
    }
    if (c == "t_s") {
      *why = "--columns: t_s is the time base, not a value column";
      return false;
    }
    if (!seen.insert(c).second) {
      *why = "--columns names '" + c + "' twice";
      return false;
    }
  }
  if (after_s && before_s && *after_s > *before_s) {
    *why = "--after is later than --before: no row would be kept";
    return false;
  }
  if (interp != track::InterpMethod::kLinear && interp != track::InterpMethod::kCubic) {
    *why = "--interp must be linear or cubic";
    return false;
  }
  return Table().Check(*this, why);
}

CompareResult Compare(const io::CsvTable& estimate, const io::CsvTable& reference,
                      const CompareOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  CompareResult result;
  result.estimate_rows = estimate.rows();
  result.reference_rows = reference.rows();

  const int e_t = estimate.RequireColumn("t_s");
  const int r_t = reference.RequireColumn("t_s");
  std::vector<int> e_cols, r_cols;
  for (const auto& c : options.columns) {
    e_cols.push_back(estimate.RequireColumn(c));
    r_cols.push_back(reference.RequireColumn(c));
  }
  estimate.RequireNonDecreasing(e_t);
  reference.RequireNonDecreasing(r_t);

  for (std::size_t i = 0; i < estimate.rows(); ++i) result.t_s.push_back(estimate.Double(i, e_t));
  std::vector<double> ref_t;
  for (std::size_t i = 0; i < reference.rows(); ++i) ref_t.push_back(reference.Double(i, r_t));

  for (std::size_t c = 0; c < options.columns.size(); ++c) {
    ColumnComparison cc;
    cc.column = options.columns[c];
    cc.angle = IsAngleColumn(cc.column);
    cc.unit = UnitOf(cc.column);
    if (cc.angle && options.arcsec) {
      cc.unit = "arcsec";
      cc.scale = 3600.0;
    }
    // Reference series; angles in radians so that unwrapping uses ±π.
    std::vector<std::optional<double>> ref_v;
    for (std::size_t i = 0; i < reference.rows(); ++i) {
      auto v = reference.OptionalDouble(i, r_cols[c]);
      if (v && cc.angle) v = geo::DegToRad(*v);
      ref_v.push_back(v);
    }
    std::vector<double> t = ref_t;
    track::InterpOptions io;
    io.method = options.interp;
    io.max_gap_s = options.max_gap_s;
    io.angle = cc.angle;
    if (cc.angle) ref_v = track::UnwrapAngles(ref_v);
    result.reference_duplicate_times = track::MergeDuplicateTimes(&t, &ref_v);
    const track::TimeSeriesInterpolator ref(std::move(t), ref_v, io);

    std::vector<double> kept;
    cc.errors.resize(estimate.rows());
    for (std::size_t i = 0; i < estimate.rows(); ++i) {
      const double t_i = result.t_s[i];
      if ((options.after_s && t_i < *options.after_s) || (options.before_s && t_i > *options.before_s)) {
        ++cc.skipped_time_window;
        continue;
      }
      const auto est = estimate.OptionalDouble(i, e_cols[c]);
      if (!est) {
        ++cc.skipped_estimate_empty;
        continue;
      }
      const track::InterpValue r = ref.At(t_i);
      if (r.status == track::InterpStatus::kOutside) {
        ++cc.skipped_reference_outside;
        continue;
      }
      if (!r.ok()) {
        ++cc.skipped_reference_gap;
        continue;
      }
      const double err =
          cc.angle ? geo::RadToDeg(geo::AngleDiff(geo::DegToRad(*est), r.value)) : *est - r.value;
      cc.errors[i] = err;
      kept.push_back(err * cc.scale);
    }
    cc.stats = ComputeErrorStats(kept);
    result.columns.push_back(std::move(cc));
  }
  return result;
}

io::Json ColumnsToJson(const CompareResult& result) {
  io::Json cols = io::Json::object();
  for (const auto& cc : result.columns) {
    io::Json j;
    if (cc.stats) {
      j["n"] = cc.stats->n;
      j["max"] = NumberOrNull(cc.stats->max);
      j["min"] = NumberOrNull(cc.stats->min);
      j["mean"] = NumberOrNull(cc.stats->mean);
      j["std"] = NumberOrNull(cc.stats->std);
      j["rms"] = NumberOrNull(cc.stats->rms);
      j["p95_abs"] = NumberOrNull(cc.stats->p95_abs);
    } else {
      j["n"] = 0;
      for (const char* k : {"max", "min", "mean", "std", "rms", "p95_abs"}) j[k] = nullptr;
    }
    j["unit"] = cc.unit.empty() ? io::Json(nullptr) : io::Json(cc.unit);
    j["angle"] = cc.angle;
    j["n_skipped"] = {{"estimate_empty", cc.skipped_estimate_empty},
                      {"reference_outside", cc.skipped_reference_outside},
                      {"reference_gap", cc.skipped_reference_gap},
                      {"time_window", cc.skipped_time_window}};
    cols[cc.column] = j;
  }
  return cols;
}

io::CsvWriter ErrorsCsv(const CompareResult& result) {
  std::vector<std::string> names = {"t_s"};
  for (const auto& cc : result.columns) names.push_back("err_" + cc.column);
  io::CsvWriter w(names);
  for (std::size_t i = 0; i < result.t_s.size(); ++i) {
    w.Add(result.t_s[i], 9);
    for (const auto& cc : result.columns) w.Add(cc.errors[i], cc.angle ? 12 : 9);
    w.EndRow();
  }
  return w;
}

std::string FormatTable(const CompareResult& result) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-16s %-7s %7s %13s %13s %13s %13s %13s %13s\n", "column", "unit", "n",
                "max", "min", "mean", "std", "rms", "p95_abs");
  out += line;
  for (const auto& cc : result.columns) {
    const std::string unit = cc.unit.empty() ? "-" : cc.unit;
    if (!cc.stats) {
      std::snprintf(line, sizeof line, "%-16s %-7s %7d %13s %13s %13s %13s %13s %13s\n", cc.column.c_str(),
                    unit.c_str(), 0, "-", "-", "-", "-", "-", "-");
    } else {
      const ErrorStats& s = *cc.stats;
      std::snprintf(line, sizeof line, "%-16s %-7s %7zu %13.6g %13.6g %13.6g %13.6g %13.6g %13.6g\n",
                    cc.column.c_str(), unit.c_str(), s.n, s.max, s.min, s.mean, s.std, s.rms, s.p95_abs);
    }
    out += line;
  }
  return out;
}

io::CsvRowRule CompareRowRule(const std::vector<std::string>& columns) {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.optional_numbers = columns;
  return rule;
}

}  // namespace rk::analysis

namespace rk::analysis {

io::RunSummary CompareSummary(const CompareResult& result) {
  io::RunSummary s;
  for (const ColumnComparison& cc : result.columns) {
    if (!cc.stats) {
      s.Warn("no_comparable_row",
             "column " + cc.column + ": no comparable row (estimate empty " + std::to_string(cc.skipped_estimate_empty) +
                 ", reference outside " + std::to_string(cc.skipped_reference_outside) + ", reference gap " +
                 std::to_string(cc.skipped_reference_gap) + ", cut by --after/--before " +
                 std::to_string(cc.skipped_time_window) + "); statistics are null");
      continue;
    }
    s.AddFigure("rms error " + cc.column, cc.stats->rms, cc.unit, std::to_string(cc.stats->n) + " rows");
  }
  return s;
}

}  // namespace rk::analysis

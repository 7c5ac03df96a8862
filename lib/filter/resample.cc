// Resampling to target times; see resample.h.
#include "filter/resample.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "geo/angles.h"
#include "io/error.h"
#include "io/json_util.h"
#include "io/run_summary.h"
#include "numeric/robust_stats.h"
#include "track/interp.h"

namespace rk::filter {
namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();
constexpr double kGapSlack = 1e-9;  // relative, as in track/interp.cc (decimal time stamps)

// What one column gives a target time: nothing (outside: beyond margin_s of its usable samples; gap: between
// two usable samples further apart than max_gap_s), a value between or at its samples, or an extrapolated one.
enum class TargetUse : unsigned char { kOutside, kGap, kInside, kExtrapolated };

// TargetUse of every target time (non-decreasing) for column c, in one walk over the rows: no copy of the
// column's samples.
std::vector<TargetUse> ClassifyTargets(const Series& series, std::size_t c, const std::vector<double>& targets,
                                       double max_gap_s, double margin_s) {
  const std::size_t n = series.rows();
  const auto col = static_cast<Eigen::Index>(c);
  const auto usable = [&](std::size_t r) { return std::isfinite(series.values(static_cast<Eigen::Index>(r), col)); };
  std::vector<TargetUse> use(targets.size(), TargetUse::kOutside);
  std::size_t first = 0;
  while (first < n && !usable(first)) ++first;
  if (first == n) return use;
  std::size_t last = n - 1;
  while (!usable(last)) --last;
  const std::vector<double>& ts = series.t_s;
  // next: the first usable row with t_s ≥ t (t inside [ts[first], ts[last]]); prev: the usable row before it.
  std::size_t next = first, prev = n;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const double t = targets[i];
    const bool before = t < ts[first], after = t > ts[last];
    if (before || after) {
      const double dist = before ? ts[first] - t : t - ts[last];
      use[i] = dist > margin_s ? TargetUse::kOutside : TargetUse::kExtrapolated;
      continue;
    }
    while (ts[next] < t) {
      prev = next;
      do ++next;
      while (!usable(next));
    }
    // t equal to a sample is always inside; otherwise next > first, so prev is a usable row.
    const bool on_sample = ts[next] == t;
    use[i] = !on_sample && ts[next] - ts[prev] > max_gap_s * (1.0 + kGapSlack) ? TargetUse::kGap
                                                                              : TargetUse::kInside;
  }
  return use;
}

bool Evaluated(TargetUse u) { return u == TargetUse::kInside || u == TargetUse::kExtrapolated; }

// kalman: the Singer smoother (block by block, SingerSmoother) evaluated at the targets each column gives a
// value; values and 1σ into res, its summary into res->singer.
void ResampleKalman(const Series& series, const std::vector<double>& targets,
                    const std::vector<std::vector<TargetUse>>& use, const SingerSeriesOptions& options,
                    ResampleResult* res) {
  const SingerSmoother smoother(series, options);
  res->singer = smoother.summary();
  const std::size_t nc = series.columns.size();
  std::vector<std::size_t> next(nc, 0);  // per column: the next target to evaluate
  const auto skip = [&](std::size_t c) {
    while (next[c] < targets.size() && !Evaluated(use[c][next[c]])) ++next[c];
  };
  smoother.ForEachBlock([&](const SingerBlock& block) {
    for (std::size_t c = 0; c < nc; ++c) {
      // Targets are non-decreasing, and so is the row each needs.
      for (skip(c); next[c] < targets.size() && smoother.EvaluationRow(c, targets[next[c]]) < block.end(); skip(c)) {
        const std::size_t i = next[c]++;
        Eigen::Vector3d x;
        Eigen::Matrix3d P;
        smoother.Evaluate(block, c, targets[i], &x, &P);
        res->values[c][i] = x(0);
        res->sigmas[c][i] = std::sqrt(std::max(P(0, 0), 0.0));
      }
    }
  });
  for (std::size_t c = 0; c < nc; ++c) RK_CHECK(next[c] == targets.size(), "kalman resampling left targets");
}

// linear / cubic of column c at the targets it gives a value (track::TimeSeriesInterpolator on its usable
// samples, angles unwrapped; beyond the ends the straight line through the two outermost samples).
void ResampleInterpolated(const Series& series, std::size_t c, const std::vector<double>& targets,
                          const std::vector<TargetUse>& use, const ResampleOptions& options, ResampleResult* res) {
  const bool angle = series.is_angle[c];
  std::vector<double> tu, vu;
  for (std::size_t r = 0; r < series.rows(); ++r) {
    double v = series.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
    if (!std::isfinite(v)) continue;
    if (angle && !vu.empty()) v = vu.back() + geo::WrapPi(v - vu.back());
    tu.push_back(series.t_s[r]);
    vu.push_back(v);
  }
  if (tu.empty()) return;
  track::InterpOptions io;
  io.method = options.method == ResampleMethod::kLinear ? track::InterpMethod::kLinear : track::InterpMethod::kCubic;
  io.max_gap_s = res->max_gap_s;
  io.angle = false;  // already unwrapped above
  const track::TimeSeriesInterpolator interp(tu, std::vector<std::optional<double>>(vu.begin(), vu.end()), io);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const double t = targets[i];
    double value = kNoValue;
    if (use[i] == TargetUse::kExtrapolated) {
      if (tu.size() == 1) {
        value = vu[0];
      } else {
        const std::size_t j = t < tu.front() ? 0 : tu.size() - 2;
        value = vu[j] + (vu[j + 1] - vu[j]) * (t - tu[j]) / (tu[j + 1] - tu[j]);
      }
    } else if (use[i] == TargetUse::kInside) {
      const track::InterpValue v = interp.At(t);
      RK_CHECK(v.ok(), "interpolator refused a time inside a segment");
      value = v.value;
    } else {
      continue;
    }
    res->values[c][i] = value;
  }
}

}  // namespace

bool ParseResampleMethod(const std::string& name, ResampleMethod* method) {
  if (name == "linear") *method = ResampleMethod::kLinear;
  else if (name == "cubic") *method = ResampleMethod::kCubic;
  else if (name == "kalman") *method = ResampleMethod::kKalman;
  else return false;
  return true;
}

std::string ResampleMethodName(ResampleMethod method) {
  switch (method) {
    case ResampleMethod::kLinear: return "linear";
    case ResampleMethod::kCubic: return "cubic";
    case ResampleMethod::kKalman: return "kalman";
  }
  return "kalman";
}

std::string ResampleReasonName(ResampleReason r) {
  switch (r) {
    case ResampleReason::kNone: return "";
    case ResampleReason::kGap: return "gap";
    case ResampleReason::kOutside: return "outside";
  }
  return "";
}

const io::OptionTable<ResampleOptions>& ResampleOptions::Table() {
  static const io::OptionTable<ResampleOptions> table =
      io::OptionTable<ResampleOptions>()
          .Choice("--method", &ResampleOptions::method,
                  {ResampleMethod::kLinear, ResampleMethod::kCubic, ResampleMethod::kKalman}, ResampleMethodName,
                  "linear, cubic or kalman (Singer RTS smoother)")
          .Real("--max-gap", &ResampleOptions::max_gap_s, "s", io::Bounds::AtLeast(0.0),
                "Longest interval (s) between usable samples interpolated across; default 2.5 x the median "
                "input interval")
          .Real("--margin", &ResampleOptions::margin_s, "s", io::Bounds::AtLeast(0.0),
                "Extrapolation allowed (s) before the first / after the last usable sample; beyond it rows "
                "are empty with status invalid, reason outside")
          .Real(
              "--maneuver-time", [](ResampleOptions& o) -> double& { return o.singer.maneuver_time_s; }, "s",
              io::Bounds::Positive(), "kalman: Singer maneuver time constant tau_m (s)");
  return table;
}

bool ResampleOptions::Check(std::string* why) const {
  return Table().Check(*this, why) && singer.Check(why);
}

std::vector<double> TimesAtRate(double t0, double t1, double rate_hz) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw UsageError("--rate must be > 0 Hz");
  if (!std::isfinite(t0) || !std::isfinite(t1)) throw UsageError("--t0/--t1 must be finite");
  if (t1 < t0) throw UsageError("--t1 is before --t0");
  const double count = std::floor((t1 - t0) * rate_hz + 1e-9) + 1.0;
  if (count > kMaxRateTargets) throw UsageError("--rate gives more than 1e8 target times");
  std::vector<double> t(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = t0 + static_cast<double>(i) / rate_hz;
  return t;
}

ResampleResult Resample(const Series& series, const std::vector<double>& targets, const ResampleOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    RK_CHECK(std::isfinite(targets[i]) && (i == 0 || targets[i] >= targets[i - 1]),
             "target times must be finite and non-decreasing");
  }
  const std::size_t nc = series.columns.size();
  const std::size_t n = series.rows();
  ResampleResult res;
  res.t_s = targets;
  res.rows = targets.size();
  {
    std::vector<double> dt;
    dt.reserve(n);
    for (std::size_t r = 1; r < n; ++r) dt.push_back(series.t_s[r] - series.t_s[r - 1]);
    res.median_interval_s = dt.empty() ? kNoValue : numeric::UpperMedianInPlace(dt);
  }
  res.max_gap_s = options.max_gap_s > 0.0 ? options.max_gap_s : kDefaultGapFactor * res.median_interval_s;
  res.values.assign(nc, std::vector<double>(targets.size(), kNoValue));
  res.sigmas.assign(nc, std::vector<double>(targets.size(), kNoValue));
  res.reason.assign(targets.size(), ResampleReason::kNone);

  std::vector<std::vector<TargetUse>> use(nc);
  std::vector<std::size_t> extrapolated(targets.size(), 0);
  for (std::size_t c = 0; c < nc; ++c) {
    use[c] = ClassifyTargets(series, c, targets, res.max_gap_s, options.margin_s);
    for (std::size_t i = 0; i < targets.size(); ++i) {
      // Row reason: that of the first column without a value.
      if (use[c][i] == TargetUse::kExtrapolated) extrapolated[i] = 1;
      if (res.reason[i] != ResampleReason::kNone) continue;
      if (use[c][i] == TargetUse::kOutside) res.reason[i] = ResampleReason::kOutside;
      if (use[c][i] == TargetUse::kGap) res.reason[i] = ResampleReason::kGap;
    }
  }
  if (options.method == ResampleMethod::kKalman) {
    ResampleKalman(series, targets, use, options.singer, &res);
  } else {
    for (std::size_t c = 0; c < nc; ++c) ResampleInterpolated(series, c, targets, use[c], options, &res);
  }
  for (std::size_t i = 0; i < targets.size(); ++i) {
    switch (res.reason[i]) {
      case ResampleReason::kNone: ++res.rows_ok; break;
      case ResampleReason::kGap: ++res.rows_gap; break;
      case ResampleReason::kOutside: ++res.rows_outside; break;
    }
    res.rows_extrapolated += extrapolated[i];
  }
  return res;
}

nlohmann::json ResampleResult::ToJson(const Series& series, const ResampleOptions& options) const {
  io::Json j;
  j["method"] = ResampleMethodName(options.method);
  j["max_gap_s"] = max_gap_s;
  j["margin_s"] = options.margin_s;
  j["median_interval_s"] = median_interval_s;
  j["input_rows"] = series.rows();
  j["rows"] = rows;
  j["rows_ok"] = rows_ok;
  j["rows_gap"] = rows_gap;
  j["rows_outside"] = rows_outside;
  j["rows_extrapolated"] = rows_extrapolated;
  j["summary"] = {{"rows_ok", rows_ok}, {"rows_gap", rows_gap}, {"rows_outside", rows_outside}};
  if (options.method == ResampleMethod::kKalman) {
    j["maneuver_time_s"] = options.singer.maneuver_time_s;
    j["columns"] = singer.ColumnsJson(series, false);
    j["summary"]["nis_mean"] = singer.SummaryJson(series)["nis_mean"];
  }
  return j;
}

}  // namespace rk::filter

namespace rk::filter {

io::RunSummary ResampleResult::Summary(const Series& series, const ResampleOptions& options) const {
  io::RunSummary s;
  s.CountRows(RowStatus::kOk, rows_ok);
  s.CountRows(RowStatus::kLost, rows_gap);
  s.CountRows(RowStatus::kInvalid, rows_outside);
  if (rows_gap + rows_outside > 0) {
    s.Flag("rows_without_value", std::to_string(rows_gap + rows_outside) + " of " + std::to_string(rows) +
                                     " target times have no value (" + std::to_string(rows_gap) + " in a gap, " +
                                     std::to_string(rows_outside) + " outside the input)");
  }
  if (rows > 0) {
    s.AddFigure("rows ok", static_cast<double>(rows_ok) / static_cast<double>(rows), "fraction",
                std::to_string(rows_ok) + " of " + std::to_string(rows));
  }
  s.details = ToJson(series, options);
  return s;
}

}  // namespace rk::filter

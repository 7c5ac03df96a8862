// rk-smooth resample: one series brought to the times of another (--at frames.csv) or to a
// regular rate (SPEC.md §1.1). Method: lib/filter/resample.h.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "filter/resample.h"
#include "filter/series.h"
#include "filter/singer_series.h"
#include "filter/smoothed_series.h"
#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "smooth_commands.h"

namespace rk::app {
namespace {

struct ResampleArgs {
  std::string input, output, columns, at;
  double rate_hz = std::numeric_limits<double>::quiet_NaN();
  double t0_s = std::numeric_limits<double>::quiet_NaN();
  double t1_s = std::numeric_limits<double>::quiet_NaN();
  filter::ResampleOptions opt;                  // the table's options (--method, --max-gap, --margin, --maneuver-time)
  std::vector<double> accel_sigma, meas_sigma;  // column units
  bool sigmas = false, ignore_status = false;
  CLI::Option* rate_opt = nullptr;
  CLI::Option* at_opt = nullptr;
  CLI::Option* t0_opt = nullptr;
  CLI::Option* t1_opt = nullptr;
  io::BadRows bad_rows = io::BadRows::kError;
};

constexpr int kResampleDecimals = 9;

// Exactly one of --at and --rate; --t0/--t1 only with --rate; one stdin input; --report and -o not an
// input and not both stdout.
void CheckResampleArgs(const ResampleArgs& args, const Context& ctx, bool have_at, bool have_rate) {
  if (have_at == have_rate) throw UsageError("give exactly one of --at FILE and --rate HZ");
  if (have_rate && !(args.rate_hz > 0.0 && std::isfinite(args.rate_hz)))
    throw UsageError("--rate must be > 0 Hz");
  if (have_at && (args.t0_opt->count() || args.t1_opt->count())) {
    throw UsageError("--t0/--t1 go with --rate, not with --at");
  }
  cli::CheckStreams(ctx.common, {{"-i", args.input}, {"--at", have_at ? args.at : ""}}, {{"-o", args.output}});
}

filter::ResampleOptions ResampleOptionsOf(const ResampleArgs& args, bool max_gap_given) {
  filter::ResampleOptions opt = args.opt;
  // 0 is "not given" (2.5 x the median interval); given, it must be > 0.
  if (max_gap_given && !(opt.max_gap_s > 0.0)) throw UsageError("--max-gap must be > 0 s");
  opt.singer.accel_sigma = args.accel_sigma;
  opt.singer.meas_sigma = args.meas_sigma;
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  return opt;
}

// The target times, and the columns of --at copied to the output (those the output does not write itself).
struct ResampleTargets {
  std::vector<double> t_s;
  std::vector<std::string> pass_names;
  std::vector<int> pass_cols;
  io::CsvTable at_table = io::CsvTable::Parse("t_s\n", "none");
};

ResampleTargets TargetsOf(const ResampleArgs& args, const filter::Series& series, bool have_at) {
  ResampleTargets tg;
  if (!have_at) {
    const double t0 = args.t0_opt->count() ? args.t0_s : series.t_s.front();
    const double t1 = args.t1_opt->count() ? args.t1_s : series.t_s.back();
    tg.t_s = filter::TimesAtRate(t0, t1, args.rate_hz);
    return tg;
  }
  io::CsvReadOptions at_read;
  at_read.bad_rows = args.bad_rows;
  at_read.rule.non_decreasing = "t_s";
  tg.at_table = io::CsvTable::Read(args.at, at_read);
  const int c_t = tg.at_table.RequireColumn("t_s");
  tg.at_table.RequireNonDecreasing(c_t);
  for (std::size_t r = 0; r < tg.at_table.rows(); ++r) tg.t_s.push_back(tg.at_table.Double(r, c_t));
  if (tg.t_s.empty()) throw DataError(tg.at_table.name(), 0, 0, "no target times");
  std::vector<std::string> reserved = {"t_s", "kind", "status", "reason"};
  for (const auto& c : series.columns) {
    reserved.push_back(c);
    reserved.push_back(filter::DerivedColumnName(c, 0, true));
  }
  for (std::size_t c = 0; c < tg.at_table.header().size(); ++c) {
    const std::string& h = tg.at_table.header()[c];
    if (std::find(reserved.begin(), reserved.end(), h) != reserved.end()) continue;
    tg.pass_names.push_back(h);
    tg.pass_cols.push_back(static_cast<int>(c));
  }
  return tg;
}

// t_s, the copied columns of --at, kind, the values, status, reason (and 1-sigma with kalman --sigmas):
// filter::SmoothedSeriesWriter.
io::CsvWriter ResampleCsv(const filter::Series& series, const ResampleTargets& tg, const filter::ResampleResult& res,
                          const filter::ResampleOptions& opt, bool with_sigmas) {
  const std::size_t nc = series.columns.size();
  filter::SmoothedColumns columns;
  columns.copied = tg.pass_names;
  columns.reason = true;
  columns.sigma_orders = with_sigmas ? 1 : 0;
  filter::SmoothedSeriesWriter w(series, columns, kResampleDecimals);
  const std::string kind = opt.method == filter::ResampleMethod::kKalman ? "smoothed" : "estimate";
  std::vector<std::string_view> copied(tg.pass_cols.size());
  for (std::size_t i = 0; i < tg.t_s.size(); ++i) {
    for (std::size_t k = 0; k < tg.pass_cols.size(); ++k) copied[k] = tg.at_table.Cell(i, tg.pass_cols[k]);
    for (std::size_t c = 0; c < nc; ++c) {
      w.Set(c, res.values[c][i]);
      if (with_sigmas) w.SetSigma(c, 0, res.sigmas[c][i]);
    }
    const char* status = "ok";
    if (res.reason[i] == filter::ResampleReason::kGap) status = "lost";
    if (res.reason[i] == filter::ResampleReason::kOutside) status = "invalid";
    w.Write(tg.t_s[i], kind, status, filter::ResampleReasonName(res.reason[i]), &copied);
  }
  return std::move(w.csv());
}

// The input series (status-masked unless --ignore-status) and the number of rows masked; the table (its
// row index) is released on return.
filter::Series ReadResampleInput(const ResampleArgs& args, const std::vector<std::string>& columns,
                                 std::size_t* masked) {
  const io::CsvTable table = io::CsvTable::Read(args.input, {args.bad_rows, filter::SeriesRowRule(columns)});
  filter::Series series = filter::ReadSeries(table, columns, 3);
  *masked = args.ignore_status ? 0 : filter::MaskByStatus(table, &series, 3);
  return series;
}

int RunResample(const ResampleArgs& args, const CLI::App& sub, const Context& ctx) {
  const bool have_at = args.at_opt->count() > 0, have_rate = args.rate_opt->count() > 0;
  CheckResampleArgs(args, ctx, have_at, have_rate);
  filter::ResampleOptions opt = ResampleOptionsOf(args, sub.count("--max-gap") > 0);

  const std::vector<std::string> columns = io::SplitList(args.columns);
  std::size_t masked = 0;
  filter::Series series = ReadResampleInput(args, columns, &masked);
  opt.singer.accel_sigma = filter::ColumnUnitsToInternal(opt.singer.accel_sigma, series, "--accel-sigma");
  opt.singer.meas_sigma = filter::ColumnUnitsToInternal(opt.singer.meas_sigma, series, "--meas-sigma");

  const ResampleTargets targets = TargetsOf(args, series, have_at);
  const filter::ResampleResult res = filter::Resample(series, targets.t_s, opt);
  const bool with_sigmas = args.sigmas && opt.method == filter::ResampleMethod::kKalman;
  const io::CsvWriter w = ResampleCsv(series, targets, res, opt, with_sigmas);

  const io::RunSummary summary = res.Summary(series, opt);
  io::Json report;
  if (!ctx.common.report_path.empty()) {
    report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    cli::AddReportInput(&report, "input", args.input);
    if (have_at) cli::AddReportInput(&report, "at", args.at);
    report["subcommand"] = "resample";
    report["rows_masked_by_status"] = masked;
    report["options"] = opt.ToJson();
  }
  w.Write(args.output);
  if (!ctx.common.report_path.empty()) cli::WriteReport(ctx.common.report_path, report, summary);
  cli::WarnAll(ctx.tool, ctx.common, summary);
  return 0;
}

}  // namespace

Command AddResampleCommand(CLI::App& app) {
  auto args = std::make_shared<ResampleArgs>();
  CLI::App* sub = app.add_subcommand(
      "resample",
      "Bring value columns to other times (--at FILE with t_s, or --rate HZ): linear, cubic or kalman "
      "(Singer RTS smoother); gap limit, no extrapolation beyond --margin "
      "(docs/rk-smooth-singer-resample.md)");
  sub->add_option("-i,--input", args->input, "Input CSV with t_s and the value columns ('-' = stdin)")
      ->required();
  cli::AddBadRowsOption(sub, &args->bad_rows);
  sub->add_option("--columns", args->columns, "Value columns, comma-separated (e.g. range_m)")->required();
  args->at_opt = sub->add_option("--at", args->at,
                                 "CSV of target times (column t_s, non-decreasing); its other columns (e.g. "
                                 "frame) are copied to the output");
  args->rate_opt = sub->add_option("--rate", args->rate_hz, "Target times at this rate (Hz), > 0");
  args->t0_opt =
      sub->add_option("--t0", args->t0_s, "With --rate: first target time (s); default first input t_s");
  args->t1_opt =
      sub->add_option("--t1", args->t1_s, "With --rate: last target time (s); default last input t_s");
  sub->add_option("-o,--output", args->output, "Output CSV ('-' = stdout)")->required();
  cli::AddOptions(sub, &args->opt, filter::ResampleOptions::Table());
  sub->add_option("--accel-sigma", args->accel_sigma,
                  "kalman: RMS acceleration in column units/s^2, one or one per column; default: chosen by "
                  "maximum likelihood on a grid 1/16..8 x (_m 0.5, _deg 5, _px 50)")
      ->delimiter(',');
  sub->add_option("--meas-sigma", args->meas_sigma,
                  "kalman: measurement noise std in column units, one or one per column; default estimated "
                  "from the data")
      ->delimiter(',');
  sub->add_flag("--sigmas", args->sigmas, "kalman: add 1-sigma columns <base>_sigma_<unit>");
  sub->add_flag("--ignore-status", args->ignore_status,
                "Use values whatever the input's status column says (default: non-zero device codes and "
                "predicted/lost/invalid rows are missing)");
  return {sub, [args, sub](const Context& ctx) { return RunResample(*args, *sub, ctx); }};
}

}  // namespace rk::app

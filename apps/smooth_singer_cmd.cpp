// rk-smooth singer: Singer-model Kalman filter + RTS smoother per column, with rate and
// acceleration outputs (SPEC.md §1.1). Method: lib/filter/singer_series.h.
#include <cmath>
#include <string>
#include <vector>

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

struct SingerArgs {
  std::string input, output, columns;
  std::vector<double> accel_sigma, meas_sigma;  // column units (degrees for _deg columns)
  filter::SingerSeriesOptions opt;              // the table's options (--maneuver-time)
  bool no_smooth = false, derivatives = true, sigmas = false, ignore_status = false;
  io::BadRows bad_rows = io::BadRows::kError;
};

constexpr int kDecimals = 9;

void CheckSingerPaths(const SingerArgs& args, const Context& ctx) {
  cli::CheckStreams(ctx.common, {{"-i", args.input}}, {{"-o", args.output}});
}

filter::SingerSeriesOptions SingerOptionsOf(const SingerArgs& args) {
  filter::SingerSeriesOptions opt = args.opt;
  opt.smooth = !args.no_smooth;
  opt.accel_sigma = args.accel_sigma;
  opt.meas_sigma = args.meas_sigma;
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  return opt;
}

// The smoothed (or filtered) series, one row per input row (filter::SmoothedSeriesWriter), written block by
// block (filter::SingerSmoother) into `out`: neither the estimates nor the text of the whole series are held.
void WriteSingerCsv(const filter::Series& series, const filter::SingerSmoother& smoother, const SingerArgs& args,
                    io::OutputFile* out) {
  const std::size_t nc = series.columns.size();
  filter::SmoothedColumns columns;
  columns.derivatives = args.derivatives;
  columns.sigma_orders = args.sigmas ? (args.derivatives ? 3 : 1) : 0;
  filter::SmoothedSeriesWriter w(series, columns, kDecimals);
  const std::string kind = smoother.summary().smoothed ? "smoothed" : "estimate";
  Eigen::Vector3d x;
  Eigen::Matrix3d P;
  const auto row = [&](const filter::SingerBlock& block, std::size_t r) {
    for (std::size_t c = 0; c < nc; ++c) {
      if (!block.At(c, r, &x, &P)) continue;
      w.Set(c, x(0), x(1), x(2));
      for (int i = 0; i < columns.sigma_orders; ++i) w.SetSigma(c, i, std::sqrt(std::max(P(i, i), 0.0)));
    }
    w.Write(series.t_s[r], kind, filter::SingerRowStatusName(smoother.RowStatus(r)));
  };
  smoother.ForEachBlock([&](const filter::SingerBlock& block) {
    for (std::size_t r = block.begin(); r < block.end(); ++r) row(block, r);
    out->Write(w.TakeText());
  });
  out->Write(w.TakeText());  // the header alone when there are no rows
}

// The input series (status-masked unless --ignore-status) and the number of rows masked; the table (its
// row index) is released on return.
filter::Series ReadSingerInput(const SingerArgs& args, const std::vector<std::string>& columns, std::size_t* masked) {
  const io::CsvTable table = io::CsvTable::Read(args.input, {args.bad_rows, filter::SeriesRowRule(columns)});
  filter::Series series = filter::ReadSeries(table, columns, 3);
  *masked = args.ignore_status ? 0 : filter::MaskByStatus(table, &series, 3);
  return series;
}

int RunSinger(const SingerArgs& args, const Context& ctx) {
  CheckSingerPaths(args, ctx);
  const std::vector<std::string> columns = io::SplitList(args.columns);
  filter::SingerSeriesOptions opt = SingerOptionsOf(args);

  std::size_t masked = 0;
  const filter::Series series = ReadSingerInput(args, columns, &masked);
  opt.accel_sigma = filter::ColumnUnitsToInternal(opt.accel_sigma, series, "--accel-sigma");
  opt.meas_sigma = filter::ColumnUnitsToInternal(opt.meas_sigma, series, "--meas-sigma");
  const filter::SingerSmoother smoother(series, opt);

  const io::RunSummary summary = smoother.summary().Summary(series, opt.maneuver_time_s);
  io::Json report;
  if (!ctx.common.report_path.empty()) {
    report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    cli::AddReportInput(&report, "input", args.input);
    report["subcommand"] = "singer";
    report["rows_masked_by_status"] = masked;
    report["options"] = opt.ToJson();
  }
  io::OutputFile out(args.output);
  WriteSingerCsv(series, smoother, args, &out);
  out.Commit();
  if (!ctx.common.report_path.empty()) cli::WriteReport(ctx.common.report_path, report, summary);
  cli::WarnAll(ctx.tool, ctx.common, summary);
  return 0;
}

}  // namespace

Command AddSingerCommand(CLI::App& app) {
  auto args = std::make_shared<SingerArgs>();
  CLI::App* sub = app.add_subcommand(
      "singer",
      "Singer-model Kalman filter + RTS smoother per column, with rate and acceleration columns "
      "(docs/rk-smooth-singer-resample.md)");
  sub->add_option("-i,--input", args->input, "Input CSV with t_s and the value columns ('-' = stdin)")
      ->required();
  cli::AddBadRowsOption(sub, &args->bad_rows);
  sub->add_option("--columns", args->columns, "Value columns, comma-separated (e.g. range_m,az_deg,el_deg)")
      ->required();
  sub->add_option("-o,--output", args->output, "Output CSV ('-' = stdout)")->required();
  cli::AddOptions(sub, &args->opt, filter::SingerSeriesOptions::Table());
  sub->add_option("--accel-sigma", args->accel_sigma,
                  "RMS acceleration sigma_m in column units/s^2 (deg/s^2 for _deg), one value or one per "
                  "column; default: chosen per column by maximum likelihood on a grid 1/16..8 x (_m 0.5, "
                  "_deg 5, _px 50)")
      ->delimiter(',');
  sub->add_option("--meas-sigma", args->meas_sigma,
                  "Measurement noise std in column units, one value or one per column; default: estimated "
                  "from the data (MAD of 4th differences), reported in --report")
      ->delimiter(',');
  sub->add_flag("--no-smooth", args->no_smooth,
                "Forward filter only (kind 'estimate'); default: RTS smoother");
  sub->add_flag("--derivatives,!--no-derivatives", args->derivatives,
                "Rate and acceleration columns <base>_rate_<unit>_s, <base>_accel_<unit>_s2 (default on)");
  sub->add_flag("--sigmas", args->sigmas, "Add 1-sigma columns <base>_sigma_<unit> (and of the derivatives)");
  sub->add_flag("--ignore-status", args->ignore_status,
                "Use values whatever the input's status column says (default: non-zero device codes and "
                "predicted/lost/invalid rows are not measurements)");
  return {sub, [args](const Context& ctx) { return RunSinger(*args, ctx); }};
}

}  // namespace rk::app

// rk-smooth singer: Singer-model Kalman filter + RTS smoother per column, with rate and
// acceleration outputs (SPEC.md §1.1). Method: lib/filter/singer_series.h.
#include <cmath>
#include <string>
#include <vector>

#include "filter/series.h"
#include "filter/singer_series.h"
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

// t_s, kind, the columns, status, then rates and accelerations, then the 1-sigma columns.
std::vector<std::string> SingerHeader(const std::vector<std::string>& columns, const SingerArgs& args) {
  std::vector<std::string> header = {"t_s", "kind"};
  for (const auto& c : columns) header.push_back(c);
  header.push_back("status");
  if (args.derivatives) {
    for (const auto& c : columns) {
      header.push_back(filter::DerivedColumnName(c, 1));
      header.push_back(filter::DerivedColumnName(c, 2));
    }
  }
  if (args.sigmas) {
    for (const auto& c : columns) {
      header.push_back(filter::DerivedColumnName(c, 0, true));
      if (args.derivatives) {
        header.push_back(filter::DerivedColumnName(c, 1, true));
        header.push_back(filter::DerivedColumnName(c, 2, true));
      }
    }
  }
  return header;
}

// The smoothed (or filtered) series, one row per input row, in column units, written block by block
// (filter::SingerSmoother) into `out`: neither the estimates nor the text of the whole series are held.
void WriteSingerCsv(const filter::Series& series, const filter::SingerSmoother& smoother, const SingerArgs& args,
                    io::OutputFile* out) {
  const std::size_t nc = series.columns.size();
  const std::vector<bool> is360 = filter::AngleColumnsIn360(series);
  io::CsvWriter w(SingerHeader(series.columns, args));
  const std::string kind = smoother.summary().smoothed ? "smoothed" : "estimate";
  std::vector<Eigen::Vector3d> x(nc);
  std::vector<Eigen::Matrix3d> P(nc);
  std::vector<bool> have(nc);
  const auto unit = [&](std::size_t c) { return series.is_angle[c] ? geo::RadToDeg(1.0) : 1.0; };
  const auto row = [&](const filter::SingerBlock& block, std::size_t r) {
    w.Add(series.t_s[r], kDecimals).Add(kind);
    for (std::size_t c = 0; c < nc; ++c) {
      have[c] = block.At(c, r, &x[c], &P[c]);
      if (!have[c]) {
        w.AddEmpty();
      } else if (series.is_angle[c]) {
        const double deg = geo::RadToDeg(x[c](0));
        w.Add(is360[c] ? geo::WrapDeg360(deg) : geo::WrapDeg180(deg), kDecimals);
      } else {
        w.Add(x[c](0), kDecimals);
      }
    }
    w.Add(filter::SingerRowStatusName(smoother.RowStatus(r)));
    if (args.derivatives) {
      for (std::size_t c = 0; c < nc; ++c) {
        if (!have[c]) {
          w.AddEmpty().AddEmpty();
        } else {
          w.Add(x[c](1) * unit(c), kDecimals).Add(x[c](2) * unit(c), kDecimals);
        }
      }
    }
    if (args.sigmas) {
      for (std::size_t c = 0; c < nc; ++c) {
        const int k = args.derivatives ? 3 : 1;
        for (int i = 0; i < k; ++i) {
          if (!have[c])
            w.AddEmpty();
          else
            w.Add(std::sqrt(std::max(P[c](i, i), 0.0)) * unit(c), kDecimals);
        }
      }
    }
    w.EndRow();
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

  io::Json report;
  if (!ctx.common.report_path.empty()) {
    report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    cli::AddReportInput(&report, "input", args.input);
    const io::Json body = smoother.summary().ToJson(series, opt.maneuver_time_s);
    for (auto it = body.begin(); it != body.end(); ++it) report[it.key()] = it.value();
    report["subcommand"] = "singer";
    report["rows_masked_by_status"] = masked;
    report["options"] = opt.ToJson();
  }
  io::OutputFile out(args.output);
  WriteSingerCsv(series, smoother, args, &out);
  out.Commit();
  if (!ctx.common.report_path.empty()) cli::WriteReport(ctx.common.report_path, report);
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

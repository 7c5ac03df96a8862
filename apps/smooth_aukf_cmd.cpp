// rk-smooth aukf: adaptive UKF fixed-lead prediction (seed 000) with an optional unscented RTS
// smoother. Thin CLI over lib/filter/aukf_series.h; see docs/rk-smooth.md.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "filter/aukf_series.h"
#include "filter/series.h"
#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "smooth_commands.h"

namespace rk::app {

namespace {

struct AukfArgs {
  std::string input, output, columns, adapt = "auto", meas_sigma, q;
  filter::AukfOptions opt;
  filter::AukfOutputOptions out;
  io::BadRows bad_rows = io::BadRows::kError;
};

std::vector<double> ParseNumbers(const std::string& list, const std::string& option) {
  std::vector<double> v;
  if (list.empty()) return v;
  for (const auto& item : io::SplitList(list)) {
    try {
      std::size_t used = 0;
      const double x = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(x)) throw std::invalid_argument(item);
      v.push_back(x);
    } catch (const std::exception&) {
      throw UsageError(option + ": '" + item + "' is not a number");
    }
  }
  return v;
}

// The filter options from the flags: the table's, --adapt, the memory (--fading given: fading, else the
// window), the noise lists (one value or one per column; file units → radians for angle columns). Throws
// UsageError.
filter::AukfOptions AukfOptionsOf(const AukfArgs& a, const CLI::App& sub, std::vector<std::string>* columns_out) {
  filter::AukfOptions opt = a.opt;
  if (!filter::ParseAdaptMode(a.adapt == "auto" ? "none" : a.adapt, &opt.adapt.mode)) {
    throw UsageError("--adapt: unknown mode " + a.adapt);
  }
  if (sub.count("--fading") > 0) {
    opt.adapt.memory = filter::AdaptMemory::kFading;
    if (sub.count("--window") > 0) throw UsageError("--window and --fading exclude each other");
  }
  const std::vector<std::string> columns = io::SplitList(a.columns);
  *columns_out = columns;
  if (columns.empty() || columns.size() > static_cast<std::size_t>(filter::ukf::kMaxColumns)) {
    throw UsageError("--columns: give 1 to 12 columns, got " + std::to_string(columns.size()));
  }
  opt.meas_sigma = ParseNumbers(a.meas_sigma, "--meas-sigma");
  opt.q = ParseNumbers(a.q, "--q");
  for (const auto* list : {&opt.meas_sigma, &opt.q}) {
    if (list->size() > 1 && list->size() != columns.size()) {
      throw UsageError(std::string(list == &opt.q ? "--q" : "--meas-sigma") +
                       ": give one value or one per column (" + std::to_string(columns.size()) + ")");
    }
  }
  // One value applies to every column; then file units → radians for angle columns.
  if (opt.meas_sigma.size() == 1) opt.meas_sigma.assign(columns.size(), opt.meas_sigma[0]);
  if (opt.q.size() == 1) opt.q.assign(columns.size(), opt.q[0]);
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (!filter::IsAngleColumn(columns[c])) continue;
    if (!opt.meas_sigma.empty()) opt.meas_sigma[c] = geo::DegToRad(opt.meas_sigma[c]);
    if (!opt.q.empty()) opt.q[c] *= geo::DegToRad(1.0) * geo::DegToRad(1.0);
  }
  return opt;
}

void CheckAukfPaths(const AukfArgs& a, const Context& ctx) {
  cli::CheckStreams(ctx.common, {{"-i", a.input}}, {{"-o", a.output}});
}

int RunAukfCommand(const AukfArgs& a, const CLI::App& sub, const Context& ctx) {
  std::vector<std::string> columns;
  const filter::AukfOptions opt = AukfOptionsOf(a, sub, &columns);
  CheckAukfPaths(a, ctx);

  const io::CsvTable table = io::CsvTable::Read(a.input, {a.bad_rows, filter::SeriesRowRule(columns)});
  const filter::Series series = filter::ReadSeries(table, columns, 3);
  const filter::AukfResult result = filter::RunAukf(series, opt);
  const io::CsvWriter csv = filter::AukfCsv(series, result, a.out);

  io::RunSummary summary = filter::AukfSummary(series, opt, result);
  summary.details["options"]["adapt_requested"] = a.adapt;
  io::Json report;
  if (!ctx.common.report_path.empty()) {
    report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    cli::AddReportInput(&report, "input", a.input);
    report["subcommand"] = "aukf";
    report["rows_written"] = csv.rows();
  }
  csv.Write(a.output);
  if (!ctx.common.report_path.empty()) cli::WriteReport(ctx.common.report_path, report, summary);
  cli::WarnAll(ctx.tool, ctx.common, summary);
  return 0;
}

}  // namespace

Command AddAukfCommand(CLI::App& app) {
  auto args = std::make_shared<AukfArgs>();
  CLI::App* sub = app.add_subcommand(
      "aukf",
      "Adaptive unscented Kalman filter with fixed-lead prediction (seed 000): per column a constant-"
      "acceleration state [p, p', p''] with white-jerk process noise; for each interval a prediction to "
      "t(k-1) + lead*tau (kind 'prediction'), a second half step and the measurement update (kind "
      "'estimate'). Adaptive R/Q from the innovations (Mohamed & Schwarz 1999). Columns ending _deg are "
      "wrap-safe angles. --smooth adds an unscented RTS pass (kind 'smoothed' at sample and mid-times).");
  sub->add_option("-i,--input", args->input, "Input CSV with t_s and the value columns ('-' = stdin)")
      ->required();
  cli::AddBadRowsOption(sub, &args->bad_rows);
  sub->add_option("--columns", args->columns,
                  "Comma-separated value columns, 1 to 12 (e.g. e_m,n_m,u_m,yaw_deg)")
      ->required();
  sub->add_option("-o,--output", args->output, "Output CSV ('-' = stdout)")->required();
  // The table's options, with --adapt and the noise lists at their places in --help.
  const auto add_adapt = [sub, args] {
    sub->add_option("--adapt", args->adapt,
                    "Adapt the noise from the innovations: none, r, q, qr, or auto (= none with the "
                    "data-estimated noise: "
                    "measured best on the turntable benchmark; r alone can diverge, see docs/rk-smooth.md)")
        ->check(CLI::IsMember({"auto", "none", "r", "q", "qr"}))
        ->capture_default_str();
  };
  const auto add_lists = [sub, args] {
    sub->add_option("--meas-sigma", args->meas_sigma,
                    "Initial measurement noise 1-sigma, one value or one per column, in file units (degrees for "
                    "_deg); default: estimated from the data (--noise-estimate)");
    sub->add_option("--q", args->q,
                    "White-jerk intensity q, one value or one per column, in file units^2/s^5 (deg^2/s^5 for "
                    "_deg); default: estimated from the data (--noise-estimate)");
  };
  cli::AddOptions(sub, &args->opt, filter::AukfOptions::Table(),
                  {{"--window", add_adapt}, {"--noise-estimate", add_lists}});
  cli::AddOptions(sub, &args->out, filter::AukfOutputOptions::Table());

  return {sub, [args, sub](const Context& ctx) { return RunAukfCommand(*args, *sub, ctx); }};
}

}  // namespace rk::app

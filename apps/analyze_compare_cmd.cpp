// rk-analyze compare: estimate vs reference statistics per column (SPEC.md §1.1). Thin CLI: the
// method lives in lib/analysis (analysis/compare.h), user page docs/rk-analyze.md.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/compare.h"
#include "analyze_commands.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"

namespace rk::app {
namespace {

struct CompareArgs {
  std::string est_path, ref_path, columns_arg, out_path, errors_path;
  double after_s = 0.0, before_s = 0.0;
  bool table = false;
  analysis::CompareOptions opt;
  CLI::Option* after_opt = nullptr;
  CLI::Option* before_opt = nullptr;
  io::BadRows bad_rows = io::BadRows::kError;
};

// The comparison options: a.opt (its table's options, parsed by CLI11) with --columns and --after/--before.
// Throws UsageError.
analysis::CompareOptions CompareOptionsOf(const CompareArgs& a) {
  analysis::CompareOptions opt = a.opt;
  opt.columns = io::SplitList(a.columns_arg);
  if (*a.after_opt) opt.after_s = a.after_s;
  if (*a.before_opt) opt.before_s = a.before_s;
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  return opt;
}

// One stdin input; -o, --errors, --table and --report: no output an input, no two on stdout.
void CheckComparePaths(const CompareArgs& a, const Context& ctx) {
  cli::CheckStreams(ctx.common, {{"--estimate", a.est_path}, {"--reference", a.ref_path}},
                    {{"--errors", a.errors_path}, {"-o", a.out_path, true}});
  if (a.table && io::IsStdStream(a.errors_path)) {
    throw UsageError("--table cannot share stdout with --errors -; write --errors to a file");
  }
}

// The statistics JSON (-o, and --report): inputs, options, rows, per column statistics.
io::Json CompareReport(const CompareArgs& a, const Context& ctx, const analysis::CompareOptions& opt,
                       const analysis::CompareResult& result) {
  io::Json report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
  cli::AddReportInput(&report, "estimate", a.est_path);
  cli::AddReportInput(&report, "reference", a.ref_path);
  report["options"] = {
      {"interp", track::InterpMethodName(opt.interp)},
      {"after_s", opt.after_s ? io::Json(*opt.after_s) : io::Json(nullptr)},
      {"before_s", opt.before_s ? io::Json(*opt.before_s) : io::Json(nullptr)},
      {"max_gap_s", std::isfinite(opt.max_gap_s) ? io::Json(opt.max_gap_s) : io::Json(nullptr)},
      {"arcsec", opt.arcsec},
      {"errors", "estimate - reference"},
      {"std", "sample (n-1)"},
      {"p95_abs", "type-7 linear-interpolated percentile of |error|"}};
  report["rows"] = {{"estimate", result.estimate_rows}, {"reference", result.reference_rows}};
  report["columns"] = analysis::ColumnsToJson(result);
  return report;
}

int RunCompare(const CompareArgs& a, const Context& ctx) {
  const analysis::CompareOptions opt = CompareOptionsOf(a);
  CheckComparePaths(a, ctx);
  const io::CsvReadOptions read{a.bad_rows, analysis::CompareRowRule(opt.columns)};
  const io::CsvTable estimate = io::CsvTable::Read(a.est_path, read);
  const io::CsvTable reference = io::CsvTable::Read(a.ref_path, read);
  const analysis::CompareResult result = analysis::Compare(estimate, reference, opt);
  const io::RunSummary summary = analysis::CompareSummary(result);
  cli::WarnAll(ctx.tool, ctx.common, summary);
  const io::Json report = CompareReport(a, ctx, opt, result);
  if (!a.errors_path.empty()) analysis::ErrorsCsv(result).Write(a.errors_path);
  io::WriteJson(a.out_path, report);
  if (!ctx.common.report_path.empty() && ctx.common.report_path != a.out_path) {
    cli::WriteReport(ctx.common.report_path, report, summary);
  }
  if (a.table) {
    const std::string text = analysis::FormatTable(result);
    if (io::IsStdStream(a.out_path)) {
      std::cerr << text;
    } else {
      std::cout << text;
    }
  }
  return 0;
}

}  // namespace

Command AddCompareCommand(CLI::App& parent) {
  CLI::App* compare =
      parent.add_subcommand("compare",
                            "Estimate vs reference: the reference interpolated at the estimate's times (no "
                            "extrapolation), errors = "
                            "estimate - reference per column, statistics n, max, min, mean, std (n-1), rms, "
                            "p95_abs. Columns ending _deg "
                            "are angles: unwrapped interpolation, errors wrapped to (-180, 180].");
  auto a = std::make_shared<CompareArgs>();
  auto& est_path = a->est_path;
  auto& ref_path = a->ref_path;
  auto& columns_arg = a->columns_arg;
  auto& out_path = a->out_path;
  auto& errors_path = a->errors_path;
  auto& after_s = a->after_s;
  auto& before_s = a->before_s;
  auto& table = a->table;
  compare->add_option("--estimate", est_path, "Estimate CSV with t_s and the columns ('-' = stdin)")
      ->required();
  compare->add_option("--reference", ref_path, "Reference CSV with t_s and the columns")->required();
  cli::AddBadRowsOption(compare, &a->bad_rows);
  compare
      ->add_option("--columns", columns_arg, "Comma-separated columns to compare, e.g. az_deg,el_deg,range_m")
      ->required();
  a->after_opt = compare->add_option("--after", after_s, "Use only estimate rows with t_s >= S");
  a->before_opt = compare->add_option("--before", before_s, "Use only estimate rows with t_s <= S");
  compare->add_option("-o,--output", out_path, "Statistics JSON ('-' = stdout)")->required();
  compare->add_option(
      "--errors", errors_path,
      "Also write the error series CSV: t_s,err_<C>... (file units, empty where not computed)");
  compare->add_flag("--table", table, "Print a fixed-width table to stdout (to stderr when -o is '-')");
  cli::AddOptions(compare, &a->opt, analysis::CompareOptions::Table());

  return {compare, [a](const Context& ctx) { return RunCompare(*a, ctx); }};
}

}  // namespace rk::app

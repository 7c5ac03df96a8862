// rk-analyze: error analysis. Subcommand `compare`: estimate vs reference
// statistics per column (SPEC.md §1.1). Thin CLI: the method lives in
// lib/analysis (analysis/compare.h).
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "analysis/compare.h"
#include "io/cli.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"

namespace {

const char* const kTool = "rk-analyze";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Error analysis of rangekit outputs against a reference (truth or another estimate).", kTool};
  app.require_subcommand(1);
  rk::cli::CommonOptions common;
  rk::cli::AddCommonOptions(app, kTool, &common);

  CLI::App* compare =
      app.add_subcommand("compare",
                         "Estimate vs reference: the reference interpolated at the estimate's times (no "
                         "extrapolation), errors = "
                         "estimate - reference per column, statistics n, max, min, mean, std (n-1), rms, "
                         "p95_abs. Columns ending _deg "
                         "are angles: unwrapped interpolation, errors wrapped to (-180, 180].");
  std::string est_path, ref_path, columns_arg, out_path, errors_path;
  double after_s = 0.0, before_s = 0.0;
  bool table = false;
  rk::analysis::CompareOptions opt;
  compare->add_option("--estimate", est_path, "Estimate CSV with t_s and the columns ('-' = stdin)")
      ->required();
  compare->add_option("--reference", ref_path, "Reference CSV with t_s and the columns")->required();
  compare
      ->add_option("--columns", columns_arg, "Comma-separated columns to compare, e.g. az_deg,el_deg,range_m")
      ->required();
  CLI::Option* after_opt = compare->add_option("--after", after_s, "Use only estimate rows with t_s >= S");
  CLI::Option* before_opt = compare->add_option("--before", before_s, "Use only estimate rows with t_s <= S");
  compare->add_option("-o,--output", out_path, "Statistics JSON ('-' = stdout)")->required();
  compare->add_option(
      "--errors", errors_path,
      "Also write the error series CSV: t_s,err_<C>... (file units, empty where not computed)");
  compare->add_flag("--table", table, "Print a fixed-width table to stdout (to stderr when -o is '-')");
  compare->add_flag("--arcsec", opt.arcsec,
                    "Statistics of _deg columns in arc-seconds (\"unit\": \"arcsec\")");
  std::string interp = "linear";
  compare->add_option("--interp", interp, "Reference interpolation: linear or cubic (4-point Lagrange)")
      ->check(CLI::IsMember({"linear", "cubic"}))
      ->capture_default_str();
  compare->add_option(
      "--max-gap", opt.max_gap_s,
      "Longest reference interval (s) interpolated across (default: no limit; empty reference "
      "values always break the interval)");

  return rk::cli::Run(app, kTool, argc, argv, [&]() -> int {
    if (!rk::track::ParseInterpMethod(interp, &opt.interp))
      throw rk::UsageError("unknown --interp " + interp);
    opt.columns = rk::io::SplitList(columns_arg);
    if (*after_opt) opt.after_s = after_s;
    if (*before_opt) opt.before_s = before_s;
    std::string why;
    if (!opt.Check(&why)) throw rk::UsageError(why);
    if (rk::io::IsStdStream(est_path) && rk::io::IsStdStream(ref_path)) {
      throw rk::UsageError("only one input can be read from stdin ('-')");
    }
    if (!errors_path.empty() && rk::io::IsStdStream(errors_path) && rk::io::IsStdStream(out_path)) {
      throw rk::UsageError("--errors and -o cannot both be stdout");
    }
    if (table && rk::io::IsStdStream(errors_path)) {
      throw rk::UsageError("--table cannot share stdout with --errors -; write --errors to a file");
    }
    const std::vector<std::string> inputs = {est_path, ref_path};
    rk::io::CheckOutputNotInput(out_path, inputs);
    if (!errors_path.empty()) rk::io::CheckOutputNotInput(errors_path, inputs);
    if (!common.report_path.empty()) rk::io::CheckOutputNotInput(common.report_path, inputs);
    if (!errors_path.empty() && errors_path == out_path && !rk::io::IsStdStream(out_path)) {
      throw rk::UsageError("--errors and -o name the same file " + out_path);
    }

    const rk::io::CsvTable estimate = rk::io::CsvTable::Read(est_path);
    const rk::io::CsvTable reference = rk::io::CsvTable::Read(ref_path);
    const rk::analysis::CompareResult result = rk::analysis::Compare(estimate, reference, opt);
    for (const auto& cc : result.columns) {
      if (!cc.stats) {
        rk::cli::Warn(kTool, common,
                      "column " + cc.column + ": no comparable row (estimate empty " +
                          std::to_string(cc.skipped_estimate_empty) + ", reference outside " +
                          std::to_string(cc.skipped_reference_outside) + ", reference gap " +
                          std::to_string(cc.skipped_reference_gap) + ", cut by --after/--before " +
                          std::to_string(cc.skipped_time_window) + "); statistics are null");
      }
    }

    rk::io::Json report = rk::cli::MakeReport(kTool, argc, argv);
    rk::cli::AddReportInput(&report, "estimate", est_path);
    rk::cli::AddReportInput(&report, "reference", ref_path);
    report["options"] = {
        {"interp", rk::track::InterpMethodName(opt.interp)},
        {"after_s", opt.after_s ? rk::io::Json(*opt.after_s) : rk::io::Json(nullptr)},
        {"before_s", opt.before_s ? rk::io::Json(*opt.before_s) : rk::io::Json(nullptr)},
        {"max_gap_s", std::isfinite(opt.max_gap_s) ? rk::io::Json(opt.max_gap_s) : rk::io::Json(nullptr)},
        {"arcsec", opt.arcsec},
        {"errors", "estimate - reference"},
        {"std", "sample (n-1)"},
        {"p95_abs", "type-7 linear-interpolated percentile of |error|"}};
    report["rows"] = {{"estimate", result.estimate_rows}, {"reference", result.reference_rows}};
    report["columns"] = rk::analysis::ColumnsToJson(result);

    if (!errors_path.empty()) rk::analysis::ErrorsCsv(result).Write(errors_path);
    rk::io::WriteJson(out_path, report);
    if (!common.report_path.empty() && common.report_path != out_path) {
      rk::io::WriteJson(common.report_path, report);
    }
    if (table) {
      const std::string text = rk::analysis::FormatTable(result);
      if (rk::io::IsStdStream(out_path)) {
        std::cerr << text;
      } else {
        std::cout << text;
      }
    }
    return 0;
  });
}

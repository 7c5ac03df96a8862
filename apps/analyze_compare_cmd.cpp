// rk-analyze compare: estimate vs reference statistics per column (SPEC.md §1.1). Thin CLI: the
// method lives in lib/analysis (analysis/compare.h), user page docs/rk-analyze.md.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "analysis/compare.h"
#include "analyze_commands.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"

namespace rk::app {
namespace {

struct CompareArgs {
  std::string est_path, ref_path, columns_arg, out_path, errors_path, interp = "linear";
  double after_s = 0.0, before_s = 0.0;
  bool table = false;
  analysis::CompareOptions opt;
  CLI::Option* after_opt = nullptr;
  CLI::Option* before_opt = nullptr;
  io::BadRows bad_rows = io::BadRows::kError;
};

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
  auto& opt = a->opt;
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
  compare->add_flag("--arcsec", opt.arcsec,
                    "Statistics of _deg columns in arc-seconds (\"unit\": \"arcsec\")");
  auto& interp = a->interp;
  compare->add_option("--interp", interp, "Reference interpolation: linear or cubic (4-point Lagrange)")
      ->check(CLI::IsMember({"linear", "cubic"}))
      ->capture_default_str();
  compare->add_option(
      "--max-gap", opt.max_gap_s,
      "Longest reference interval (s) interpolated across (default: no limit; empty reference "
      "values always break the interval)");

  return {
      compare, [a](const Context& ctx) -> int {
        analysis::CompareOptions opt = a->opt;
        const auto& est_path = a->est_path;
        const auto& ref_path = a->ref_path;
        const auto& out_path = a->out_path;
        const auto& errors_path = a->errors_path;
        const auto& interp = a->interp;
        const bool table = a->table;
        const auto& common = ctx.common;
        const int argc = ctx.argc;
        char** const argv = ctx.argv;
        if (!rk::track::ParseInterpMethod(interp, &opt.interp))
          throw rk::UsageError("unknown --interp " + interp);
        opt.columns = rk::io::SplitList(a->columns_arg);
        if (*a->after_opt) opt.after_s = a->after_s;
        if (*a->before_opt) opt.before_s = a->before_s;
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

        const rk::io::CsvReadOptions read{a->bad_rows, rk::analysis::CompareRowRule(opt.columns)};
        const rk::io::CsvTable estimate = rk::io::CsvTable::Read(est_path, read);
        const rk::io::CsvTable reference = rk::io::CsvTable::Read(ref_path, read);
        const rk::analysis::CompareResult result = rk::analysis::Compare(estimate, reference, opt);
        for (const auto& cc : result.columns) {
          if (!cc.stats) {
            rk::cli::Warn(ctx.tool, common,
                          "column " + cc.column + ": no comparable row (estimate empty " +
                              std::to_string(cc.skipped_estimate_empty) + ", reference outside " +
                              std::to_string(cc.skipped_reference_outside) + ", reference gap " +
                              std::to_string(cc.skipped_reference_gap) + ", cut by --after/--before " +
                              std::to_string(cc.skipped_time_window) + "); statistics are null");
          }
        }

        rk::io::Json report = rk::cli::MakeReport(ctx.tool, argc, argv);
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
          rk::cli::WriteReport(common.report_path, report);
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
      }};
}

}  // namespace rk::app

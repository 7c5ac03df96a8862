// The trial report page TRIAL/out/report.html (docs/rk-run.md, "The report page"): rk-run asks
// scripts/rk-report for it once at the end of a run. The page is a view of out/, not a product: it is not in
// report.json, no step depends on it, and failing to make it is a warning, never a failed run.
#pragma once

#include <string>
#include <vector>

namespace rk::run {

inline constexpr const char* kReportPageTool = "rk-report";
inline constexpr const char* kReportPageFile = "report.html";

// Runs `rk-report OUT --quiet` (found in `tool_dirs`, then on PATH) on TRIAL/out when `rebuilt` (a new out/
// was just committed) or when out/report.html is missing or older than out/report.json. Its output and
// errors go to out/steps/report-page.log. Returns "" when the page is made or already current, else the
// one-line reason it is not (tool missing, its error line, interrupted). `no_figures`: tables and warnings only
// (rk-report --no-figures), for a run with --no-plots that replaced an out/ that had a page.
// `out_path`: TRIAL/out or rk-run --out DIR.
std::string MakeReportPage(const std::string& trial_dir, const std::string& out_path,
                           const std::vector<std::string>& tool_dirs, bool rebuilt, bool no_figures = false);

}  // namespace rk::run

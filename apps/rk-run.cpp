// rk-run: the whole chain for one trial manifest, idempotent and safe to repeat (SPEC.md §1,
// docs/rk-run.md). Thin CLI over lib/run (run/runner.h): the tools themselves run as child processes.
#include <CLI/CLI.hpp>
#include <iostream>
#include <mutex>
#include <string>
#include <vector>

#include "io/cli.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "run/process.h"
#include "run/runner.h"

namespace {

const char* const kTool = "rk-run";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Run the whole chain for one trial: every step the manifest calls for (rk-extract, rk-locate, "
      "rk-smooth, rk-attitude, rk-register, rk-plot) into TRIAL/out/, with report.json. Steps whose inputs, "
      "options and tool are unchanged since the last good run are skipped; a failed run leaves the previous "
      "out/ intact; a lock keeps two runs of one trial apart (docs/rk-run.md).",
      kTool};
  rk::cli::CommonOptions common;
  rk::cli::AddCommonOptions(app, kTool, &common);
  rk::run::RunOptions opt;
  std::string bin_dir;
  bool no_plots = false;
  app.add_option("trial", opt.trial, "Trial manifest trial.json, or the trial folder that holds it")->required();
  rk::cli::AddOptions(&app, &opt, rk::run::RunOptions::Table(),
                      {{"--jobs", [&] {
                         app.add_flag("--no-plots", no_plots,
                                      "Draw nothing this time (no plot, no page figures); nothing already drawn is deleted");
                       }}});
  app.add_option("--out", opt.out_dir,
                 "Folder for the products instead of TRIAL/out (a trial on a read-only disk); rk-run's lock, log and "
                 "last-run.json go beside it as .DIR.rk-run.lock, DIR.rk-run.log, DIR.last-run.json");
  app.add_option("--tool-cache", opt.tool_cache,
                 "JSON file where tool identities (--version, SHA-256) are kept between runs, so that many "
                 "trials ask each tool once (rk-nightly passes one)");
  app.add_option("--bin", bin_dir, "Folder searched first for the tools (then rk-run's own folder, then PATH)");

  return rk::cli::Run(app, kTool, argc, argv, [&]() -> int {
    opt.plots = !no_plots;
    opt.command_line.assign(argv, argv + argc);
    if (!bin_dir.empty()) opt.tool_dirs.push_back(bin_dir);
    const std::string self = rk::run::SelfDir();
    if (!self.empty()) opt.tool_dirs.push_back(self);
    if (!common.report_path.empty()) {
      rk::io::CheckOutputNotInput(common.report_path, {opt.trial});
    }
    const bool progress = rk::cli::ShowProgress(common);
    // Event lines ("extract-az: run (...)") and, between them, the running steps' own progress redrawn in
    // place (from rk-run's watcher thread, hence the lock).
    std::mutex stderr_mu;
    if (progress) {
      opt.progress = [&stderr_mu](const std::string& line) {
        std::lock_guard<std::mutex> lock(stderr_mu);
        std::cerr << "\r\x1b[K" << kTool << ": " << line << "\n" << std::flush;
      };
      opt.step_progress = [&stderr_mu](const std::string& line) {
        std::lock_guard<std::mutex> lock(stderr_mu);
        std::cerr << "\r" << kTool << ": " << line << "\x1b[K" << std::flush;
      };
    }
    rk::run::InstallStopHandlers();
    const rk::run::RunSummary s = rk::run::RunTrial(opt);
    if (progress) std::cerr << "\r\x1b[K" << std::flush;  // the last progress redraw
    if (!common.report_path.empty()) rk::cli::WriteReport(common.report_path, s.summary);
    if (s.result == rk::run::TrialResult::kFailed || s.result == rk::run::TrialResult::kLocked) {
      throw rk::Error(s.exit_code, s.error);
    }
    // The plan per unit (planned, skipped and why) on stderr, terminal or not, unless --quiet.
    if (!common.quiet) {
      for (const auto& line : s.units) std::cerr << kTool << ": " << line << "\n";
    }
    // The table goes to stdout unless --quiet, or unless --report - already writes JSON there.
    const bool report_on_stdout = rk::io::IsStdStream(common.report_path);
    if ((opt.dry_run || !common.quiet) && !report_on_stdout) std::cout << rk::run::SummaryTable(s) << std::flush;
    if (s.steps_warned > 0 && !common.quiet) {
      for (const auto& l : s.steps) {
        if (l.status == "warning") rk::cli::Warn(kTool, common, l.id + ": " + l.reason);
      }
    }
    return 0;
  });
}

// rk-run's engine: one trial, one call (docs/rk-run.md).
//   lock → finish/clean interrupted swaps → read trial.json → plan the steps → fingerprint each step
//   (inputs' SHA-256, command line and options, tool version and executable, upstream steps) → skip
//   the steps whose fingerprint matches the last good run and whose products are intact → run the
//   others as child processes into TRIAL/out.tmp.XXXXXX (products of skipped steps hard-linked in) →
//   report.json → atomic swap into TRIAL/out/.
// A failure leaves the previous out/ untouched; every attempt is appended to TRIAL/rk-run.log and
// summarised in TRIAL/last-run.json.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "io/error.h"
#include "io/json_util.h"
#include "io/options.h"

namespace rk::run {

struct RunOptions {
  std::string trial;            // trial.json, or the trial folder
  // The products' folder instead of TRIAL/out ("" = TRIAL/out), e.g. for a trial on a read-only disk;
  // rk-run's lock, log and last-run.json then go beside it (docs/rk-run.md "--out").
  std::string out_dir;
  bool force = false;           // re-run every step
  bool dry_run = false;         // only say what would run and why (no lock, nothing written)
  bool keep_going = false;      // after a failure, still run the steps that do not depend on it
  bool rehash = false;          // hash every input (ignore the size+mtime shortcut)
  bool plots = true;            // plot steps (rk-plot)
  int jobs = 1;                 // steps run at the same time, 1..64
  double wait_lock_s = 0.0;     // wait this long for another run's lock (0 = fail at once)
  std::vector<std::string> tool_dirs;  // folders searched for the tools before PATH
  std::string tool_cache;       // JSON file of tool identities shared between runs ("" = none)
  std::vector<std::string> command_line;  // for the report
  std::function<void(const std::string&)> progress;  // one line per event, may be empty
  // The running steps' own progress (done/total, rate, ETA of each tool that reports it through
  // io::cli::ProgressMeter's RK_PROGRESS_FILE), one line redrawn about twice a second; empty = none
  // (then the tools are not asked for it).
  std::function<void(const std::string&)> step_progress;
  // The command-line options above, described once (io::OptionTable).
  static const io::OptionTable<RunOptions>& Table();
  bool Check(std::string* why) const;
};

enum class TrialResult { kDone, kUpToDate, kFailed, kLocked, kPlanned };
const char* TrialResultName(TrialResult r);  // "done", "up-to-date", "failed", "locked", "planned"

struct StepLine {  // one row of the summary table
  std::string id, status, reason;
  double wall_s = 0.0;
};

struct RunSummary {
  TrialResult result = TrialResult::kFailed;
  ExitCode exit_code = ExitCode::kOk;
  std::string error;      // the one-line error (empty on success)
  std::string trial_dir;  // absolute
  std::string name;       // trial name
  io::Json summary;       // what TRIAL/last-run.json and --report get
  std::vector<StepLine> steps;
  // One line per unit of the trial: the steps planned and skipped and why (run/plan.h UnitPlan::Line); rk-run
  // prints them on stderr after a run that did not fail, unless --quiet (a failed run prints its one error line).
  std::vector<std::string> units;
  int steps_run = 0, steps_skipped = 0, steps_failed = 0, steps_warned = 0;
  double wall_s = 0.0, tool_time_s = 0.0, tool_cpu_s = 0.0;
};

// Runs (or plans) one trial. Step failures are returned in the summary, not thrown; IoError is
// thrown only when the trial folder itself cannot be used (no lock file can be made).
RunSummary RunTrial(const RunOptions& options);

// The short text table rk-run prints (one line per step).
std::string SummaryTable(const RunSummary& summary);

}  // namespace rk::run

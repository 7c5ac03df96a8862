// rk-run's engine inside (internal to lib/run; the interface is run/runner.h). One TrialRun runs one
// trial in stages, each in its own file:
//   runner.cc      resolve the trial, lock, plan (BuildPlan), gather the facts and decide (Decide,
//                  decide.cc), then execute and commit, and the summary
//   execute.cc     run the steps as child processes (fork/kill scheduling), the steps' logs and errors
//   run_report.cc  out/report.json and TRIAL/last-run.json
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/error.h"
#include "io/json_util.h"
#include "run/decide.h"
#include "run/digest.h"
#include "run/manifest.h"
#include "run/plan.h"
#include "run/process.h"
#include "run/step_progress.h"
#include "run/run_log.h"
#include "run/runner.h"
#include "run/tools.h"
#include "run/trial_dir.h"

namespace rk::run::internal {

// Copies every member of a tool report's "summary" object into a step's quality figures `quality`
// (run_report.cc), except a name the figures already have; no per-kind code (docs/rk-run.md).
void AddToolSummary(const io::Json& tool_report, io::Json* quality);

// One step of the plan with its decision and outcome.
struct StepRun {
  explicit StepRun(const Step& s) : step(s) {}
  const Step& step;  // in TrialRun::plan_
  const ToolIdentity* tool = nullptr;
  io::Json key_parts;
  std::string key;
  Decision decision = Decision::kInactive;
  std::string reason;
  const io::Json* previous = nullptr;  // this step's entry in the last good report
  // Outcome
  std::string status;  // "ok", "skipped", "failed", "warning", "not-run", "off", "not-applicable"
  ChildResult child;
  std::string ran_utc;
  std::string error;
  std::vector<std::string> log_tail;
  bool started = false, finished = false;
  // A plot step that --no-plots leaves undrawn with nothing to keep: not listed anywhere (as if not
  // planned), so that a run with --no-plots reports what it did.
  bool Unlisted() const { return status == "off" && step.kind == "plot" && reason == "--no-plots"; }
};

class TrialRun {
 public:
  explicit TrialRun(const RunOptions& o) : o_(o), t0_(std::chrono::steady_clock::now()), started_utc_(UtcNow()) {}

  RunSummary Run();

 private:
  void Say(const std::string& s) {
    if (o_.progress) o_.progress(s);
    if (log_) log_->Line(s);
  }

  void Fail(ExitCode code, const std::string& error) {
    if (s_.error.empty()) {
      s_.exit_code = code;
      s_.error = error;
    }
    failed_ = true;
  }
  // runner.cc
  void ResolveTrial();
  bool Lock(std::unique_ptr<TrialLock>* lock);
  bool PlanDecideExecute();
  void Plan();
  void LoadRecords();
  void GatherFacts(std::vector<StepFacts>* facts);
  void CheckStepOptions(const Step& st, const ToolIdentity& tool);
  void Decide();
  void WriteToolCache();
  void DryRunSummary();
  void Commit();
  void ReportPage(bool rebuilt);
  void WriteRunning();
  void WriteLastRun();
  void Finish();
  // execute.cc
  void Execute();
  void LinkSkippedProducts();
  void LaunchReady(const std::map<std::string, std::size_t>& index, std::map<pid_t, std::size_t>* running);
  void StartStep(std::size_t i, std::map<pid_t, std::size_t>* running);
  void KillChildren(std::map<pid_t, std::size_t>* running);
  void FinishStep(StepRun* r);
  std::string FailureMessage(const StepRun& r, const std::string& line) const;
  std::string FinalOutPaths(std::string text) const;
  bool TooFewSamples(const StepRun& r) const;
  // run_report.cc
  io::Json StepJson(const StepRun& r, bool full) const;
  io::Json StepOutcomeJson(const StepRun& r) const;
  io::Json BuildReport() const;
  io::Json BuildSummaryJson() const;
  io::Json UnitsJson() const;

  const RunOptions& o_;
  std::chrono::steady_clock::time_point t0_;
  std::string started_utc_;
  RunSummary s_;
  std::string manifest_file_;
  std::string user_dir_;  // the trial folder as the user named it (for messages)
  // Where the products and rk-run's own files go (ResolveTrial): TRIAL/out, TRIAL/.rk-run.lock,
  // TRIAL/rk-run.log, TRIAL/last-run.json; with --out DIR: DIR, and DIR's name with .rk-run.lock (hidden),
  // .rk-run.log, .last-run.json beside it (a read-only trial folder can be reprocessed).
  std::string out_, lock_file_, log_file_, last_run_file_;
  std::unique_ptr<RunLog> log_;
  std::unique_ptr<TrialManifest> m_;
  io::Json previous_;  // last good out/report.json (or null)
  std::unique_ptr<DigestCache> digests_;
  std::unique_ptr<Tools> tools_;
  std::vector<Step> plan_;
  std::vector<UnitPlan> units_;  // the plan per unit (PlanByUnit)
  std::vector<StepRun> runs_;  // one per step of plan_
  std::string work_;      // absolute working folder
  std::string work_rel_;  // its name (relative to the trial folder)
  bool failed_ = false;
  bool rebuild_ = false;  // a new out/ is needed even if no step runs
  std::string rebuild_reason_;
  bool had_page_ = false;  // the out/ that Commit replaced had a report page
  std::string page_warning_;  // why out/report.html was not made ("" = made, current or not asked for)
  // The running steps' progress files (o_.step_progress only): step id → (file, start time). Written by
  // the main thread (StartStep, FinishStep), read by the watcher thread (step_progress.cc).
  StepProgressFiles progress_files_;
};

}  // namespace rk::run::internal

// rk-run's engine, the stages of one trial (see run/trial_run.h for the files of the others).
#include "run/runner.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <set>
#include <sstream>

#include "io/version.h"
#include "run/previous_report.h"
#include "run/report_page.h"
#include "run/sha256.h"
#include "run/trial_dir.h"
#include "run/trial_run.h"
#include "trial/layout.h"

namespace rk::run {
namespace fs = std::filesystem;
using io::Json;

const char* TrialResultName(TrialResult r) {
  switch (r) {
    case TrialResult::kDone: return "done";
    case TrialResult::kUpToDate: return "up-to-date";
    case TrialResult::kFailed: return "failed";
    case TrialResult::kLocked: return "locked";
    case TrialResult::kPlanned: return "planned";
  }
  return "?";
}

const io::OptionTable<RunOptions>& RunOptions::Table() {
  using O = RunOptions;
  using B = io::Bounds;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Flag("--force", &O::force, "Re-run every step, even those that are up to date")
          .Alias("-f")
          .Flag("--dry-run", &O::dry_run, "Only print which steps would run and why (no lock taken, nothing written)")
          .Alias("-n")
          .Flag("--keep-going", &O::keep_going,
                "After a failed step, still run the steps that do not depend on it (the run still fails)")
          .Alias("-k")
          .Flag("--rehash", &O::rehash,
                "Hash every input and tool again instead of trusting unchanged size + modification time")
          .Integer("--jobs", &O::jobs, "", B::Closed(1, 64), "Steps run at the same time (1..64)")
          .Alias("-j")
          .Real("--wait-lock", &O::wait_lock_s, "s", B::Closed(0, 7 * 86400.0),
                "If another rk-run holds this trial, wait up to S seconds for it (0 = fail at once)");
  return table;
}

bool RunOptions::Check(std::string* why) const {
  if (trial.empty()) {
    *why = "no trial given";
    return false;
  }
  return Table().Check(*this, why);
}

namespace internal {

// The manifest file and trial folder from what the user gave (trial.json or its folder).
void TrialRun::ResolveTrial() {
  std::error_code ec;
  fs::path given(o_.trial);
  manifest_file_ = fs::is_directory(given, ec) ? (given / trial::kManifestFile).string() : given.string();
  user_dir_ = fs::is_directory(given, ec) ? given.string() : given.parent_path().string();
  if (user_dir_.empty()) user_dir_ = ".";
  manifest_file_ = fs::absolute(manifest_file_, ec).lexically_normal().string();
  s_.trial_dir = fs::path(manifest_file_).parent_path().string();
  s_.name = fs::path(s_.trial_dir).filename().string();
  if (!fs::is_regular_file(manifest_file_, ec)) {
    throw IoError(manifest_file_, fs::exists(manifest_file_, ec) ? "is not a file" : "no such trial manifest");
  }
}

// Takes the trial lock and opens the run log; false (with the "locked" summary) when another rk-run
// holds the lock.
bool TrialRun::Lock(std::unique_ptr<TrialLock>* lock) {
  std::string holder;
  *lock = TrialLock::Acquire(s_.trial_dir, o_.wait_lock_s, &holder);
  if (!*lock) {
    s_.result = TrialResult::kLocked;
    s_.exit_code = ExitCode::kIo;
    s_.error = s_.trial_dir + ": locked by another rk-run (" + holder + ")";
    s_.wall_s = Seconds(t0_);
    s_.summary = BuildSummaryJson();
    return false;
  }
  log_ = std::make_unique<RunLog>(s_.trial_dir);
  std::string cl;
  for (const auto& a : o_.command_line) cl += (cl.empty() ? "" : " ") + a;
  log_->Line("start: " + cl + " (rk-run " + kVersion + ")");
  return true;
}

void TrialRun::Plan() {
  m_ = std::make_unique<TrialManifest>(LoadManifest(manifest_file_));
  s_.name = m_->name;
  PlanOptions po;
  po.plots = o_.plots;
  plan_ = BuildPlan(*m_, po);
  runs_.reserve(plan_.size());
  for (const auto& step : plan_) runs_.emplace_back(step);
  // Per unit: the steps planned and skipped and why; then a product the manifest asks for and the plan
  // cannot make fails the run (DataError at its place in trial.json, exit 3) before anything runs.
  units_ = PlanByUnit(*m_, plan_);
  for (const UnitPlan& u : units_) {
    s_.units.push_back(u.Line());
    if (log_) log_->Line("plan: " + u.Line());
  }
  CheckRequestedProducts(*m_, plan_);
}

// The last good report (trusted only if IsUsableReport), the input digests and the tool identities
// with the shortcuts it records.
void TrialRun::LoadRecords() {
  previous_ = LoadJsonOrNull((fs::path(s_.trial_dir) / kOutDir / kReportFile).string());
  if (!previous_.is_null() && !IsUsableReport(previous_)) {
    if (previous_.is_object() && previous_.value("tool", Json()) == "rk-run") Say("warning: out/report.json is damaged; every step runs again");
    previous_ = Json(nullptr);
  }
  digests_ = std::make_unique<DigestCache>(s_.trial_dir, previous_.is_object() ? previous_.value("inputs", Json()) : Json(),
                                           !o_.rehash);
  digests_->Digest(fs::path(manifest_file_).filename().string());
  const Json shared = o_.tool_cache.empty() ? Json() : LoadJsonOrNull(o_.tool_cache);
  tools_ = std::make_unique<Tools>(o_.tool_dirs, previous_.is_object() ? previous_.value("tools", Json()) : Json(),
                                   shared, !o_.rehash);
}

// The tool and input digests of each active step, in plan order (one StepFacts per step pushed so
// far). A step blocked upstream or lacking its tool gets no digests. A missing tool of a step that is
// not warn_only, an unreadable input or a tool that does not answer --version throws; the reason of
// the step being gathered then stays as the original engine left it (blocked by upstream, or "").
void TrialRun::GatherFacts(std::vector<StepFacts>* facts) {
  std::set<std::string> cannot_run;
  for (std::size_t i = 0; i < plan_.size(); ++i) {
    const Step& st = plan_[i];
    StepFacts f;
    if (st.state == PlanState::kActive) {
      runs_[i].reason = BlockedBy(st, cannot_run);
      f.tool = tools_->Get(st.tool);
      if (!f.tool && !st.warn_only) {
        throw IoError(st.tool, std::string("not found next to rk-run") +
                                   (o_.tool_dirs.empty() ? "" : " (" + o_.tool_dirs.back() + ")") +
                                   " or on PATH; needed by step " + st.id);
      }
      if (!f.tool || !runs_[i].reason.empty()) {
        cannot_run.insert(st.id);
      } else {
        for (const auto& in : st.inputs) f.input_sha256.push_back(digests_->Digest(in.path).sha256);
      }
    }
    facts->push_back(std::move(f));
  }
}

// Gathers the facts and applies the pure Decide() to the steps. When gathering stops at a step (an
// error), the steps before it are still decided, so that the summary shows them.
void TrialRun::Decide() {
  std::vector<StepFacts> facts;
  std::exception_ptr stop;
  try {
    GatherFacts(&facts);
  } catch (...) {
    stop = std::current_exception();
  }
  const fs::path out = fs::path(s_.trial_dir) / kOutDir;
  DecideInput in;
  in.steps = std::span<const Step>(plan_.data(), facts.size());
  in.facts = facts;
  in.previous = previous_.is_object() ? &previous_ : nullptr;
  if (in.previous) in.out_files = ProbeOutFiles(out.string(), previous_);
  std::error_code ec;
  in.out_dir_exists = fs::is_directory(out, ec);
  in.manifest_sha256 = Sha256Hex(m_->text);
  in.force = o_.force;
  const RunDecision d = run::Decide(in);
  for (std::size_t i = 0; i < d.steps.size(); ++i) {
    StepRun& r = runs_[i];
    const StepDecision& sd = d.steps[i];
    r.tool = facts[i].tool;
    r.decision = sd.decision;
    r.status = sd.status;
    r.reason = sd.reason;
    r.key_parts = sd.key_parts;
    r.key = sd.key;
    r.previous = sd.previous;
  }
  if (stop) std::rethrow_exception(stop);
  rebuild_ = d.rebuild;
  rebuild_reason_ = d.rebuild_reason;
}

// Re-reads and merges the --tool-cache file: other trials of the same nightly run may have added
// tools meanwhile.
void TrialRun::WriteToolCache() {
  if (o_.tool_cache.empty() || !tools_->shared_changed()) return;
  try {
    Json merged = LoadJsonOrNull(o_.tool_cache);
    if (!merged.is_object()) merged = Json::object();
    for (const auto& [k, v] : tools_->shared().items()) merged[k] = v;
    io::WriteJson(o_.tool_cache, merged);
  } catch (const Error& e) {
    Say(std::string("warning: tool cache not written: ") + e.what());
  }
}

void TrialRun::DryRunSummary() {
  s_.result = TrialResult::kPlanned;
  for (const auto& r : runs_) {
    std::string st = r.decision == Decision::kRun ? "would run" : r.status;
    s_.steps.push_back({r.step.id, st, r.reason, 0.0});
  }
  s_.steps_skipped = static_cast<int>(std::count_if(runs_.begin(), runs_.end(), [](const StepRun& r) { return r.decision == Decision::kSkip; }));
  s_.steps_run = static_cast<int>(std::count_if(runs_.begin(), runs_.end(), [](const StepRun& r) { return r.decision == Decision::kRun; }));
  s_.summary = BuildSummaryJson();
  s_.summary["rebuild_out"] = rebuild_;
  if (rebuild_) s_.summary["rebuild_reason"] = rebuild_reason_;
  s_.wall_s = Seconds(t0_);
}

// out/report.json into the working folder, then the atomic swap into out/.
void TrialRun::Commit() {
  const Json rep = BuildReport();
  const std::string rp = (fs::path(work_) / kReportFile).string();
  io::WriteJson(rp, rep);
  SyncPath(rp);
  const std::string how = CommitOut(s_.trial_dir, work_);
  work_.clear();
  s_.result = TrialResult::kDone;
  Say("out/ replaced (" + how + ")");
}

// Everything between the lock and the summary; true when a dry run is complete (s_ is final).
bool TrialRun::PlanDecideExecute() {
  if (!o_.dry_run) {
    for (const auto& n : RecoverAndClean(s_.trial_dir)) Say(n);
  }
  Plan();
  LoadRecords();
  Decide();
  WriteToolCache();
  if (o_.dry_run) {
    DryRunSummary();
    return true;
  }
  if (!rebuild_) {
    s_.result = TrialResult::kUpToDate;
    s_.steps_skipped = static_cast<int>(runs_.size());
    Say("up to date: nothing to run");
    ReportPage(false);
  } else {
    Say("building a new out/: " + rebuild_reason_);
    Execute();
    if (!failed_) {
      Commit();
      ReportPage(true);
    }
  }
  return false;
}

// The summary table's lines, TRIAL/last-run.json and the result line.
void TrialRun::Finish() {
  if (failed_) {
    s_.result = TrialResult::kFailed;
    if (!work_.empty()) RemoveOutTree(work_);
  }
  for (const auto& r : runs_) {
    double w = r.decision == Decision::kRun && r.child.pid > 0 ? r.child.wall_s : 0.0;
    s_.steps.push_back({r.step.id, r.status.empty() ? "?" : r.status, r.reason, w});
  }
  s_.wall_s = Seconds(t0_);
  s_.summary = BuildSummaryJson();
  if (!page_warning_.empty()) s_.summary["report_page_warning"] = page_warning_;
  if (!o_.dry_run) {
    try {
      io::WriteJson((fs::path(s_.trial_dir) / "last-run.json").string(), s_.summary);
    } catch (const Error& e) {
      Say(std::string("warning: ") + e.what());
    }
    Say(std::string("result: ") + TrialResultName(s_.result) +
        (s_.error.empty() ? "" : " (exit " + std::to_string(static_cast<int>(s_.exit_code)) + "): " + s_.error) +
        " in " + Fmt(s_.wall_s) + " s");
  }
}

// out/report.html (run/report_page.h) with --plots only: --no-plots makes no figure of any kind. A page that
// cannot be made is a warning in the log and the summary; the run still succeeds.
void TrialRun::ReportPage(bool rebuilt) {
  if (!o_.plots) return;
  page_warning_ = MakeReportPage(s_.trial_dir, o_.tool_dirs, rebuilt);
  if (page_warning_.empty()) return;
  page_warning_ = "report page not made: " + page_warning_;
  Say("warning: " + page_warning_);
}

RunSummary TrialRun::Run() {
  ResolveTrial();
  std::unique_ptr<TrialLock> lock;  // held until the summary is written
  if (!o_.dry_run && !Lock(&lock)) return s_;
  try {
    if (PlanDecideExecute()) return s_;
  } catch (const Error& e) {
    Fail(e.code(), e.what());
    Say(std::string("error: ") + e.what());
  } catch (const std::exception& e) {
    Fail(ExitCode::kProcessing, std::string("internal: ") + e.what());
    Say(std::string("error: internal: ") + e.what());
  }
  Finish();
  return s_;
}

}  // namespace internal

RunSummary RunTrial(const RunOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  internal::TrialRun run(options);
  return run.Run();
}

std::string SummaryTable(const RunSummary& s) {
  std::ostringstream os;
  std::size_t w = 4;
  for (const auto& l : s.steps) w = std::max(w, l.id.size());
  char buf[512];
  std::snprintf(buf, sizeof buf, "%-*s  %-14s %8s  %s\n", static_cast<int>(w), "step", "status", "time_s", "reason");
  os << buf;
  for (const auto& l : s.steps) {
    const std::string t = l.wall_s > 0 ? Fmt(l.wall_s) : "";
    std::snprintf(buf, sizeof buf, "%-*s  %-14s %8s  %s\n", static_cast<int>(w), l.id.c_str(), l.status.c_str(),
                  t.c_str(), l.reason.c_str());
    os << buf;
  }
  std::snprintf(buf, sizeof buf, "%s: %s (%d run, %d skipped, %d failed, %d warnings) in %.2f s, tools %.2f s\n",
                s.name.c_str(), TrialResultName(s.result), s.steps_run, s.steps_skipped, s.steps_failed,
                s.steps_warned, s.wall_s, s.tool_time_s);
  os << buf;
  return os.str();
}

}  // namespace rk::run

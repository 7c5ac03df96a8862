// rk-run's engine, the stages of one trial (see run/trial_run.h for the files of the others).
#include "run/runner.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <set>
#include <sstream>

#include "io/version.h"
#include "io/file_util.h"
#include "io/json_positions.h"
#include "run/previous_report.h"
#include "run/process.h"
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
  const fs::path trial(s_.trial_dir);
  if (o_.out_dir.empty()) {
    out_ = (trial / kOutDir).string();
    lock_file_ = (trial / kLockFile).string();
    log_file_ = (trial / kRunLogFile).string();
    last_run_file_ = (trial / kLastRunFile).string();
  } else {
    const fs::path out = fs::absolute(o_.out_dir, ec).lexically_normal();
    const fs::path named = out.has_filename() ? out : out.parent_path();
    const std::string name = named.filename().string();
    const fs::path beside = named.parent_path();
    out_ = named.string();
    io::MakeDirectories(beside.string());  // the products' folder's parent: DIR itself is made by the swap
    lock_file_ = (beside / ("." + name + kLockFile)).string();
    log_file_ = (beside / (name + "." + kRunLogFile)).string();
    last_run_file_ = (beside / (name + "." + kLastRunFile)).string();
  }
}

// Takes the trial lock and opens the run log; false (with the "locked" summary) when another rk-run
// holds the lock.
bool TrialRun::Lock(std::unique_ptr<TrialLock>* lock) {
  std::string holder;
  *lock = TrialLock::Acquire(lock_file_, o_.wait_lock_s, &holder);
  if (!*lock) {
    s_.result = TrialResult::kLocked;
    s_.exit_code = ExitCode::kIo;
    s_.error = s_.trial_dir + ": locked by another rk-run (" + holder + ")";
    s_.wall_s = Seconds(t0_);
    s_.summary = BuildSummaryJson();
    return false;
  }
  log_ = std::make_unique<RunLog>(log_file_);
  std::string cl;
  for (const auto& a : o_.command_line) cl += (cl.empty() ? "" : " ") + a;
  log_->Line("start: " + cl + " (rk-run " + kVersion + ")");
  return true;
}

void TrialRun::Plan() {
  m_ = std::make_unique<TrialManifest>(LoadManifest(manifest_file_));
  s_.name = m_->name;
  PlanOptions po;
  po.plots = true;  // with --no-plots the plot steps are planned too: Decide keeps those it does not redraw
  plan_ = BuildPlan(*m_, po);
  runs_.reserve(plan_.size());
  for (const auto& step : plan_) runs_.emplace_back(step);
  // Per unit: the steps planned and skipped and why; then a product the manifest asks for and the plan
  // cannot make fails the run (DataError at its place in trial.json, exit 3) before anything runs.
  // The plan lines say what this run may draw: with --no-plots, no plot step.
  std::vector<Step> shown;
  for (const Step& st : plan_) {
    if (o_.plots || st.kind != "plot") shown.push_back(st);
  }
  units_ = PlanByUnit(*m_, shown);
  for (const UnitPlan& u : units_) {
    s_.units.push_back(u.Line());
    if (log_) log_->Line("plan: " + u.Line());
  }
  CheckRequestedProducts(*m_, plan_);
}

// The last good report (trusted only if IsUsableReport), the input digests and the tool identities
// with the shortcuts it records.
void TrialRun::LoadRecords() {
  previous_ = LoadJsonOrNull((fs::path(out_) / kReportFile).string());
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
        CheckStepOptions(st, *f.tool);
        for (const auto& in : st.inputs) f.input_sha256.push_back(digests_->Digest(in.path).sha256);
      }
    }
    facts->push_back(std::move(f));
  }
}

// Every option a manifest's "steps" gives the step must be one of the tool's own long options, by its
// exact name (Tools::OptionNames, from the tool's --help): no abbreviation a parser might expand, no option
// the tool does not have. DataError (exit 3) at the option's key in trial.json.
void TrialRun::CheckStepOptions(const Step& st, const ToolIdentity& tool) {
  if (st.settings.options.empty()) return;
  const std::set<std::string>& names = tools_->OptionNames(tool, st.subcommand);
  if (names.empty()) return;  // no readable --help: the tool's own parser is the check
  for (const auto& [opt, value] : st.settings.options) {
    if (names.count(opt)) continue;
    const io::JsonPositions pos(m_->text);
    std::string pointer = "/steps";
    for (const std::string& key : {st.unit + "/" + st.kind, st.kind, std::string(kBadRowsSetting)}) {
      const Json& steps = m_->steps;
      if (steps.contains(key) && (key == kBadRowsSetting || (steps.at(key).is_object() && steps.at(key).contains(opt)))) {
        pointer += "/" + io::PointerToken(key) + (key == kBadRowsSetting ? "" : "/" + io::PointerToken(opt));
        break;
      }
    }
    trial::FailAt(manifest_file_, pos, pointer,
                  "'" + opt + "' is not an option of " + st.tool + (st.subcommand.empty() ? "" : " " + st.subcommand) +
                      " (options are given by their full long name, as its --help lists them)",
                  pointer != "/steps");
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
  const fs::path out(out_);
  DecideInput in;
  in.steps = std::span<const Step>(plan_.data(), facts.size());
  in.facts = facts;
  in.previous = previous_.is_object() ? &previous_ : nullptr;
  if (in.previous) in.out_files = ProbeOutFiles(out.string(), previous_);
  std::error_code ec;
  in.out_dir_exists = fs::is_directory(out, ec);
  in.manifest_sha256 = Sha256Hex(m_->text);
  in.force = o_.force;
  in.plots = o_.plots;
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
    if (r.Unlisted()) continue;
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
  std::error_code ec;
  std::set<std::string> made = PathsMadeByRun(previous_);
  for (const char* f : {kReportFile, kReportPageFile, "steps/report-page.log"}) made.insert(f);
  const std::vector<std::string> kept =
      KeepUserEntries(out_, work_, made, previous_.is_object());
  if (!kept.empty()) {
    Say("kept " + std::to_string(kept.size()) + " file(s) in out/ that rk-run did not make (first: out/" +
        kept.front() + ")");
  }
  had_page_ = fs::is_regular_file(fs::path(out_) / kReportPageFile, ec);
  const Json rep = BuildReport();
  const std::string rp = (fs::path(work_) / kReportFile).string();
  io::WriteJson(rp, rep);
  SyncPath(rp);
  const std::string how = CommitOut(out_, work_);
  work_.clear();
  s_.result = TrialResult::kDone;
  Say("out/ replaced (" + how + ")");
}

// TRIAL/last-run.json says "running" before anything else is done, so that a run that cannot write its
// result later (a full disk) never leaves an older "done" behind for a cron script to read.
void TrialRun::WriteRunning() {
  Json j = BuildSummaryJson();
  j["result"] = "running";
  j["status"] = "running";
  j["exit_code"] = nullptr;
  j["pid"] = static_cast<long>(::getpid());
  io::WriteOwnFileAtomic(last_run_file_, io::JsonText(j));
}

// The result into TRIAL/last-run.json. When it cannot be written, the file must not keep claiming
// anything: it is cut down, in place (no new block needed on a full disk), to a "failed" stub, or
// removed; the run's exit code and error say so.
void TrialRun::WriteLastRun() {
  std::string why;
  try {
    io::WriteOwnFileAtomic(last_run_file_, io::JsonText(s_.summary));
    return;
  } catch (const Error& e) {
    why = e.what();
  }
  const Json stub = {{"tool", "rk-run"}, {"result", "failed"}, {"status", "failed"}, {"exit_code", 4},
                     {"error", "last-run.json could not be written"}};
  const std::string text = stub.dump() + "\n";
  bool stubbed = false;
  try {
    const int fd = io::OpenOwnFile(last_run_file_, O_WRONLY);
    stubbed = ::pwrite(fd, text.data(), text.size(), 0) == static_cast<ssize_t>(text.size()) &&
              ::ftruncate(fd, static_cast<off_t>(text.size())) == 0 && ::fsync(fd) == 0;
    ::close(fd);
  } catch (const Error&) {
  }
  std::error_code ec;
  if (!stubbed) fs::remove(last_run_file_, ec);
  const std::string done_with_it = std::string(" (") + kLastRunFile + (stubbed ? " cut down to a 'failed' stub)" : " removed)");
  const std::string msg = "cannot write the run's result: " + why + done_with_it;
  if (s_.exit_code == ExitCode::kOk) {
    s_.exit_code = ExitCode::kIo;
    s_.error = msg;
    s_.result = TrialResult::kFailed;
  } else {
    s_.error += s_.error.find(why) == std::string::npos ? "; " + msg : done_with_it;
  }
  s_.summary = BuildSummaryJson();  // what --report gets says it too
  Say("error: " + msg);
}

// Everything between the lock and the summary; true when a dry run is complete (s_ is final).
bool TrialRun::PlanDecideExecute() {
  if (!o_.dry_run) {
    WriteRunning();
    CheckOutIsFolder(out_);
    for (const auto& n : RecoverAndClean(out_)) Say(n);
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
    s_.steps_skipped = static_cast<int>(
        std::count_if(runs_.begin(), runs_.end(), [](const StepRun& r) { return !r.Unlisted(); }));
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
    if (r.Unlisted()) continue;
    double w = r.decision == Decision::kRun && r.child.pid > 0 ? r.child.wall_s : 0.0;
    s_.steps.push_back({r.step.id, r.status.empty() ? "?" : r.status, r.reason, w});
  }
  s_.wall_s = Seconds(t0_);
  s_.summary = BuildSummaryJson();
  if (!page_warning_.empty()) s_.summary["report_page_warning"] = page_warning_;
  if (!o_.dry_run) {
    WriteLastRun();
    Say(std::string("result: ") + TrialResultName(s_.result) +
        (s_.error.empty() ? "" : " (exit " + std::to_string(static_cast<int>(s_.exit_code)) + "): " + s_.error) +
        " in " + Fmt(s_.wall_s) + " s");
  }
}

// out/report.html (run/report_page.h) with --plots only: --no-plots makes no figure of any kind. A page that
// cannot be made is a warning in the log and the summary; the run still succeeds.
// With --no-plots: an up-to-date out/ keeps the page it has; a new out/ replacing one that had a page gets a
// page without figures (current tables and warnings: the page is never left describing the old out/).
void TrialRun::ReportPage(bool rebuilt) {
  if (!o_.plots && !(rebuilt && had_page_)) return;
  page_warning_ = MakeReportPage(s_.trial_dir, out_, o_.tool_dirs, rebuilt, !o_.plots);
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
  // A stop signal that came after the last step (while committing or making the page) still makes an
  // interrupted run: exit 1, as docs/rk-run.md says, even though out/ may already be complete.
  if (!o_.dry_run && StopSignal() != 0 && !failed_) {
    Fail(ExitCode::kProcessing, "interrupted by signal " + std::to_string(StopSignal()) +
                                    (s_.result == TrialResult::kDone ? " (after the new out/ was complete)" : ""));
    Say(std::string("error: ") + s_.error);
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

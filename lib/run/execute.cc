// rk-run's engine: running the steps that Decide() chose, as child processes (run/process.h), at most
// --jobs at a time, each when its upstream steps are done; stopping them when rk-run is stopped; and
// what a finished step's exit code and log say.
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "io/csv.h"
#include "io/file_util.h"
#include "run/previous_report.h"
#include "run/trial_run.h"

namespace rk::run::internal {
namespace fs = std::filesystem;
using io::Json;

namespace {

constexpr std::size_t kLogTailLines = 40;    // lines of a failed step's log kept in the summary
constexpr std::size_t kMaxPlotColumns = 12;  // data-dependent plots (radar biases)
constexpr double kChildStopGraceS = 5.0;     // SIGTERM → SIGKILL delay when rk-run is stopped

// The last `max_lines` lines of a tool's output (progress redraws folded to their last state).
std::vector<std::string> TailLines(const std::string& text, std::size_t max_lines) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    size_t pos;
    while ((pos = line.find('\r')) != std::string::npos) line = line.substr(pos + 1);  // progress redraws
    lines.push_back(line);
    if (lines.size() > 4 * max_lines) lines.erase(lines.begin(), lines.begin() + static_cast<long>(max_lines));
  }
  if (lines.size() > max_lines) lines.erase(lines.begin(), lines.end() - static_cast<long>(max_lines));
  return lines;
}

// The error line of a failed tool: its last "rk-...: error: ..." line, else its last line.
std::string ErrorLine(const std::vector<std::string>& tail) {
  for (auto it = tail.rbegin(); it != tail.rend(); ++it) {
    if (it->rfind("rk-", 0) == 0 && it->find(": error: ") != std::string::npos) return *it;
  }
  for (auto it = tail.rbegin(); it != tail.rend(); ++it) {
    if (!it->empty()) return *it;
  }
  return "";
}

ExitCode ExitCodeOfStep(const ChildResult& r) {
  if (r.signal != 0) return ExitCode::kProcessing;
  switch (r.exit_code) {
    case 1: return ExitCode::kProcessing;
    case 2: return ExitCode::kInvalidData;  // the tool rejected options: the manifest's "steps" are the input
    case 3: return ExitCode::kInvalidData;
    case 4: return ExitCode::kIo;
    case 125:
    case 126:
    case 127: return ExitCode::kIo;  // could not be executed
    default: return ExitCode::kProcessing;
  }
}

std::vector<std::string> CommandLine(const StepRun& r, const std::string& out_prefix) {
  std::vector<std::string> argv = {r.tool ? r.tool->path : r.step.tool};
  for (const auto& a : r.step.args) argv.push_back(a.out_path ? out_prefix + "/" + a.text : a.text);
  if (r.step.tool_report) {
    argv.push_back("--report");
    argv.push_back(out_prefix + "/" + r.step.ReportFile());
  }
  return argv;
}

// Value columns of a CSV for a plot (radar biases): every column of its header but time, frame and
// status. Only the header is read, and any file gives an answer: not io::CsvTable, which reads the
// whole table and throws on a ragged row or a missing header (the plot then gets "t_s" instead).
std::string PlotColumnsOf(const std::string& csv_path) {
  std::ifstream in(csv_path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    break;
  }
  std::vector<std::string> cols;
  for (const auto& c : io::SplitList(line)) {
    if (c == "t_s" || c == "frame" || c == "status" || c == "kind" || c.empty()) continue;
    if (cols.size() < kMaxPlotColumns) cols.push_back(c);
  }
  std::string out;
  for (const auto& c : cols) out += (out.empty() ? "" : ",") + c;
  return out;
}

}  // namespace

// Products of the steps that are up to date are hard-linked from the previous out/.
void TrialRun::LinkSkippedProducts() {
  const fs::path out(out_);
  for (auto& r : runs_) {
    if (r.decision != Decision::kSkip || !r.previous) continue;
    for (const auto& o : r.previous->value("outputs", Json::array())) {
      const std::string p = o.value("path", "");
      LinkOrCopy((out / p).string(), (fs::path(work_) / p).string());
    }
    for (const char* f : {"report", "log"}) {
      if (r.previous->contains(f) && (*r.previous)[f].is_string()) {
        const std::string p = (*r.previous)[f].get<std::string>();
        std::error_code ec;
        if (fs::is_regular_file(out / p, ec)) LinkOrCopy((out / p).string(), (fs::path(work_) / p).string());
      }
    }
  }
}

// Starts step i: its log begins with the command line.
void TrialRun::StartStep(std::size_t i, std::map<pid_t, std::size_t>* running) {
  StepRun& r = runs_[i];
  r.started = true;
  r.ran_utc = UtcNow();
  ChildSpec spec;
  spec.argv = CommandLine(r, work_rel_);
  if (!r.step.plot_columns_from.empty()) {
    const std::string cols = PlotColumnsOf((fs::path(work_) / r.step.plot_columns_from).string());
    for (auto& a : spec.argv) {
      if (a == "@columns") a = cols.empty() ? "t_s" : cols;
    }
  }
  for (const auto& o : r.step.outputs) fs::create_directories((fs::path(work_) / o).parent_path());
  for (const auto& [path, text] : r.step.generated) io::WriteFileAtomic((fs::path(work_) / path).string(), text);
  spec.cwd = s_.trial_dir;
  spec.log_path = (fs::path(work_) / r.step.LogFile()).string();
  spec.capture = true;  // the tool's last lines are known even when its log cannot be written
  const std::string progress_env =
      progress_files_.Add(r.step.id, (fs::path(work_) / "steps" / (r.step.FileStem() + ".progress")).string());
  if (!progress_env.empty()) spec.env.push_back(progress_env);
  {
    std::ofstream head(spec.log_path);
    head << "# " << r.ran_utc << " " << r.step.id << ":";
    for (const auto& a : spec.argv) head << " " << a;
    head << "\n";
  }
  Say(r.step.id + ": run (" + r.reason + ")");
  const pid_t pid = StartChild(spec);
  (*running)[pid] = i;
}

// Starts, in plan order and up to --jobs at once, the steps to run whose upstream steps are done; a
// step whose upstream failed or did not run is marked not-run.
void TrialRun::LaunchReady(const std::map<std::string, std::size_t>& index, std::map<pid_t, std::size_t>* running) {
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    if (static_cast<int>(running->size()) >= o_.jobs) break;
    StepRun& r = runs_[i];
    if (r.decision != Decision::kRun || r.started) continue;
    bool ready = true, dead = false;
    std::string dead_why;
    for (const auto& d : r.step.depends_on) {
      const StepRun& u = runs_[index.at(d)];
      // An upstream step with a warning made no product (a plot, or too few samples): nothing to start from.
      if ((u.decision == Decision::kSkip && u.status != "warning") || (u.finished && (u.status == "ok"))) continue;
      if (u.decision == Decision::kRun && !u.finished) {
        ready = false;
        continue;
      }
      dead = true;
      dead_why = d;
    }
    if (dead) {
      r.started = r.finished = true;
      r.status = "not-run";
      r.reason = "needs " + dead_why + ", which failed or did not run";
      continue;
    }
    if (!ready) continue;
    StartStep(i, running);
  }
}

void TrialRun::Execute() {
  const fs::path trial(s_.trial_dir);
  work_ = MakeWorkDir(out_);
  // Tools run in the trial folder: the working folder by its name there, or by its full path when
  // out/ is a link to another folder.
  work_rel_ = fs::path(work_).parent_path() == trial ? fs::path(work_).filename().string() : work_;
  fs::create_directories(fs::path(work_) / "steps");
  LinkSkippedProducts();
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < runs_.size(); ++i) index[runs_[i].step.id] = i;
  std::map<pid_t, std::size_t> running;
  bool stop_launching = false;
  progress_files_.Start(o_.step_progress);
  for (;;) {
    if (StopSignal() != 0) {
      KillChildren(&running);
      Fail(ExitCode::kProcessing, "interrupted by signal " + std::to_string(StopSignal()));
      break;
    }
    if (!stop_launching) LaunchReady(index, &running);
    if (running.empty()) break;
    ChildResult res;
    if (!WaitAnyChild(&res)) continue;  // a stop signal: handled at the top
    auto it = running.find(res.pid);
    if (it == running.end()) continue;
    StepRun& r = runs_[it->second];
    running.erase(it);
    r.child = res;
    FinishStep(&r);
    if (failed_ && !o_.keep_going) stop_launching = true;
  }
  progress_files_.Stop();
  for (auto& r : runs_) {
    if (r.decision == Decision::kRun && !r.started) {
      r.status = "not-run";
      r.reason = "not started after an earlier failure";
    }
  }
  s_.steps_skipped = static_cast<int>(
      std::count_if(runs_.begin(), runs_.end(), [](const StepRun& r) { return r.decision == Decision::kSkip; }));
  for (const auto& r : runs_) {
    if (r.decision == Decision::kRun && r.finished && r.child.pid > 0) {
      s_.tool_time_s += r.child.wall_s;
      s_.tool_cpu_s += r.child.user_s + r.child.sys_s;
    }
  }
}

void TrialRun::KillChildren(std::map<pid_t, std::size_t>* running) {
  for (const auto& [pid, i] : *running) ::kill(pid, SIGTERM);
  const auto t = std::chrono::steady_clock::now();
  while (!running->empty()) {
    for (auto it = running->begin(); it != running->end();) {
      int status = 0;
      const pid_t w = ::waitpid(it->first, &status, WNOHANG);
      if (w == it->first || (w < 0 && errno == ECHILD)) {
        CollectChildOutput(it->first);  // into its log (the folder is removed anyway), the memfd released
        StepRun& r = runs_[it->second];
        r.finished = true;
        r.status = "failed";
        r.error = "stopped (rk-run received signal " + std::to_string(StopSignal()) + ")";
        it = running->erase(it);
      } else {
        ++it;
      }
    }
    if (running->empty()) break;
    if (Seconds(t) > kChildStopGraceS) {
      for (const auto& [pid, i] : *running) ::kill(pid, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

// `text` with the working folder's name (out.tmp.XXXXXX, or its full path) replaced by the folder it
// becomes: no message names a temporary path.
std::string TrialRun::FinalOutPaths(std::string text) const {
  const std::string final_name = fs::path(out_).parent_path() == fs::path(s_.trial_dir) ? std::string(kOutDir) : out_;
  for (const std::string& w : {work_, work_rel_}) {
    if (w.empty()) continue;
    for (std::size_t at = text.find(w); at != std::string::npos; at = text.find(w, at + final_name.size())) {
      text.replace(at, w.size(), final_name);
    }
  }
  return text;
}

// The step's tool said its input was valid but held too few samples for its method (the report's
// "error_kind": io/error.h kTooFewSamples).
bool TrialRun::TooFewSamples(const StepRun& r) const {
  if (r.child.exit_code != 3 || !r.step.tool_report) return false;
  const Json rep = LoadJsonOrNull((fs::path(work_) / r.step.ReportFile()).string());
  return rep.is_object() && rep.value("error_kind", Json()) == kTooFewSamples;
}

// The run's error for a failed step whose log's error line is `line`.
std::string TrialRun::FailureMessage(const StepRun& r, const std::string& line) const {
  const ExitCode code = ExitCodeOfStep(r.child);
  std::string msg = r.step.id + ": " + r.error;
  // A tool's data or I/O error names FILE:LINE:COL relative to the trial folder: lead with it, as
  // seen from where rk-run was started, so that editors can jump to it.
  const std::string prefix = r.step.tool + ": error: ";
  if ((code == ExitCode::kInvalidData || code == ExitCode::kIo) && line.rfind(prefix, 0) == 0) {
    std::string what = line.substr(prefix.size());
    const auto colon = what.find(':');
    std::error_code ec;
    if (colon != std::string::npos && colon > 0 && what.rfind("out.tmp.", 0) != 0 &&
        fs::exists(fs::path(s_.trial_dir) / what.substr(0, colon), ec)) {
      what = (fs::path(user_dir_) / what.substr(0, colon)).lexically_normal().string() + what.substr(colon);
    }
    msg = what + " (step " + r.step.id + ": " + r.step.tool + " " + r.child.Describe() + ")";
  }
  if (r.child.exit_code == 2) {
    msg = manifest_file_ + ": steps: " + r.step.tool + " rejected the options of step " + r.step.id +
          (line.empty() ? "" : ": " + line);
  }
  return msg;
}

void TrialRun::FinishStep(StepRun* r) {
  r->finished = true;
  progress_files_.Remove(r->step.id);
  const bool ok = r->child.signal == 0 && r->child.exit_code == 0;
  if (ok) {
    r->status = "ok";
    s_.steps_run++;
    Say(r->step.id + ": ok in " + Fmt(r->child.wall_s) + " s");
    return;
  }
  r->log_tail = TailLines(r->child.output, kLogTailLines);
  // A tool names its outputs in the working folder, which is gone after the run: say out/ instead.
  for (auto& l : r->log_tail) l = FinalOutPaths(l);
  if (!r->child.log_error.empty()) r->log_tail.push_back("(rk-run: the step's log could not be written: " + r->child.log_error + ")");
  std::string line = ErrorLine(r->log_tail);
  r->error = r->step.tool + " " + r->child.Describe() + (line.empty() ? "" : ": " + line);
  for (const auto& out : r->step.outputs) {
    std::error_code ec;
    fs::remove(fs::path(work_) / out, ec);
  }
  if (r->step.warn_only || TooFewSamples(*r)) {
    // A plot, or a method that the data are too thin for (a beacon seen in two frames cannot be smoothed):
    // a warning, not a failed trial. The chain delivers what it could; the steps that need this one's
    // product are not run, and the page says why.
    r->status = "warning";
    r->reason = r->error;
    s_.steps_warned++;
    Say(r->step.id + ": WARNING (not counted as a failure): " + r->error);
  } else {
    r->status = "failed";
    s_.steps_failed++;
    Say(r->step.id + ": FAILED: " + r->error);
    for (const auto& l : r->log_tail) {
      if (log_) log_->Line("  | " + l);
    }
    Fail(ExitCodeOfStep(r->child), FailureMessage(*r, line));
  }
}

}  // namespace rk::run::internal

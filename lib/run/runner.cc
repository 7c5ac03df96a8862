#include "run/runner.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "io/csv.h"
#include "io/file_util.h"
#include "io/version.h"
#include "run/digest.h"
#include "run/elf_build_id.h"
#include "run/manifest.h"
#include "run/plan.h"
#include "run/process.h"
#include "run/sha256.h"
#include "run/trial_dir.h"

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

bool RunOptions::Check(std::string* why) const {
  if (trial.empty()) {
    *why = "no trial given";
    return false;
  }
  if (jobs < 1 || jobs > 64) {
    *why = "--jobs must be 1..64";
    return false;
  }
  if (!(wait_lock_s >= 0.0) || wait_lock_s > 7 * 86400.0) {
    *why = "--wait-lock must be 0..604800 s";
    return false;
  }
  return true;
}

namespace {

constexpr std::uintmax_t kLogRotateBytes = 1u << 20;  // rk-run.log is rotated to rk-run.log.1 past 1 MiB
constexpr std::size_t kLogTailLines = 40;             // lines of a failed step's log kept in the summary
constexpr std::size_t kMaxPlotColumns = 12;           // data-dependent plots (radar biases)
constexpr double kChildStopGraceS = 5.0;              // SIGTERM → SIGKILL delay when rk-run is stopped

std::string UtcNow() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[40];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  char out[48];
  std::snprintf(out, sizeof out, "%s.%03dZ", buf, static_cast<int>(ms));
  return out;
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double Round3(double x) { return std::round(x * 1000.0) / 1000.0; }

std::string Fmt(double x, int decimals = 2) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

// TRIAL/rk-run.log: one timestamped line per event, appended (rotated past 1 MiB).
class RunLog {
 public:
  explicit RunLog(const std::string& trial_dir) {
    const fs::path p = fs::path(trial_dir) / "rk-run.log";
    std::error_code ec;
    if (fs::exists(p, ec) && fs::file_size(p, ec) > kLogRotateBytes) {
      fs::rename(p, fs::path(trial_dir) / "rk-run.log.1", ec);
    }
    fd_ = ::open(p.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0) throw IoError(p.string(), std::string("cannot open the run log: ") + std::strerror(errno));
  }
  ~RunLog() {
    if (fd_ >= 0) ::close(fd_);
  }
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;
  void Line(const std::string& text) {
    const std::string s = UtcNow() + " [" + std::to_string(::getpid()) + "] " + text + "\n";
    [[maybe_unused]] const ssize_t n = ::write(fd_, s.data(), s.size());  // O_APPEND: one write per line
  }

 private:
  int fd_ = -1;
};

std::vector<std::string> TailLines(const std::string& path, std::size_t max_lines) {
  std::ifstream in(path);
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

// Shape checks of what rk-run reads back from the last report (out/report.json) and from the shared
// --tool-cache file, field by field with the type it is read as. These files are rk-run's own output,
// but a hand edit, another program or another version can leave anything in them: a record that is not
// of this shape is not trusted (its steps run again) instead of ending the run in a JSON type error.
bool OptionalOf(const Json& j, const char* key, bool (Json::*is)() const noexcept) {
  return !j.contains(key) || (j.at(key).*is)();
}
bool StringsOnly(const Json& j, std::initializer_list<const char*> keys) {
  for (const char* k : keys) {
    if (!OptionalOf(j, k, &Json::is_string)) return false;
  }
  return true;
}
// {path?, bytes?, mtime_ns?, ...} as file digests, tool identities and step outputs are written.
bool IsFileRecord(const Json& j) {
  return j.is_object() && OptionalOf(j, "bytes", &Json::is_number_unsigned) &&
         OptionalOf(j, "mtime_ns", &Json::is_number_integer) && OptionalOf(j, "files", &Json::is_number_unsigned) &&
         StringsOnly(j, {"path", "sha256", "id", "version"});
}
bool IsStepRecord(const Json& s) {
  if (!s.is_object() || !StringsOnly(s, {"id", "status", "reason", "key", "report", "log"})) return false;
  if (s.contains("outputs")) {
    if (!s["outputs"].is_array()) return false;
    for (const auto& o : s["outputs"]) {
      if (!IsFileRecord(o)) return false;
    }
  }
  if (!s.contains("key_parts")) return true;
  const Json& k = s["key_parts"];
  if (!k.is_object()) return false;
  if (k.contains("tool") && !(k["tool"].is_object() && StringsOnly(k["tool"], {"version"}))) return false;
  if (k.contains("inputs") && k["inputs"].is_array()) {
    for (const auto& i : k["inputs"]) {
      if (!i.is_object() || !StringsOnly(i, {"path", "sha256"})) return false;
    }
  }
  if (k.contains("upstream")) {
    if (!k["upstream"].is_object()) return false;
    for (const auto& [id, key] : k["upstream"].items()) {
      if (!key.is_string()) return false;
    }
  }
  return true;
}
// A report of rk-run whose every part rk-run reads has the expected type.
bool IsUsableReport(const Json& r) {
  if (!r.is_object() || r.value("tool", Json()) != "rk-run") return false;
  for (const char* records : {"inputs", "tools"}) {
    if (!r.contains(records)) continue;
    if (!r[records].is_object()) return false;
    for (const auto& [name, rec] : r[records].items()) {
      if (!IsFileRecord(rec)) return false;
    }
  }
  if (r.contains("trial") && !(r["trial"].is_object() && StringsOnly(r["trial"], {"manifest_sha256"}))) return false;
  if (r.contains("steps")) {
    if (!r["steps"].is_array()) return false;
    for (const auto& s : r["steps"]) {
      if (!IsStepRecord(s)) return false;
    }
  }
  return true;
}

struct ToolIdentity {
  std::string name, path, version;
  std::string id;  // "build-id:<hex>" (ELF GNU build ID) or "sha256:<hex>" (scripts)
  std::uintmax_t bytes = 0;
  std::int64_t mtime_ns = 0;
  Json ToJson() const {
    return {{"path", path}, {"version", version}, {"id", id}, {"bytes", bytes}, {"mtime_ns", mtime_ns}};
  }
};

// Finds and identifies the tools (--version output and the executable's GNU build ID, or SHA-256 for
// scripts, with the same size+mtime shortcut as the inputs).
class Tools {
 public:
  // `previous`: the "tools" of the last good report; `shared`: the --tool-cache file's content (the
  // same records, shared by every trial of a nightly run so that each tool is asked once).
  Tools(std::vector<std::string> dirs, const Json& previous, const Json& shared, bool trust_stat)
      : dirs_(std::move(dirs)), previous_(previous.is_object() ? previous : Json::object()),
        shared_(shared.is_object() ? shared : Json::object()), trust_(trust_stat) {}
  bool shared_changed() const { return shared_changed_; }
  const Json& shared() const { return shared_; }

  // Null when the tool cannot be found; IoError when it exists but will not tell its version.
  const ToolIdentity* Get(const std::string& name) {
    auto it = cache_.find(name);
    if (it != cache_.end()) return it->second ? &*it->second : nullptr;
    const std::string path = FindExecutable(name, dirs_);
    if (path.empty()) {
      cache_[name] = std::nullopt;
      return nullptr;
    }
    ToolIdentity id;
    id.name = name;
    id.path = path;
    if (!StatFile(path, &id.bytes, &id.mtime_ns)) throw IoError(path, "cannot read the executable");
    const auto matches = [&](const Json* prev) {
      return prev && IsFileRecord(*prev) && prev->value("path", "") == path &&
             prev->value("bytes", std::uintmax_t{0}) == id.bytes &&
             prev->value("mtime_ns", std::int64_t{0}) == id.mtime_ns && prev->contains("id") &&
             prev->contains("version");
    };
    const Json* prev = previous_.contains(name) ? &previous_.at(name) : nullptr;
    if (!matches(prev)) prev = shared_.contains(path) ? &shared_.at(path) : nullptr;
    if (trust_ && matches(prev)) {
      id.id = prev->at("id").get<std::string>();
      id.version = prev->at("version").get<std::string>();
    } else {
      const std::string build_id = ElfBuildId(path);
      id.id = build_id.empty() ? "sha256:" + Sha256File(path) : "build-id:" + build_id;
      std::string out;
      const int rc = RunAndCapture({path, "--version"}, &out);
      const auto nl = out.find('\n');
      id.version = out.substr(0, nl);
      if (rc != 0 || id.version.empty()) {
        throw IoError(path, "does not answer --version (exit code " + std::to_string(rc) + "): not a rangekit tool?");
      }
      shared_[path] = id.ToJson();
      shared_changed_ = true;
    }
    cache_[name] = id;
    return &*cache_[name];
  }
  Json ToJson() const {
    Json j = Json::object();
    for (const auto& [name, id] : cache_) {
      if (id) j[name] = id->ToJson();
    }
    return j;
  }

 private:
  std::vector<std::string> dirs_;
  Json previous_, shared_;
  bool trust_;
  bool shared_changed_ = false;
  std::map<std::string, std::optional<ToolIdentity>> cache_;
};

enum class Decision { kRun, kSkip, kInactive, kBlocked };

struct StepRun {
  Step step;
  const ToolIdentity* tool = nullptr;
  Json key_parts;
  std::string key;
  Decision decision = Decision::kInactive;
  std::string reason;
  const Json* previous = nullptr;  // this step's entry in the last good report
  // Outcome
  std::string status;  // "ok", "skipped", "failed", "warning", "not-run", "off", "not-applicable"
  ChildResult child;
  std::string ran_utc;
  std::string error;
  std::vector<std::string> log_tail;
  bool started = false, finished = false;
};

std::vector<std::string> CommandLine(const StepRun& r, const std::string& out_prefix) {
  std::vector<std::string> argv = {r.tool ? r.tool->path : r.step.tool};
  for (const auto& a : r.step.args) argv.push_back(a.out_path ? out_prefix + "/" + a.text : a.text);
  if (r.step.tool_report) {
    argv.push_back("--report");
    argv.push_back(out_prefix + "/" + r.step.ReportFile());
  }
  return argv;
}

// Value columns of a CSV for a plot (radar biases): every column but time, frame and status.
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

// Quality figures of a product table: rows and the count of each status value.
Json TableQuality(const std::string& path) {
  Json q = Json::object();
  try {
    const io::CsvTable t = io::CsvTable::Read(path);
    q["rows"] = t.rows();
    const int sc = t.Column("status");
    if (sc >= 0) {
      std::map<std::string, std::size_t> counts;
      for (std::size_t r = 0; r < t.rows(); ++r) ++counts[std::string(t.Cell(r, sc))];
      Json s = Json::object();
      for (const auto& [k, n] : counts) s[k.empty() ? "(empty)" : k] = n;
      q["status"] = s;
      if (t.rows() > 0 && counts.count("ok")) {
        q["ok_fraction"] = Round3(static_cast<double>(counts["ok"]) / static_cast<double>(t.rows()));
      }
    }
  } catch (const std::exception& e) {
    q["error"] = e.what();
  }
  return q;
}

// A few headline figures from the tools' own reports, where they exist.
void AddToolFigures(const std::string& kind, const Json& rep, Json* q) {
  if (!rep.is_object()) return;
  if (kind == "extract-beacon") {
    if (rep.contains("mean_ncc")) (*q)["mean_ncc"] = rep["mean_ncc"];
    if (rep.contains("frames")) (*q)["frames"] = rep["frames"];
  } else if (kind == "locate") {
    if (rep.contains("range_coverage")) (*q)["range_coverage"] = rep["range_coverage"];
  } else if (kind == "smooth" && rep.contains("columns") && rep["columns"].is_object()) {
    Json nis = Json::object();
    for (const auto& [c, v] : rep["columns"].items()) {
      if (v.is_object() && v.contains("nis_mean")) nis[c] = v["nis_mean"];
    }
    (*q)["nis_mean"] = nis;
  }
}

Json LoadJsonOrNull(const std::string& path) {
  try {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return Json(nullptr);
    return io::LoadJson(path);
  } catch (const std::exception&) {
    return Json(nullptr);
  }
}

class TrialRun {
 public:
  explicit TrialRun(const RunOptions& o) : o_(o), t0_(std::chrono::steady_clock::now()), started_utc_(UtcNow()) {}

  RunSummary Run();

 private:
  void Say(const std::string& s) {
    if (o_.progress) o_.progress(s);
    if (log_) log_->Line(s);
  }
  void Plan();
  void Decide();
  void Execute();
  void KillChildren(std::map<pid_t, std::size_t>* running);
  void FinishStep(StepRun* r);
  Json StepJson(const StepRun& r, bool full) const;
  Json BuildReport() const;
  Json BuildSummaryJson() const;
  void Fail(ExitCode code, const std::string& error) {
    if (s_.error.empty()) {
      s_.exit_code = code;
      s_.error = error;
    }
    failed_ = true;
  }

  const RunOptions& o_;
  std::chrono::steady_clock::time_point t0_;
  std::string started_utc_;
  RunSummary s_;
  std::string manifest_file_;
  std::string user_dir_;  // the trial folder as the user named it (for messages)
  std::unique_ptr<RunLog> log_;
  std::unique_ptr<TrialManifest> m_;
  Json previous_;  // last good out/report.json (or null)
  std::unique_ptr<DigestCache> digests_;
  std::unique_ptr<Tools> tools_;
  std::vector<StepRun> runs_;
  std::string work_;      // absolute working folder
  std::string work_rel_;  // its name (relative to the trial folder)
  bool failed_ = false;
  bool rebuild_ = false;  // a new out/ is needed even if no step runs
  std::string rebuild_reason_;
};

void TrialRun::Plan() {
  m_ = std::make_unique<TrialManifest>(LoadManifest(manifest_file_));
  s_.name = m_->name;
  PlanOptions po;
  po.plots = o_.plots;
  for (auto& step : BuildPlan(*m_, po)) {
    StepRun r;
    r.step = std::move(step);
    runs_.push_back(std::move(r));
  }
}

void TrialRun::Decide() {
  const fs::path out = fs::path(s_.trial_dir) / kOutDir;
  std::map<std::string, const Json*> prev_steps;
  if (previous_.is_object() && previous_.contains("steps") && previous_["steps"].is_array()) {
    for (const auto& e : previous_["steps"]) {
      if (e.is_object() && e.contains("id") && e["id"].is_string()) prev_steps[e["id"].get<std::string>()] = &e;
    }
  }
  std::map<std::string, const StepRun*> by_id;
  for (auto& r : runs_) {
    const Step& st = r.step;
    by_id[st.id] = &r;
    if (st.state != PlanState::kActive) {
      r.decision = Decision::kInactive;
      r.status = PlanStateName(st.state);
      r.reason = st.note;
      continue;
    }
    // Upstream steps that cannot produce their outputs block this one.
    bool blocked = false;
    for (const auto& d : st.depends_on) {
      auto it = by_id.find(d);
      if (it != by_id.end() && it->second->decision == Decision::kBlocked) {
        blocked = true;
        r.reason = "needs " + d + ", which cannot run";
      }
    }
    r.tool = tools_->Get(st.tool);
    if (!r.tool) {
      const std::string why = st.tool + " not found (searched next to rk-run and on PATH)";
      if (st.warn_only) {
        r.decision = Decision::kBlocked;
        r.status = "warning";
        r.reason = why;
        continue;
      }
      throw IoError(st.tool, std::string("not found next to rk-run") +
                                 (o_.tool_dirs.empty() ? "" : " (" + o_.tool_dirs.back() + ")") +
                                 " or on PATH; needed by step " + st.id);
    }
    if (blocked) {
      r.decision = Decision::kBlocked;
      r.status = "not-run";
      continue;
    }
    Json inputs = Json::array();
    for (const auto& in : st.inputs) {
      const FileDigest& d = digests_->Digest(in.path);
      inputs.push_back({{"role", in.role}, {"path", in.path}, {"sha256", d.sha256}});
    }
    Json upstream = Json::object();
    for (const auto& d : st.depends_on) upstream[d] = by_id.at(d)->key;
    std::vector<std::string> args;
    for (const auto& a : st.args) args.push_back(a.out_path ? std::string(kOutDir) + "/" + a.text : a.text);
    r.key_parts = {{"tool", {{"name", st.tool}, {"version", r.tool->version}, {"id", r.tool->id}}},
                   {"args", args},
                   {"inputs", inputs},
                   {"upstream", upstream}};
    r.key = Sha256Hex(r.key_parts.dump());

    auto pit = prev_steps.find(st.id);
    r.previous = pit == prev_steps.end() ? nullptr : pit->second;
    const Json* p = r.previous;
    std::string why;
    if (o_.force) {
      why = "--force";
    } else if (!p) {
      why = "new step";
    } else if (!p->contains("key")) {
      why = "new step (was " + p->value("status", std::string("?")) + ")";
    } else if (p->value("key", "") != r.key) {
      const Json pk = p->value("key_parts", Json::object());
      if (pk.value("tool", Json()) != r.key_parts["tool"]) {
        const std::string pv = pk.contains("tool") ? pk["tool"].value("version", "?") : "?";
        why = pv != r.tool->version ? "tool version changed (" + pv + " -> " + r.tool->version + ")"
                                    : "tool executable changed";
      } else if (pk.value("inputs", Json()) != inputs) {
        std::string which;
        std::map<std::string, std::string> before;
        if (pk.contains("inputs") && pk["inputs"].is_array()) {
          for (const auto& i : pk["inputs"]) before[i.value("path", "")] = i.value("sha256", "");
        }
        for (const auto& i : inputs) {
          const std::string path = i["path"].get<std::string>();
          if (!before.count(path) || before[path] != i["sha256"].get<std::string>()) {
            which += (which.empty() ? "" : ", ") + path;
          }
        }
        why = which.empty() ? "inputs changed" : "input changed: " + which;
      } else if (pk.value("args", Json()) != r.key_parts["args"]) {
        why = "command line or options changed";
      } else {
        std::string which;
        for (const auto& d : st.depends_on) {
          if (!pk.contains("upstream") || pk["upstream"].value(d, "") != r.key_parts["upstream"][d]) {
            which += (which.empty() ? "" : ", ") + d;
          }
        }
        why = "upstream changed: " + (which.empty() ? std::string("?") : which);
      }
    } else {
      // Same fingerprint: the products must still be there as they were written.
      const Json outs = p->value("outputs", Json::array());
      if (!outs.is_array() || (outs.empty() && !st.outputs.empty() && p->value("status", "") != "warning")) {
        why = "products not recorded";
      }
      for (const auto& o : outs) {
        if (!why.empty()) break;
        std::uintmax_t b = 0;
        std::int64_t t = 0;
        const std::string path = o.value("path", "");
        if (!StatFile((out / path).string(), &b, &t) || b != o.value("bytes", std::uintmax_t{0}) ||
            t != o.value("mtime_ns", std::int64_t{0})) {
          why = "product missing or changed: out/" + path;
        }
      }
      for (const char* f : {"report", "log"}) {
        if (!why.empty()) break;
        if (!p->contains(f) || !(*p)[f].is_string()) continue;
        std::error_code ec;
        if (!fs::is_regular_file(out / (*p)[f].get<std::string>(), ec)) why = std::string("step ") + f + " missing";
      }
    }
    if (why.empty()) {
      r.decision = Decision::kSkip;
      r.status = "skipped";
      r.reason = "up to date";
      if (p->value("status", "") == "warning") {
        r.status = "warning";
        r.reason = "up to date (earlier warning: " + p->value("reason", std::string("?")) + ")";
      }
    } else {
      r.decision = Decision::kRun;
      r.reason = why;
    }
  }

  // Is a new out/ needed?
  const auto run_count = std::count_if(runs_.begin(), runs_.end(), [](const StepRun& r) { return r.decision == Decision::kRun; });
  std::error_code ec;
  if (run_count > 0) {
    rebuild_ = true;
    rebuild_reason_ = std::to_string(run_count) + " step(s) to run";
  } else if (!fs::is_directory(out, ec) || !previous_.is_object()) {
    rebuild_ = true;
    rebuild_reason_ = "no complete out/";
  } else {
    std::set<std::string> before, now;
    for (const auto& [id, e] : prev_steps) {
      if (e->value("status", "") == "ok" || e->value("status", "") == "skipped" || e->value("status", "") == "warning") before.insert(id);
    }
    for (const auto& r : runs_) {
      if (r.decision == Decision::kSkip || (r.decision == Decision::kBlocked && r.step.warn_only)) {
        now.insert(r.step.id);
      }
    }
    const std::string manifest_sha = Sha256Hex(m_->text);
    if (before != now) {
      rebuild_ = true;
      rebuild_reason_ = "the set of steps changed";
    } else if (previous_.value("trial", Json::object()).value("manifest_sha256", "") != manifest_sha) {
      rebuild_ = true;
      rebuild_reason_ = "trial.json changed (no step affected)";
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

void TrialRun::FinishStep(StepRun* r) {
  r->finished = true;
  const std::string log = (fs::path(work_) / r->step.LogFile()).string();
  const bool ok = r->child.signal == 0 && r->child.exit_code == 0;
  if (ok) {
    r->status = "ok";
    s_.steps_run++;
    Say(r->step.id + ": ok in " + Fmt(r->child.wall_s) + " s");
    return;
  }
  r->log_tail = TailLines(log, kLogTailLines);
  std::string line = ErrorLine(r->log_tail);
  r->error = r->step.tool + " " + r->child.Describe() + (line.empty() ? "" : ": " + line);
  for (const auto& out : r->step.outputs) {
    std::error_code ec;
    fs::remove(fs::path(work_) / out, ec);
  }
  if (r->step.warn_only) {
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
    ExitCode code = ExitCodeOfStep(r->child);
    std::string msg = r->step.id + ": " + r->error;
    // A tool's data or I/O error names FILE:LINE:COL relative to the trial folder: lead with it, as
    // seen from where rk-run was started, so that editors can jump to it.
    const std::string prefix = r->step.tool + ": error: ";
    if ((code == ExitCode::kInvalidData || code == ExitCode::kIo) && line.rfind(prefix, 0) == 0) {
      std::string what = line.substr(prefix.size());
      const auto colon = what.find(':');
      std::error_code ec;
      if (colon != std::string::npos && colon > 0 && what.rfind("out.tmp.", 0) != 0 &&
          fs::exists(fs::path(s_.trial_dir) / what.substr(0, colon), ec)) {
        what = (fs::path(user_dir_) / what.substr(0, colon)).lexically_normal().string() + what.substr(colon);
      }
      msg = what + " (step " + r->step.id + ": " + r->step.tool + " " + r->child.Describe() + ")";
    }
    if (r->child.exit_code == 2) {
      msg = manifest_file_ + ": steps: " + r->step.tool + " rejected the options of step " + r->step.id +
            (line.empty() ? "" : ": " + line);
    }
    Fail(code, msg);
  }
}

void TrialRun::Execute() {
  const fs::path trial(s_.trial_dir);
  const fs::path out = trial / kOutDir;
  work_ = MakeWorkDir(s_.trial_dir);
  // Tools run in the trial folder: the working folder by its name there, or by its full path when
  // out/ is a link to another folder.
  work_rel_ = fs::path(work_).parent_path() == trial ? fs::path(work_).filename().string() : work_;
  fs::create_directories(fs::path(work_) / "steps");
  // Products of the steps that are up to date are hard-linked from the previous out/.
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
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < runs_.size(); ++i) index[runs_[i].step.id] = i;
  std::map<pid_t, std::size_t> running;
  bool stop_launching = false;
  for (;;) {
    if (StopSignal() != 0) {
      KillChildren(&running);
      Fail(ExitCode::kProcessing, "interrupted by signal " + std::to_string(StopSignal()));
      break;
    }
    // Launch what is ready.
    for (std::size_t i = 0; i < runs_.size() && !stop_launching; ++i) {
      if (static_cast<int>(running.size()) >= o_.jobs) break;
      StepRun& r = runs_[i];
      if (r.decision != Decision::kRun || r.started) continue;
      bool ready = true, dead = false;
      std::string dead_why;
      for (const auto& d : r.step.depends_on) {
        const StepRun& u = runs_[index.at(d)];
        if (u.decision == Decision::kSkip || (u.finished && (u.status == "ok"))) continue;
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
      spec.cwd = s_.trial_dir;
      spec.log_path = (fs::path(work_) / r.step.LogFile()).string();
      {
        std::ofstream head(spec.log_path);
        head << "# " << r.ran_utc << " " << r.step.id << ":";
        for (const auto& a : spec.argv) head << " " << a;
        head << "\n";
      }
      Say(r.step.id + ": run (" + r.reason + ")");
      const pid_t pid = StartChild(spec);
      running[pid] = i;
    }
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

Json TrialRun::StepJson(const StepRun& r, bool full) const {
  Json j;
  j["id"] = r.step.id;
  j["status"] = r.status;
  if (!r.reason.empty()) j["reason"] = r.reason;
  if (!full) {
    j["wall_s"] = Round3(r.child.wall_s);
    if (r.child.pid > 0) j["exit_code"] = r.child.signal ? Json(nullptr) : Json(r.child.exit_code);
    if (!r.error.empty()) j["error"] = r.error;
    if (!r.log_tail.empty()) j["log_tail"] = r.log_tail;
    return j;
  }
  j["unit"] = r.step.unit;
  j["kind"] = r.step.kind;
  j["tool"] = r.step.tool;
  if (!r.step.subcommand.empty()) j["subcommand"] = r.step.subcommand;
  j["options"] = r.step.settings.AsJson();
  if (r.decision == Decision::kInactive || r.key.empty()) return j;
  std::vector<std::string> cl;
  cl.push_back(r.step.tool);
  for (const auto& a : r.step.args) cl.push_back(a.out_path ? std::string(kOutDir) + "/" + a.text : a.text);
  j["command_line"] = cl;
  j["inputs"] = r.key_parts["inputs"];
  j["key"] = r.key;
  j["key_parts"] = r.key_parts;
  if (r.decision == Decision::kSkip && r.previous) {
    // Carried over from the run that produced it.
    for (const char* k : {"outputs", "time", "ran_utc", "exit_code", "quality", "tool_report", "report", "log"}) {
      if (r.previous->contains(k)) j[k] = (*r.previous)[k];
    }
    return j;
  }
  if (!r.started || r.child.pid <= 0) return j;
  j["ran_utc"] = r.ran_utc;
  j["exit_code"] = r.child.signal ? Json(nullptr) : Json(r.child.exit_code);
  if (r.child.signal) j["signal"] = r.child.signal;
  j["time"] = {{"wall_s", Round3(r.child.wall_s)},
               {"user_s", Round3(r.child.user_s)},
               {"sys_s", Round3(r.child.sys_s)},
               {"max_rss_kb", r.child.max_rss_kb}};
  j["log"] = r.step.LogFile();
  if (r.status == "ok" || r.status == "warning") {
    Json outs = Json::array();
    for (const auto& o : r.step.outputs) {
      const std::string p = (fs::path(work_) / o).string();
      std::uintmax_t b = 0;
      std::int64_t t = 0;
      if (!StatFile(p, &b, &t)) continue;
      outs.push_back({{"path", o}, {"bytes", b}, {"mtime_ns", t}, {"sha256", Sha256File(p)}});
    }
    j["outputs"] = outs;
    if (r.step.tool_report) {
      const std::string rp = (fs::path(work_) / r.step.ReportFile()).string();
      Json rep = LoadJsonOrNull(rp);
      if (!rep.is_null()) {
        j["report"] = r.step.ReportFile();
        j["tool_report"] = rep;
      }
    }
    if (r.status == "ok" && !r.step.table.empty()) {
      Json q = TableQuality((fs::path(work_) / r.step.table).string());
      AddToolFigures(r.step.kind, j.value("tool_report", Json()), &q);
      j["quality"] = q;
    }
  }
  if (!r.error.empty()) j["error"] = r.error;
  return j;
}

Json TrialRun::BuildReport() const {
  Json rep;
  rep["tool"] = "rk-run";
  rep["version"] = kVersion;
  rep["command_line"] = o_.command_line;
  Json inputs = digests_->ToJson();
  rep["inputs"] = inputs;
  rep["trial"] = {{"name", m_->name},
                  {"dir", s_.trial_dir},
                  {"manifest", fs::path(manifest_file_).filename().string()},
                  {"manifest_sha256", Sha256Hex(m_->text)},
                  {"epoch_utc", m_->epoch_utc.empty() ? Json(nullptr) : Json(m_->epoch_utc)},
                  {"station", m_->station}};
  rep["tools"] = tools_->ToJson();
  rep["result"] = "done";
  rep["status"] = "ok";  // out/report.json is only written by a run that succeeded (same keys as every report)
  rep["exit_code"] = 0;
  rep["started_utc"] = started_utc_;
  rep["finished_utc"] = UtcNow();
  rep["wall_s"] = Round3(Seconds(t0_));
  rep["tool_time_s"] = Round3(s_.tool_time_s);
  rep["tool_cpu_s"] = Round3(s_.tool_cpu_s);
  rep["counts"] = {{"run", s_.steps_run}, {"skipped", s_.steps_skipped}, {"warnings", s_.steps_warned}};
  Json steps = Json::array();
  for (const auto& r : runs_) steps.push_back(StepJson(r, true));
  rep["steps"] = steps;
  rep["manifest"] = m_->json;
  return rep;
}

Json TrialRun::BuildSummaryJson() const {
  Json j;
  j["tool"] = "rk-run";
  j["version"] = kVersion;
  j["command_line"] = o_.command_line;
  j["inputs"] = Json::object();
  j["inputs"]["manifest"] = manifest_file_;
  j["trial"] = s_.name;
  j["trial_dir"] = s_.trial_dir;
  j["result"] = TrialResultName(s_.result);
  j["exit_code"] = static_cast<int>(s_.exit_code);
  j["error"] = s_.error.empty() ? Json(nullptr) : Json(s_.error);
  j["status"] = s_.exit_code == ExitCode::kOk ? "ok" : "failed";  // the key every tool's report uses
  j["started_utc"] = started_utc_;
  j["finished_utc"] = UtcNow();
  j["wall_s"] = Round3(Seconds(t0_));
  j["tool_time_s"] = Round3(s_.tool_time_s);
  j["tool_cpu_s"] = Round3(s_.tool_cpu_s);
  j["counts"] = {{"run", s_.steps_run}, {"skipped", s_.steps_skipped}, {"failed", s_.steps_failed},
                 {"warnings", s_.steps_warned}};
  Json steps = Json::array();
  for (const auto& r : runs_) steps.push_back(StepJson(r, false));
  j["steps"] = steps;
  return j;
}

RunSummary TrialRun::Run() {
  std::error_code ec;
  fs::path given(o_.trial);
  manifest_file_ = fs::is_directory(given, ec) ? (given / "trial.json").string() : given.string();
  user_dir_ = fs::is_directory(given, ec) ? given.string() : given.parent_path().string();
  if (user_dir_.empty()) user_dir_ = ".";
  manifest_file_ = fs::absolute(manifest_file_, ec).lexically_normal().string();
  s_.trial_dir = fs::path(manifest_file_).parent_path().string();
  s_.name = fs::path(s_.trial_dir).filename().string();
  if (!fs::is_regular_file(manifest_file_, ec)) {
    throw IoError(manifest_file_, fs::exists(manifest_file_, ec) ? "is not a file" : "no such trial manifest");
  }

  std::unique_ptr<TrialLock> lock;
  if (!o_.dry_run) {
    std::string holder;
    lock = TrialLock::Acquire(s_.trial_dir, o_.wait_lock_s, &holder);
    if (!lock) {
      s_.result = TrialResult::kLocked;
      s_.exit_code = ExitCode::kIo;
      s_.error = s_.trial_dir + ": locked by another rk-run (" + holder + ")";
      s_.wall_s = Seconds(t0_);
      s_.summary = BuildSummaryJson();
      return s_;
    }
    log_ = std::make_unique<RunLog>(s_.trial_dir);
    std::string cl;
    for (const auto& a : o_.command_line) cl += (cl.empty() ? "" : " ") + a;
    log_->Line("start: " + cl + " (rk-run " + kVersion + ")");
  }
  try {
    if (!o_.dry_run) {
      for (const auto& n : RecoverAndClean(s_.trial_dir)) Say(n);
    }
    Plan();
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
    Decide();
    if (!o_.tool_cache.empty() && tools_->shared_changed()) {
      try {
        // Re-read and merge: other trials of the same nightly run may have added tools meanwhile.
        Json merged = LoadJsonOrNull(o_.tool_cache);
        if (!merged.is_object()) merged = Json::object();
        for (const auto& [k, v] : tools_->shared().items()) merged[k] = v;
        io::WriteJson(o_.tool_cache, merged);
      } catch (const Error& e) {
        Say(std::string("warning: tool cache not written: ") + e.what());
      }
    }
    if (o_.dry_run) {
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
      return s_;
    }
    if (!rebuild_) {
      s_.result = TrialResult::kUpToDate;
      s_.steps_skipped = static_cast<int>(runs_.size());
      Say("up to date: nothing to run");
    } else {
      Say("building a new out/: " + rebuild_reason_);
      Execute();
      if (!failed_) {
        const Json rep = BuildReport();
        const std::string rp = (fs::path(work_) / kReportFile).string();
        io::WriteJson(rp, rep);
        SyncPath(rp);
        const std::string how = CommitOut(s_.trial_dir, work_);
        work_.clear();
        s_.result = TrialResult::kDone;
        Say("out/ replaced (" + how + ")");
      }
    }
  } catch (const Error& e) {
    Fail(e.code(), e.what());
    Say(std::string("error: ") + e.what());
  } catch (const std::exception& e) {
    Fail(ExitCode::kProcessing, std::string("internal: ") + e.what());
    Say(std::string("error: internal: ") + e.what());
  }
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
  return s_;
}

}  // namespace

RunSummary RunTrial(const RunOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  TrialRun run(options);
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

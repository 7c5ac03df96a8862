// rk-run's engine: what it writes about a run — out/report.json (BuildReport, docs/rk-run.md
// "out/report.json") and TRIAL/last-run.json / --report (BuildSummaryJson).
#include <filesystem>
#include <map>

#include "io/csv.h"
#include "io/version.h"
#include "run/previous_report.h"
#include "run/sha256.h"
#include "run/trial_run.h"

namespace rk::run::internal {
namespace fs = std::filesystem;
using io::Json;

namespace {

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

}  // namespace

// The tool's headline figures: every member of its report's "summary" object (docs/architecture.md
// "Adding an rk-run step"), whatever the step kind. The table's own figures above (rows, status,
// ok_fraction, error) are rk-run's and stay: a summary member of the same name is left out.
void AddToolSummary(const Json& tool_report, Json* quality) {
  if (!tool_report.is_object() || !tool_report.contains("summary") || !tool_report["summary"].is_object()) return;
  for (const auto& [k, v] : tool_report["summary"].items()) {
    if (!quality->contains(k)) (*quality)[k] = v;
  }
}

// What a step that ran adds to its full record `j`: time, log, products with their digests, the tool's
// report and the quality figures.
Json TrialRun::StepOutcomeJson(const StepRun& r) const {
  Json j = Json::object();
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
      if (!r.step.method.empty()) q["method"] = r.step.method;  // which method made the product
      AddToolSummary(j.value("tool_report", Json()), &q);
      j["quality"] = q;
    }
  }
  if (!r.error.empty()) j["error"] = r.error;
  return j;
}

// A step's record: `full` for out/report.json, else the short one of the summary.
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
  if (!r.step.method.empty()) j["method"] = r.step.method;
  if (r.decision == Decision::kInactive || r.key.empty()) return j;
  std::vector<std::string> cl;
  cl.push_back(r.step.tool);
  for (const auto& a : r.step.args) cl.push_back(a.out_path ? std::string(kOutDir) + "/" + a.text : a.text);
  j["command_line"] = cl;
  j["inputs"] = r.key_parts["inputs"];
  j["key"] = r.key;
  j["key_parts"] = r.key_parts;
  if (r.decision == Decision::kSkip && r.previous) {
    // Carried over from the run that produced it; a stale plot (--no-plots) keeps the fingerprint it was
    // drawn with, so that the next run with plots sees it changed.
    for (const char* k : {"outputs", "time", "ran_utc", "exit_code", "quality", "tool_report", "report", "log"}) {
      if (r.previous->contains(k)) j[k] = (*r.previous)[k];
    }
    if (r.status == "stale") {
      for (const char* k : {"key", "key_parts", "inputs", "command_line"}) {
        if (r.previous->contains(k)) j[k] = (*r.previous)[k];
      }
    }
    return j;
  }
  if (!r.started || r.child.pid <= 0) return j;
  const Json outcome = StepOutcomeJson(r);
  for (const auto& [k, v] : outcome.items()) j[k] = v;
  return j;
}

Json TrialRun::BuildReport() const {
  Json rep;
  rep["tool"] = "rk-run";
  rep["version"] = kVersion;
  rep["git_commit"] = kGitCommit;
  rep["command_line"] = o_.command_line;
  Json inputs = digests_->ToJson();
  rep["inputs"] = inputs;
  rep["trial"] = {{"name", m_->name},
                  {"dir", s_.trial_dir},
                  {"manifest", fs::path(manifest_file_).filename().string()},
                  {"manifest_sha256", Sha256Hex(m_->text)},
                  {"epoch_utc", m_->epoch_utc.empty() ? Json(nullptr) : Json(m_->epoch_utc)},
                  {"station", m_->multi_station() ? Json(nullptr) : m_->Single().station}};
  if (m_->multi_station()) {  // several stations: each one's position and the trajectory's origin
    Json positions = Json::object();
    for (const trial::StationEntry& st : m_->stations) positions[st.name] = st.station;
    rep["trial"]["stations"] = positions;
    rep["trial"]["origin"] = m_->origin;
  }
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
  for (const auto& r : runs_) {
    if (!r.Unlisted()) steps.push_back(StepJson(r, true));
  }
  rep["steps"] = steps;
  rep["units"] = UnitsJson();
  rep["manifest"] = m_->json;
  return rep;
}

Json TrialRun::BuildSummaryJson() const {
  Json j;
  j["tool"] = "rk-run";
  j["version"] = kVersion;
  j["git_commit"] = kGitCommit;
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
  for (const auto& r : runs_) {
    if (!r.Unlisted()) steps.push_back(StepJson(r, false));
  }
  j["steps"] = steps;
  if (!units_.empty()) j["units"] = UnitsJson();
  return j;
}

Json TrialRun::UnitsJson() const {
  Json units = Json::array();
  for (const UnitPlan& u : units_) units.push_back(u.ToJson());
  return units;
}

}  // namespace rk::run::internal

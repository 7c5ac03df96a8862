#include "run/decide.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "run/sha256.h"
#include "run/trial_dir.h"

namespace rk::run {
using io::Json;

namespace {

// The fingerprint parts of an active step whose tool was found: tool, command line (products under
// out/), input digests, upstream fingerprints.
Json KeyParts(const Step& st, const StepFacts& facts, const std::map<std::string, const StepDecision*>& by_id) {
  Json inputs = Json::array();
  for (std::size_t i = 0; i < st.inputs.size(); ++i) {
    const StepInput& in = st.inputs[i];
    inputs.push_back({{"role", in.role}, {"path", in.path}, {"sha256", facts.input_sha256.at(i)}});
  }
  Json upstream = Json::object();
  for (const auto& d : st.depends_on) upstream[d] = by_id.at(d)->key;
  std::vector<std::string> args;
  for (const auto& a : st.args) args.push_back(a.out_path ? std::string(kOutDir) + "/" + a.text : a.text);
  Json parts = {{"tool", {{"name", st.tool}, {"version", facts.tool->version}, {"id", facts.tool->id}}},
                {"args", args},
                {"inputs", inputs},
                {"upstream", upstream}};
  // Files the plan writes for the step (the intersection's stations.json) by their content's digest; only
  // when there are some, so that the fingerprints of the other steps stay what they were.
  if (!st.generated.empty()) {
    Json generated = Json::object();
    for (const auto& [path, text] : st.generated) generated[path] = Sha256Hex(text);
    parts["generated"] = generated;
  }
  return parts;
}

// Why a step whose fingerprint differs from the recorded one `p` runs: the first part that differs.
std::string WhyChanged(const Step& st, const ToolIdentity& tool, const Json& key_parts, const Json& p) {
  const Json pk = p.value("key_parts", Json::object());
  if (pk.value("tool", Json()) != key_parts["tool"]) {
    const std::string pv = pk.contains("tool") ? pk["tool"].value("version", "?") : "?";
    return pv != tool.version ? "tool version changed (" + pv + " -> " + tool.version + ")"
                              : "tool executable changed";
  }
  const Json& inputs = key_parts["inputs"];
  if (pk.value("inputs", Json()) != inputs) {
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
    if (!which.empty()) return "input changed: " + which;
    std::string dropped;  // an input the step no longer reads (the image fit switched off: the video)
    for (const auto& entry : before) {
      const std::string& path = entry.first;
      const bool still = std::any_of(inputs.begin(), inputs.end(), [&](const Json& i) { return i["path"] == path; });
      if (!still) dropped += (dropped.empty() ? "" : ", ") + path;
    }
    return dropped.empty() ? "inputs changed" : "input no longer read: " + dropped;
  }
  if (pk.value("args", Json()) != key_parts["args"]) return "command line or options changed";
  if (pk.value("generated", Json()) != key_parts.value("generated", Json())) return "station positions or origin changed";
  std::string which;
  for (const auto& d : st.depends_on) {
    if (!pk.contains("upstream") || pk["upstream"].value(d, "") != key_parts["upstream"][d]) {
      which += (which.empty() ? "" : ", ") + d;
    }
  }
  return "upstream changed: " + (which.empty() ? std::string("?") : which);
}

// Same fingerprint: the products must still be in out/ as they were written. "" when they are.
std::string WhyProductsGone(const Step& st, const Json& p, const std::map<std::string, OutFileState>& out_files) {
  const auto state = [&](const std::string& path) {
    const auto it = out_files.find(path);
    return it == out_files.end() ? OutFileState{} : it->second;
  };
  const Json outs = p.value("outputs", Json::array());
  if (!outs.is_array() || (outs.empty() && !st.outputs.empty() && p.value("status", "") != "warning")) {
    return "products not recorded";
  }
  for (const auto& o : outs) {
    const std::string path = o.value("path", "");
    const OutFileState f = state(path);
    if (!f.stat_ok || f.bytes != o.value("bytes", std::uintmax_t{0}) ||
        f.mtime_ns != o.value("mtime_ns", std::int64_t{0})) {
      return "product missing or changed: out/" + path;
    }
  }
  for (const char* f : {"report", "log"}) {
    if (!p.contains(f) || !p[f].is_string()) continue;
    if (!state(p[f].get<std::string>()).regular) return std::string("step ") + f + " missing";
  }
  return "";
}

// The decision for one step, given the decisions of the steps before it.
StepDecision DecideStep(const Step& st, const StepFacts& facts, const DecideInput& in,
                        const std::map<std::string, const Json*>& prev_steps,
                        const std::map<std::string, const StepDecision*>& by_id,
                        const std::set<std::string>& cannot_run) {
  StepDecision r;
  if (st.state != PlanState::kActive) {
    r.decision = Decision::kInactive;
    r.status = PlanStateName(st.state);
    r.reason = st.note;
    return r;
  }
  // Upstream steps that cannot produce their outputs block this one.
  r.reason = BlockedBy(st, cannot_run);
  if (!facts.tool) {
    r.decision = Decision::kBlocked;
    r.status = st.warn_only ? "warning" : "not-run";
    r.reason = st.tool + " not found (searched next to rk-run and on PATH)";
    return r;
  }
  if (!r.reason.empty()) {
    r.decision = Decision::kBlocked;
    r.status = "not-run";
    return r;
  }
  r.key_parts = KeyParts(st, facts, by_id);
  r.key = Sha256Hex(r.key_parts.dump());

  auto pit = prev_steps.find(st.id);
  r.previous = pit == prev_steps.end() ? nullptr : pit->second;
  const Json* p = r.previous;
  std::string why;
  if (in.force) {
    why = "--force";
  } else if (!p) {
    why = "new step";
  } else if (!p->contains("key")) {
    why = "new step (was " + p->value("status", std::string("?")) + ")";
  } else if (p->value("key", "") != r.key) {
    why = WhyChanged(st, *facts.tool, r.key_parts, *p);
  } else {
    why = WhyProductsGone(st, *p, in.out_files);
  }
  if (!why.empty() && !in.plots && st.kind == "plot") {
    // --no-plots: not drawn. A run that does less never deletes what it did not redo: the previous plot,
    // if intact, is kept and marked stale (its record keeps the old key, so the next run with plots
    // redraws it).
    r.decision = Decision::kInactive;
    r.status = "off";
    r.reason = "--no-plots";
    if (p && p->contains("key") && WhyProductsGone(st, *p, in.out_files).empty() &&
        !p->value("outputs", Json::array()).empty()) {
      r.decision = Decision::kSkip;
      r.status = "stale";
      r.reason = "--no-plots: not redrawn (" + why + "); the previous plot is kept";
    }
    return r;
  }
  if (why.empty()) {
    r.decision = Decision::kSkip;
    r.status = "skipped";
    r.reason = "up to date";
    if (p->value("status", "") == "warning") {
      r.status = "warning";
      // The record of a skipped warning carries this same wrapper: say the original warning once.
      const std::string wrap = "up to date (earlier warning: ";
      std::string earlier = p->value("reason", std::string("?"));
      while (earlier.rfind(wrap, 0) == 0 && earlier.size() > wrap.size() && earlier.back() == ')') {
        earlier = earlier.substr(wrap.size(), earlier.size() - wrap.size() - 1);
      }
      r.reason = wrap + earlier + ")";
    }
  } else {
    r.decision = Decision::kRun;
    r.reason = why;
  }
  return r;
}

// Is a new out/ needed? Sets out->rebuild and out->rebuild_reason.
void DecideRebuild(const DecideInput& in, const std::map<std::string, const Json*>& prev_steps, RunDecision* out) {
  const auto run_count = std::count_if(out->steps.begin(), out->steps.end(),
                                       [](const StepDecision& r) { return r.decision == Decision::kRun; });
  if (run_count > 0) {
    out->rebuild = true;
    out->rebuild_reason = std::to_string(run_count) + " step(s) to run";
    return;
  }
  if (!in.out_dir_exists || !in.previous || !in.previous->is_object()) {
    out->rebuild = true;
    out->rebuild_reason = "no complete out/";
    return;
  }
  std::set<std::string> before, now;
  for (const auto& [id, e] : prev_steps) {
    const std::string status = e->value("status", "");
    if (status == "ok" || status == "skipped" || status == "warning" || status == "stale") before.insert(id);
  }
  for (std::size_t i = 0; i < out->steps.size(); ++i) {
    const Decision d = out->steps[i].decision;
    // A plot whose tool is missing is a warning (counted, as the report records it); one blocked by an
    // upstream step that made nothing is not-run, which no report counts.
    if (d == Decision::kSkip || (d == Decision::kBlocked && in.steps[i].warn_only && out->steps[i].status == "warning")) {
      now.insert(in.steps[i].id);
    }
  }
  if (before != now) {
    out->rebuild = true;
    out->rebuild_reason = "the set of steps changed";
  } else if (in.previous->value("trial", Json::object()).value("manifest_sha256", "") != in.manifest_sha256) {
    out->rebuild = true;
    out->rebuild_reason = "trial.json changed (no step affected)";
  }
}

}  // namespace

std::string BlockedBy(const Step& step, const std::set<std::string>& cannot_run) {
  std::string reason;
  for (const auto& d : step.depends_on) {
    if (cannot_run.count(d)) reason = "needs " + d + ", which cannot run";
  }
  return reason;
}

RunDecision Decide(const DecideInput& in) {
  if (in.facts.size() != in.steps.size()) throw std::invalid_argument("Decide: one StepFacts per step");
  const Json none;
  const std::map<std::string, const Json*> prev_steps = PreviousSteps(in.previous ? *in.previous : none);
  RunDecision out;
  out.steps.reserve(in.steps.size());  // by_id points into it
  std::map<std::string, const StepDecision*> by_id;
  std::set<std::string> cannot_run;
  for (std::size_t i = 0; i < in.steps.size(); ++i) {
    const Step& st = in.steps[i];
    out.steps.push_back(DecideStep(st, in.facts[i], in, prev_steps, by_id, cannot_run));
    by_id[st.id] = &out.steps.back();
    const StepDecision& sd = out.steps.back();
    // Blocked, or up to date with a warning that left no product (too few samples): nothing downstream runs.
    if (sd.decision == Decision::kBlocked || (sd.decision == Decision::kSkip && sd.status == "warning" && !st.warn_only)) {
      cannot_run.insert(st.id);
    }
  }
  DecideRebuild(in, prev_steps, &out);
  return out;
}

}  // namespace rk::run

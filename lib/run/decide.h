// Which steps of a trial run, and why (docs/rk-run.md, "Skipping"): a pure function of the plan, the
// last good report, the input digests and tool identities, and the state of out/ — gathered by the
// runner beforehand, so that the rules can be tested without files, tools or processes.
#pragma once

#include <map>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "io/json_util.h"
#include "run/plan.h"
#include "run/previous_report.h"
#include "run/tools.h"

namespace rk::run {

enum class Decision { kRun, kSkip, kInactive, kBlocked };

// What the world says about one active step (nothing for a step that is off or not applicable).
struct StepFacts {
  const ToolIdentity* tool = nullptr;     // null: not found (only a warn_only step may lack its tool)
  std::vector<std::string> input_sha256;  // SHA-256 of each of Step::inputs, in order (unused when blocked)
};

struct DecideInput {
  std::span<const Step> steps;       // the plan, in dependency order
  std::span<const StepFacts> facts;  // one per step
  const io::Json* previous = nullptr;  // the last good out/report.json (IsUsableReport), or null
  std::map<std::string, OutFileState> out_files;  // ProbeOutFiles(out/, *previous)
  bool out_dir_exists = false;       // out/ is a folder
  std::string manifest_sha256;       // of trial.json's text
  bool force = false;                // --force
  // false (--no-plots): a plot step that is up to date is kept (skipped); one that would run is not drawn,
  // and its previous plot, if intact, is kept with status "stale"; else it is "off".
  bool plots = true;
};

struct StepDecision {
  Decision decision = Decision::kInactive;
  std::string status;  // "skipped", "stale", "warning", "not-run", "off", "not-applicable"; "" for kRun
  std::string reason;  // "up to date", "new step", "input changed: turret.csv", ...
  io::Json key_parts;  // fingerprint parts {tool, args, inputs, upstream} (kRun, kSkip)
  std::string key;     // SHA-256 of key_parts.dump()
  const io::Json* previous = nullptr;  // this step's record in *previous (points into it)
};

struct RunDecision {
  std::vector<StepDecision> steps;  // one per step
  bool rebuild = false;             // a new out/ is needed even if no step runs
  std::string rebuild_reason;
};

// "needs D, which cannot run" for the last of the step's upstream steps in `cannot_run` (steps
// decided kBlocked), "" when none is.
std::string BlockedBy(const Step& step, const std::set<std::string>& cannot_run);

// The decision for every step and for out/. Throws std::out_of_range when a step depends on one that
// does not come before it (BuildPlan never does that).
RunDecision Decide(const DecideInput& in);

}  // namespace rk::run

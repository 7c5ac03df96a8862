// The trial manifest trial.json (SPEC.md §6) as rk-run reads it: lib/trial's reader, then rk-run's checks of
// "steps", with errors that name trial.json's line and column. The form of "steps" (per-step option overrides
// and switches) is rk-run's and is documented in docs/rk-run.md:
//   "steps": {"locate": {"range-interp": "linear"},      // options of every beacon camera's locate
//             "az/extract-beacon": {"k-detect": 6},       // camera "az" only (merged over the above)
//             "resample-range": false,                    // switch a step off
//             "plot": false,
//             "bad-rows": "skip",                         // --bad-rows of every step that reads CSV
//             "attitude-cylinder": {"image-fit": false}}  // an rk-run key (RunSettingKeys), not an option
// Option names are the tool's long options without "--"; a string or number value gives "--name
// value", true gives the flag "--name", false leaves the flag out, an array gives "--name a,b,c".
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/json_util.h"
#include "trial/manifest.h"

namespace rk::run {

// The manifest's types are lib/trial's (trial/manifest.h); rk-run names them as before.
using trial::CameraEntry;
using trial::CameraRole;
using trial::CameraRoleName;
using trial::RadarEntry;

// Step kinds rk-run knows, the camera role (or "radar") they belong to, the tool they run and the
// options rk-run sets on them itself.
struct StepKindInfo {
  const char* kind;     // "extract-beacon", "locate", ...
  const char* unit;     // "beacon", "features", "silhouette", "points", "radar", "trajectory" (the intersection of
                        // several stations, and the exports, plan.cc Export()) or "*" (any unit: plots)
  const char* tool;     // "rk-extract"
  const char* subcommand;  // "beacon" or "" (single-mode tool)
  // The input bindings: every option the plan (plan.cc) gives this kind from the manifest, long name and
  // short alias ("i" for --input) without dashes. The plan can bind no other option (it throws), so a
  // binding added here is one the manifest's "steps" may not override (IsReservedOption).
  std::vector<std::string> bindings;
  // Options that would contradict a binding and so are reserved too (--decode-only writes no track,
  // --rate/--t0/--t1 compete with --at).
  std::vector<std::string> contradicting = {};
};
const std::vector<StepKindInfo>& StepKinds();
const StepKindInfo* FindStepKind(const std::string& kind);

// Options of a step, after merging "<kind>" and "<unit>/<kind>" from "steps".
struct StepSettings {
  bool enabled = true;
  std::vector<std::pair<std::string, io::Json>> options;  // option name (no "--") → value, in order
  // rk-run's own keys of the step (RunSettingKeys): read by the plan, never passed to the tool.
  io::Json run = io::Json::object();
  bool RunFlag(const std::string& key, bool default_value) const {
    return run.contains(key) ? run.at(key).get<bool>() : default_value;
  }
  io::Json AsJson() const;  // options and run keys, as the manifest gave them
};

// Keys of a step's "steps" object that rk-run reads itself instead of passing them to the tool (all take
// true/false): "image-fit" of attitude-cylinder (docs/rk-run.md, "Steps").
inline constexpr const char* kImageFitSetting = "image-fit";
const std::vector<std::string>& RunSettingKeys(const std::string& kind);

// The key of "steps" that is not a step: the --bad-rows (error|skip) of every step that reads CSV.
inline constexpr const char* kBadRowsSetting = "bad-rows";

// The trial manifest (trial::Manifest) with "steps" checked against rk-run's step kinds and options.
struct TrialManifest : trial::Manifest {
  // Settings of step `kind` for unit `unit` (camera name or "radar").
  StepSettings Settings(const std::string& unit, const std::string& kind) const;
};

// Reads and checks trial.json (trial::LoadManifest), then its "steps". `path` may name the manifest or the
// trial directory (then DIR/trial.json). Throws IoError (unreadable), DataError "trial.json:LINE:COL: field:
// what".
TrialManifest LoadManifest(const std::string& path);
// The same from text (tests); `manifest_path` names the file in messages and gives the trial dir.
TrialManifest ParseManifest(const std::string& text, const std::string& manifest_path);

// Options a step's overrides may not set, because rk-run sets them: the common ones (-o, --report, --quiet,
// --help, --version) and the kind's bindings and contradicting options (StepKindInfo).
bool IsReservedOption(const std::string& kind, const std::string& option);
bool IsReservedOption(const StepKindInfo& kind, const std::string& option);

}  // namespace rk::run

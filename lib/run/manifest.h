// The trial manifest trial.json (SPEC.md §6) as rk-run reads it, with every field checked and
// errors that name trial.json's line and column. The form of "steps" (per-step option overrides and
// switches) is rk-run's and is documented in docs/rk-run.md:
//   "steps": {"locate": {"range-interp": "linear"},      // options of every beacon camera's locate
//             "az/extract-beacon": {"k-detect": 6},       // camera "az" only (merged over the above)
//             "resample-range": false,                    // switch a step off
//             "plot": false,
//             "bad-rows": "skip"}                         // --bad-rows of every step that reads CSV
// Option names are the tool's long options without "--"; a string or number value gives "--name
// value", true gives the flag "--name", false leaves the flag out, an array gives "--name a,b,c".
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/json_util.h"
#include "run/json_positions.h"

namespace rk::run {

enum class CameraRole { kBeacon, kFeatures, kSilhouette };
const char* CameraRoleName(CameraRole role);

struct CameraEntry {
  std::string name;                 // key in "cameras" (also the folder name in out/)
  std::vector<std::string> video;   // segments or image-sequence patterns, relative to the trial dir
  std::string frames;               // frame-times CSV (empty when fps is given instead)
  std::optional<double> fps;        // constant frame rate (Hz) when there is no frames CSV
  std::optional<double> t0_s;       // time of frame 0 with fps (s)
  std::string model;                // camera model JSON
  CameraRole role = CameraRole::kBeacon;
  std::string target;               // target model JSON (features, silhouette)
  std::optional<std::pair<double, double>> boresight_deg;  // fixed camera (az, el) when no turret log
};

struct RadarEntry {
  std::string plots;  // radar plots CSV
  std::string nav;    // platform navigation CSV
};

// Step kinds rk-run knows, the camera role (or "radar") they belong to, and the tool they run.
struct StepKindInfo {
  const char* kind;     // "extract-beacon", "locate", ...
  const char* unit;     // "beacon", "features", "silhouette", "radar" or "*" (any unit: plots)
  const char* tool;     // "rk-extract"
  const char* subcommand;  // "beacon" or "" (single-mode tool)
};
const std::vector<StepKindInfo>& StepKinds();
const StepKindInfo* FindStepKind(const std::string& kind);

// Options of a step, after merging "<kind>" and "<unit>/<kind>" from "steps".
struct StepSettings {
  bool enabled = true;
  std::vector<std::pair<std::string, io::Json>> options;  // option name (no "--") → value, in order
  io::Json AsJson() const;
};

// The key of "steps" that is not a step: the --bad-rows (error|skip) of every step that reads CSV.
inline constexpr const char* kBadRowsSetting = "bad-rows";

struct TrialManifest {
  std::string manifest_path;  // absolute path of trial.json
  std::string dir;            // absolute trial directory (the manifest's folder)
  std::string text;           // the file's text (its SHA-256 is part of the report)
  io::Json json;              // the whole manifest, extra keys included
  JsonPositions positions;
  std::string name;           // "name", else the folder's name
  std::string epoch_utc;
  io::Json station;           // {"lat_deg","lon_deg","h_m"} or null
  std::vector<CameraEntry> cameras;  // in name order
  std::string turret, range, theodolite;  // empty = none
  std::optional<RadarEntry> radar;
  io::Json steps;             // the "steps" object (checked)

  // Settings of step `kind` for unit `unit` (camera name or "radar").
  StepSettings Settings(const std::string& unit, const std::string& kind) const;
  // Every path the manifest names (trial files), relative to dir, in a stable order.
  std::vector<std::string> AllPaths() const;
};

// Reads and checks trial.json. `path` may name the manifest or the trial directory (then
// DIR/trial.json). Throws IoError (unreadable), DataError "trial.json:LINE:COL: field: what".
TrialManifest LoadManifest(const std::string& path);
// The same from text (tests); `manifest_path` names the file in messages and gives the trial dir.
TrialManifest ParseManifest(const std::string& text, const std::string& manifest_path);

// Options a step's overrides may not set, because rk-run sets them (inputs, outputs, report).
bool IsReservedOption(const std::string& kind, const std::string& option);

}  // namespace rk::run

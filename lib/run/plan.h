// The step graph of one trial (docs/rk-run.md, "Steps"): which tool runs on which recording, with
// which command line (SPEC.md §1.1), in which order. Per camera role:
//   beacon     extract-beacon → locate (turret or theodolite log, range log if any) → smooth (Singer
//              RTS on the located target: rates and accelerations); resample-range (range log at the
//              frame times)
//   features   extract-features → attitude-oi (turret log, or the camera's fixed boresight_deg)
//   silhouette extract-silhouette → attitude-cylinder (theodolite log, else the turret log)
//   radar      register (GM Bernoulli), register-batch
// and a plot step (rk-plot) for each main series. Paths are relative to the trial folder; outputs
// relative to out/.
#pragma once

#include <string>
#include <vector>

#include "run/manifest.h"

namespace rk::run {

enum class PlanState { kActive, kOff, kNotApplicable };
const char* PlanStateName(PlanState s);

struct StepArg {
  std::string text;
  bool out_path = false;  // `text` is relative to out/ (the working folder while running)
};

struct StepInput {
  std::string role;  // option it is given to ("video", "frames", "camera", ...)
  std::string path;  // relative to the trial folder
};

struct Step {
  std::string id;          // "<unit>/<kind>" or "<unit>/plot-<series>"
  std::string unit;        // camera name or "radar"
  std::string kind;        // StepKinds() kind ("plot" for plots)
  std::string tool;        // executable name, "rk-extract"
  std::string subcommand;  // "beacon", or "" for single-mode tools
  std::vector<StepArg> args;           // after the executable, overrides included
  std::vector<StepInput> inputs;       // trial files it reads
  std::vector<std::string> depends_on; // ids of the steps whose outputs it reads
  std::vector<std::string> outputs;    // products, relative to out/
  std::string table;                   // main CSV product (quality figures), relative to out/
  std::string plot_columns_from;       // plots of tables with data-dependent columns (radar biases)
  StepSettings settings;
  bool warn_only = false;   // a failure is a warning, not a failed trial (plots)
  bool tool_report = true;  // the tool takes --report
  PlanState state = PlanState::kActive;
  std::string note;         // why it is off / not applicable

  std::string FileStem() const;       // id with '/' → '.', for steps/<stem>.log
  std::string ReportFile() const { return "steps/" + FileStem() + ".report.json"; }
  std::string LogFile() const { return "steps/" + FileStem() + ".log"; }
};

struct PlanOptions {
  bool plots = true;  // false: no plot steps at all (--no-plots)
};

// Every step of the trial in dependency order (a step comes after the steps it depends on),
// including those switched off or not applicable (state and note say why).
std::vector<Step> BuildPlan(const TrialManifest& manifest, const PlanOptions& options);

// "--name value" arguments of the overrides (false flags are left out).
std::vector<std::string> OverrideArgs(const StepSettings& settings);

}  // namespace rk::run

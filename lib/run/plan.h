// The step graph of one trial (docs/rk-run.md, "Steps"): which tool runs on which recording, with
// which command line (SPEC.md §1.1), in which order. Per camera role:
//   beacon     extract-beacon → locate (turret or theodolite log, range log if any) → smooth (Singer
//              RTS on the located target: rates and accelerations); resample-range (range log at the
//              frame times)
//   features   extract-features → attitude-oi (turret log, or the camera's fixed boresight_deg)
//   silhouette extract-silhouette → attitude-cylinder (theodolite log, else the turret log)
//   points     extract-points (the camera's seeds) → locate-points (one located series per id; turret or
//              theodolite log, range log if any)
//   radar      register (GM Bernoulli), register-batch
//   trajectory intersect (several stations: rk-intersect on every located camera); export-kml, export-czml
//              (rk-export of the trajectory, or of a single station's first located target when the manifest
//              gives the station's position and a range log) into out/trajectory.kml, out/trajectory.czml
// and a plot step (rk-plot) for each main series. Paths are relative to the trial folder; outputs
// relative to out/.
#pragma once

#include <string>
#include <utility>
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
  // Files the runner writes into out/ just before the step starts: path relative to out/, content. Made by the
  // plan from the manifest (the intersection's stations.json), part of the step's fingerprint, kept with its
  // products.
  std::vector<std::pair<std::string, std::string>> generated;
  std::string method;       // how the product is made, where a kind has several ways ("image-fit" or
                            // "three-point" for attitude-cylinder); "" otherwise

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

// What the plan does for one unit of the trial (docs/rk-run.md, "Planned and skipped"): a camera, the radar,
// a log that no step reads, or the trial itself when nothing at all is planned.
struct UnitPlan {
  std::string unit;  // camera name, "radar", the manifest key of a log ("theodolite"), or "trial"
  std::string what;  // "beacon camera", "radar", "log theodolite.csv", "manifest"
  std::vector<std::string> planned;  // active steps: kind (plot-<series> for plots), " (image-fit)" if a method
  std::vector<std::pair<std::string, std::string>> skipped;  // step, why (off or not applicable)
  std::string note;  // why nothing is planned for it ("" when something is)
  // "az (beacon camera): planned extract-beacon, locate; skipped resample-range (the manifest has no range log)"
  std::string Line() const;
  io::Json ToJson() const;  // {"unit", "what", "planned": [...], "skipped": [{"step", "reason"}], "note"}
};

// One UnitPlan per camera (in plan order), the radar, each log of the manifest that no step reads, and
// "trial" when the plan is empty. Pure: the manifest and BuildPlan's steps.
std::vector<UnitPlan> PlanByUnit(const TrialManifest& manifest, const std::vector<Step>& plan);

// The manifest asks for a product the plan cannot make: throws DataError "trial.json:LINE:COL: ..." at the
// request. Requests are (1) each key of "steps" that is not false, for every unit it names (a KIND key: the
// units of that kind there are; plots excepted: a plot is a warning), and (2) each camera's role, which asks
// for its chain's last product (beacon: locate, features: attitude-oi, silhouette: attitude-cylinder) unless
// "steps" switches that step or one before it off. A requested step that is not applicable fails, as does a
// "radar/KIND" key without a radar block.
void CheckRequestedProducts(const TrialManifest& manifest, const std::vector<Step>& plan);

}  // namespace rk::run

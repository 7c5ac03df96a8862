// The plan seen per unit (which steps are planned, which are skipped and why) and the products a manifest
// asks for; declared in run/plan.h.
#include <algorithm>
#include <set>

#include "io/error.h"
#include "io/json_positions.h"
#include "run/plan.h"
#include "trial/layout.h"
#include "trial/manifest.h"

namespace rk::run {
using io::Json;

namespace {

// The step's name within its unit: "locate", "plot-located".
std::string StepName(const Step& s) { return s.id.substr(s.unit.size() + 1); }

// The last product each camera role's chain makes (a role asks for it).
const char* MainKind(CameraRole role) {
  switch (role) {
    case CameraRole::kBeacon: return "locate";
    case CameraRole::kFeatures: return "attitude-oi";
    case CameraRole::kSilhouette: return "attitude-cylinder";
    case CameraRole::kPoints: return "locate-points";
  }
  return "";
}

UnitPlan UnitOf(const std::string& unit, const std::string& what, const std::vector<Step>& plan) {
  UnitPlan u;
  u.unit = unit;
  u.what = what;
  for (const Step& s : plan) {
    if (s.unit != unit) continue;
    if (s.state == PlanState::kActive) {
      u.planned.push_back(StepName(s) + (s.method.empty() ? "" : " (" + s.method + ")"));
    } else {
      u.skipped.emplace_back(StepName(s), std::string(PlanStateName(s.state)) + ": " + s.note);
    }
  }
  if (u.planned.empty() && u.skipped.empty()) u.note = "no step of rk-run applies to it";
  return u;
}

// The manifest's logs that no step reads (planned or not): each is a unit whose note says why.
void UnusedLogs(const trial::StationEntry& st, const std::vector<Step>& plan, std::vector<UnitPlan>* units) {
  std::set<std::string> read;
  for (const Step& s : plan) {
    for (const StepInput& in : s.inputs) read.insert(in.path);
  }
  const std::pair<const char*, const std::string*> logs[] = {
      {"turret", &st.turret}, {"range", &st.range}, {"theodolite", &st.theodolite}};
  for (const auto& [key, path] : logs) {
    if (path->empty() || read.count(*path)) continue;
    UnitPlan u;
    u.unit = st.name.empty() ? key : st.name + "/" + key;
    u.what = "log " + *path;
    const std::string key_s = key;
    if (key_s == "range") {
      u.note = "not used: no beacon camera in \"cameras\" (only rk-locate and resample-range read a range log)";
    } else if (key_s == "theodolite" && st.cameras.empty()) {
      u.note = "not used: \"cameras\" lists no camera, so there are no frames to take silhouette points from "
               "(a theodolite camera needs \"video\": its frames)";
    } else if (key_s == "theodolite") {
      u.note = "not used: no silhouette camera, and the beacon cameras use the turret log";
    } else {
      u.note = st.cameras.empty() ? "not used: \"cameras\" lists no camera" : "not used: no camera needs it";
    }
    units->push_back(u);
  }
}

}  // namespace

std::string UnitPlan::Line() const {
  std::string s = unit + " (" + what + "): ";
  if (!note.empty()) return s + note;
  std::string planned_text, skipped_text;
  for (const auto& p : planned) planned_text += (planned_text.empty() ? "" : ", ") + p;
  for (const auto& [step, why] : skipped) skipped_text += (skipped_text.empty() ? "" : "; ") + step + " (" + why + ")";
  s += "planned " + (planned_text.empty() ? std::string("nothing") : planned_text);
  if (!skipped_text.empty()) s += "; skipped " + skipped_text;
  return s;
}

Json UnitPlan::ToJson() const {
  Json skipped_json = Json::array();
  for (const auto& [step, why] : skipped) skipped_json.push_back({{"step", step}, {"reason", why}});
  Json j = {{"unit", unit}, {"what", what}, {"planned", planned}, {"skipped", skipped_json}};
  if (!note.empty()) j["note"] = note;
  return j;
}

std::vector<UnitPlan> PlanByUnit(const TrialManifest& m, const std::vector<Step>& plan) {
  std::vector<UnitPlan> units;
  const std::vector<trial::StationEntry>& stations = m.stations;
  for (const trial::StationEntry& st : stations) {
    for (const CameraEntry& cam : st.cameras) {
      units.push_back(UnitOf(st.Unit(cam), std::string(CameraRoleName(cam.role)) + " camera", plan));
    }
  }
  if (m.radar) units.push_back(UnitOf("radar", "radar", plan));
  if (m.multi_station()) {
    units.push_back(UnitOf(trial::kTrajectoryUnit, "intersection of the stations", plan));
  } else if (std::any_of(plan.begin(), plan.end(), [](const Step& s) {
               return s.unit == trial::kTrajectoryUnit && s.kind.rfind("export-", 0) == 0;
             })) {
    // A single station's camera may itself be named "trajectory" (SPEC.md allows it): one unit, whose line
    // already lists the export steps beside the camera's, not the same unit twice.
    const auto same = std::find_if(units.begin(), units.end(),
                                   [](const UnitPlan& u) { return u.unit == trial::kTrajectoryUnit; });
    if (same != units.end()) {
      same->what += ", and export of the located target";
    } else {
      units.push_back(UnitOf(trial::kTrajectoryUnit, "export of the located target", plan));
    }
  }
  for (const trial::StationEntry& st : stations) UnusedLogs(st, plan, &units);
  if (plan.empty()) {
    UnitPlan u;
    u.unit = "trial";
    u.what = "manifest";
    u.note = "nothing to run: the manifest lists no camera and no radar";
    units.push_back(u);
  }
  return units;
}

void CheckRequestedProducts(const TrialManifest& m, const std::vector<Step>& plan) {
  const auto fail = [&](const std::string& pointer, const std::string& what, bool at_key) {
    trial::FailAt(m.manifest_path, m.positions, pointer, what, at_key);
  };
  for (const auto& [key, value] : m.steps.items()) {
    if (key == kBadRowsSetting || (value.is_boolean() && !value.get<bool>())) continue;
    const auto slash = key.rfind('/');
    const std::string unit = slash == std::string::npos ? "" : key.substr(0, slash);
    const std::string kind = slash == std::string::npos ? key : key.substr(slash + 1);
    // Plots are warnings; the intersection is checked last, after the cameras whose chains it needs.
    if (kind == "plot" || kind == "intersect") continue;
    const std::string pointer = "/steps/" + io::PointerToken(key);
    const bool exported = kind.rfind("export-", 0) == 0;
    if (exported && std::none_of(plan.begin(), plan.end(), [&](const Step& s) { return s.kind == kind; })) {
      fail(pointer, "asks for " + kind + ", but the trial has nothing in WGS-84 to export: it needs several stations, "
                    "or a station position, a range log and a beacon or points camera", true);
    }
    if (unit == "radar" && !m.radar) {
      fail(pointer, "asks for " + kind + " of the radar, but the manifest has no \"radar\" block ({\"plots\", \"nav\"})",
           true);
    }
    for (const Step& s : plan) {
      if (s.kind != kind || (!unit.empty() && s.unit != unit) || s.state != PlanState::kNotApplicable) continue;
      if (s.note.find(", which is off") != std::string::npos) continue;  // "steps" switched its chain off
      fail(pointer, "asks for " + s.id + ", which cannot run: " + s.note, true);
    }
  }
  for (const trial::StationEntry& st : m.stations) {
    for (const CameraEntry& cam : st.cameras) {
      const std::string unit = st.Unit(cam);
      const auto it = std::find_if(plan.begin(), plan.end(),
                                   [&](const Step& s) { return s.unit == unit && s.kind == MainKind(cam.role); });
      if (it == plan.end() || it->state != PlanState::kNotApplicable) continue;
      if (it->note.find(", which is off") != std::string::npos) continue;  // "steps" switched its chain off
      const std::string station = st.name.empty() ? "" : "/stations/" + io::PointerToken(st.name);
      fail(station + "/cameras/" + io::PointerToken(cam.name) + "/role",
           "a " + std::string(CameraRoleName(cam.role)) + " camera asks for " + it->id + ", which cannot run: " +
               it->note + " (switch it off in \"steps\" to run the rest)",
           false);
    }
  }
  // Several stations ask for their intersection.
  const auto it = std::find_if(plan.begin(), plan.end(), [](const Step& s) { return s.kind == "intersect"; });
  if (it != plan.end() && it->state == PlanState::kNotApplicable &&
      it->note.find(", which is off") == std::string::npos) {
    fail("/stations", "several stations ask for " + it->id + ", which cannot run: " + it->note +
                          " (switch it off in \"steps\" to run the rest)", true);
  }
}

}  // namespace rk::run

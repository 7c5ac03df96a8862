#include "run/manifest.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <utility>

#include "io/error.h"
#include "io/json_positions.h"
#include "trial/layout.h"

namespace rk::run {
namespace fs = std::filesystem;
using io::Json;

const std::vector<StepKindInfo>& StepKinds() {
  static const std::vector<std::string> kVideo = {"video", "frames", "fps", "t0"};
  static const std::vector<StepKindInfo> kinds = {
      {"extract-beacon", "beacon", "rk-extract", "beacon", kVideo, {"decode-only"}},
      {"locate", "beacon", "rk-locate", "", {"track", "camera", "turret", "range", "pointing", "station"}},
      {"smooth", "beacon", "rk-smooth", "singer", {"i", "input"}},
      {"resample-range", "beacon", "rk-smooth", "resample", {"i", "input", "at"}, {"rate", "t0", "t1"}},
      {"extract-features", "features", "rk-extract", "features", {"video", "frames", "fps", "t0", "target"}},
      {"attitude-oi", "features", "rk-attitude", "oi",
       {"points", "camera", "target", "turret", "boresight", "pointing"}},
      {"extract-silhouette", "silhouette", "rk-extract", "silhouette", kVideo},
      {"attitude-cylinder", "silhouette", "rk-attitude", "cylinder",
       {"points", "theodolite", "camera", "target", "video", "pointing"}},
      {"extract-points", "points", "rk-extract", "points", {"video", "frames", "fps", "t0", "seeds"}},
      {"locate-points", "points", "rk-locate", "", {"track", "camera", "turret", "range", "pointing", "station"}},
      {"register", "radar", "rk-register", "bernoulli", {"plots", "nav"}},
      {"register-batch", "radar", "rk-register", "batch", {"plots", "nav"}},
      {"intersect", "trajectory", "rk-intersect", "", {"stations"}},
      {"export-kml", "trajectory", "rk-export", "kml", {"trajectory", "located", "epoch-utc", "name"}},
      {"export-czml", "trajectory", "rk-export", "czml", {"trajectory", "located", "epoch-utc", "name"}},
      {"plot", "*", "rk-plot", "", {"i", "input"}},
  };
  return kinds;
}

const StepKindInfo* FindStepKind(const std::string& kind) {
  for (const auto& k : StepKinds()) {
    if (kind == k.kind) return &k;
  }
  return nullptr;
}

bool IsReservedOption(const StepKindInfo& kind, const std::string& option) {
  static const std::set<std::string> common = {"help", "h", "version", "report", "quiet", "q", "o", "output"};
  const auto listed = [&](const std::vector<std::string>& v) { return std::find(v.begin(), v.end(), option) != v.end(); };
  return common.count(option) > 0 || listed(kind.bindings) || listed(kind.contradicting);
}

bool IsReservedOption(const std::string& kind, const std::string& option) {
  static const StepKindInfo kUnknown = {"", "", "", "", {}};
  const StepKindInfo* info = FindStepKind(kind);
  return IsReservedOption(info ? *info : kUnknown, option);
}

Json StepSettings::AsJson() const {
  Json j = Json::object();
  for (const auto& [k, v] : options) j[k] = v;
  for (const auto& [k, v] : run.items()) j[k] = v;
  return j;
}

const std::vector<std::string>& RunSettingKeys(const std::string& kind) {
  static const std::vector<std::string> none, cylinder = {kImageFitSetting};
  return kind == "attitude-cylinder" ? cylinder : none;
}

namespace {

// Errors that point into trial.json (trial::FailAt).
class Checker {
 public:
  Checker(const std::string& file, const io::JsonPositions& pos) : file_(file), pos_(pos) {}
  [[noreturn]] void Fail(const std::string& pointer, const std::string& what, bool at_key = false) const {
    trial::FailAt(file_, pos_, pointer, what, at_key);
  }

 private:
  std::string file_;
  const io::JsonPositions& pos_;
};

bool ValidOptionName(const std::string& name) {
  static const std::regex re("^[A-Za-z0-9][A-Za-z0-9_-]*$");
  return std::regex_match(name, re);
}

void CheckStepValue(const Checker& c, const Json& v, const std::string& pointer, const std::string& kind) {
  if (v.is_boolean()) return;
  if (!v.is_object())
    c.Fail(pointer, "must be an object of options, true or false (switch the step off)");
  for (const auto& [name, value] : v.items()) {
    const std::string p = pointer + "/" + io::PointerToken(name);
    std::string opt = name;
    while (!opt.empty() && opt[0] == '-') opt.erase(0, 1);
    if (!ValidOptionName(opt)) c.Fail(p, "'" + name + "' is not an option name", true);
    const std::vector<std::string>& run_keys = RunSettingKeys(kind);
    if (std::find(run_keys.begin(), run_keys.end(), opt) != run_keys.end()) {
      if (!value.is_boolean()) c.Fail(p, "must be true or false (an rk-run setting of the step, not an option)");
      continue;
    }
    if (IsReservedOption(kind, opt)) {
      c.Fail(p, "option '--" + opt + "' is set by rk-run from the manifest and cannot be overridden", true);
    }
    const auto scalar = [](const Json& x) { return x.is_string() || x.is_number() || x.is_boolean(); };
    if (value.is_array()) {
      if (value.empty()) c.Fail(p, "an empty list is not an option value");
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (!value[i].is_string() && !value[i].is_number()) {
          c.Fail(p + "/" + std::to_string(i), "list items must be strings or numbers");
        }
      }
    } else if (!scalar(value)) {
      c.Fail(p, "option values must be a string, a number, true/false or a list");
    }
    if (value.is_number_float() && !std::isfinite(value.get<double>())) c.Fail(p, "is not finite");
  }
}

}  // namespace

namespace {

// The role of camera unit `unit` ("az", or "s1/az" in a multi-station manifest); "" when there is none.
std::string CameraUnitRole(const trial::Manifest& m, const std::string& unit) {
  for (const trial::StationEntry& st : m.stations) {
    for (const CameraEntry& cam : st.cameras) {
      if (st.Unit(cam) == unit) return CameraRoleName(cam.role);
    }
  }
  return "";
}

// rk-run's checks of a manifest lib/trial has read: every key of "steps" a step kind (or "<unit>/<kind>"
// of a unit it applies to) with valid options, or the trial-wide "bad-rows".
TrialManifest CheckSteps(trial::Manifest read, const std::string& manifest_path) {
  TrialManifest m;
  static_cast<trial::Manifest&>(m) = std::move(read);
  const Checker c(manifest_path, m.positions);
  for (const auto& [key, value] : m.steps.items()) {
    const std::string p = "/steps/" + io::PointerToken(key);
    if (key == kBadRowsSetting) {
      if (!value.is_string() || (value.get<std::string>() != "error" && value.get<std::string>() != "skip")) {
        c.Fail(p, "must be \"error\" or \"skip\" (--bad-rows of every step that reads CSV)");
      }
      continue;
    }
    std::string unit, kind = key;
    const auto slash = key.rfind('/');  // a unit may hold one: "s1/az" (station/camera)
    if (slash != std::string::npos) {
      unit = key.substr(0, slash);
      kind = key.substr(slash + 1);
    }
    const StepKindInfo* info = FindStepKind(kind);
    if (!info) {
      std::string known;
      for (const auto& k : StepKinds()) known += std::string(known.empty() ? "" : ", ") + k.kind;
      c.Fail(p, "unknown step '" + kind + "' (steps: " + known + ")", true);
    }
    // The intersection needs several stations; the exports also take a single station's located target.
    if (std::string(info->kind) == "intersect" && !m.multi_station()) {
      c.Fail(p, "step '" + kind + "' needs several stations (a manifest with 'stations')", true);
    }
    if (!unit.empty()) {
      std::string unit_role;
      if (unit == "radar") {
        unit_role = "radar";
      } else if (unit == trial::kTrajectoryUnit &&
                 (m.multi_station() || std::string(info->unit) == trial::kTrajectoryUnit)) {
        unit_role = trial::kTrajectoryUnit;
      } else {
        unit_role = CameraUnitRole(m, unit);
        if (unit_role.empty()) {
          c.Fail(p, m.multi_station() ? "no camera 'STATION/CAMERA' named '" + unit + "' in 'stations'"
                                      : "no camera named '" + unit + "' in 'cameras'", true);
        }
      }
      if (std::string(info->unit) != "*" && unit_role != info->unit) {
        c.Fail(p, "step '" + kind + "' does not apply to '" + unit + "' (a " + unit_role + " unit)", true);
      }
    }
    CheckStepValue(c, value, p, kind);
  }
  return m;
}

}  // namespace

TrialManifest ParseManifest(const std::string& text, const std::string& manifest_path) {
  return CheckSteps(trial::ParseManifest(text, manifest_path), manifest_path);
}

TrialManifest LoadManifest(const std::string& path) {
  std::error_code ec;
  std::string file = path;
  if (fs::is_directory(path, ec)) file = (fs::path(path) / trial::kManifestFile).string();
  return CheckSteps(trial::LoadManifest(file), file);
}

StepSettings TrialManifest::Settings(const std::string& unit, const std::string& kind) const {
  StepSettings s;
  // The trial-wide --bad-rows goes to every step whose tool reads CSV (all but the plots); a
  // step's own "bad-rows" (merged below) wins.
  if (steps.contains(kBadRowsSetting) && kind != "plot") s.options.emplace_back("bad-rows", steps.at(kBadRowsSetting));
  for (const std::string& key : {kind, unit + "/" + kind}) {
    if (!steps.contains(key)) continue;
    const Json& v = steps.at(key);
    if (v.is_boolean()) {
      s.enabled = v.get<bool>();
      continue;
    }
    s.enabled = true;
    for (const auto& [name, value] : v.items()) {
      std::string opt = name;
      while (!opt.empty() && opt[0] == '-') opt.erase(0, 1);
      const std::vector<std::string>& run_keys = RunSettingKeys(kind);
      if (std::find(run_keys.begin(), run_keys.end(), opt) != run_keys.end()) {
        s.run[opt] = value;
        continue;
      }
      auto it = std::find_if(s.options.begin(), s.options.end(), [&](const auto& o) { return o.first == opt; });
      if (it != s.options.end())
        it->second = value;
      else
        s.options.emplace_back(opt, value);
    }
  }
  return s;
}

}  // namespace rk::run

#include "run/manifest.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include "io/error.h"
#include "io/file_util.h"

namespace rk::run {
namespace fs = std::filesystem;
using io::Json;

const char* CameraRoleName(CameraRole role) {
  switch (role) {
    case CameraRole::kBeacon: return "beacon";
    case CameraRole::kFeatures: return "features";
    case CameraRole::kSilhouette: return "silhouette";
  }
  return "?";
}

const std::vector<StepKindInfo>& StepKinds() {
  static const std::vector<StepKindInfo> kinds = {
      {"extract-beacon", "beacon", "rk-extract", "beacon"},
      {"locate", "beacon", "rk-locate", ""},
      {"smooth", "beacon", "rk-smooth", "singer"},
      {"resample-range", "beacon", "rk-smooth", "resample"},
      {"extract-features", "features", "rk-extract", "features"},
      {"attitude-oi", "features", "rk-attitude", "oi"},
      {"extract-silhouette", "silhouette", "rk-extract", "silhouette"},
      {"attitude-cylinder", "silhouette", "rk-attitude", "cylinder"},
      {"register", "radar", "rk-register", "bernoulli"},
      {"register-batch", "radar", "rk-register", "batch"},
      {"plot", "*", "rk-plot", ""},
  };
  return kinds;
}

const StepKindInfo* FindStepKind(const std::string& kind) {
  for (const auto& k : StepKinds()) {
    if (kind == k.kind) return &k;
  }
  return nullptr;
}

bool IsReservedOption(const std::string& kind, const std::string& option) {
  static const std::set<std::string> common = {"help", "h", "version", "report", "quiet", "q", "o", "output"};
  if (common.count(option)) return true;
  static const std::map<std::string, std::set<std::string>> per_kind = {
      {"extract-beacon", {"video", "frames", "fps", "t0", "decode-only"}},
      {"extract-features", {"video", "frames", "fps", "t0", "target"}},
      {"extract-silhouette", {"video", "frames", "fps", "t0"}},
      {"locate", {"track", "camera", "turret", "range"}},
      {"smooth", {"i", "input"}},
      {"resample-range", {"i", "input", "at", "rate", "t0", "t1"}},
      {"attitude-oi", {"points", "camera", "target", "turret", "boresight"}},
      {"attitude-cylinder", {"points", "theodolite", "camera", "target"}},
      {"register", {"plots", "nav"}},
      {"register-batch", {"plots", "nav"}},
      {"plot", {"i", "input"}},
  };
  auto it = per_kind.find(kind);
  return it != per_kind.end() && it->second.count(option) > 0;
}

Json StepSettings::AsJson() const {
  Json j = Json::object();
  for (const auto& [k, v] : options) j[k] = v;
  return j;
}

namespace {

// Errors that point into trial.json.
class Checker {
 public:
  Checker(const std::string& file, const JsonPositions& pos) : file_(file), pos_(pos) {}

  [[noreturn]] void Fail(const std::string& pointer, const std::string& what, bool at_key = false) const {
    const TextPosition p = at_key ? pos_.KeyAt(pointer) : pos_.At(pointer);
    throw DataError(file_, p.line, p.column, Dotted(pointer) + (pointer.empty() ? "" : ": ") + what);
  }
  static std::string Dotted(const std::string& pointer) {
    std::string out;
    for (std::size_t i = 0; i < pointer.size(); ++i) {
      if (pointer[i] == '/') {
        if (i > 0) out.push_back('.');
      } else if (pointer[i] == '~' && i + 1 < pointer.size()) {
        out.push_back(pointer[i + 1] == '1' ? '/' : '~');
        ++i;
      } else {
        out.push_back(pointer[i]);
      }
    }
    return out;
  }
  // A relative (or absolute) path string; empty = absent (null or missing).
  std::string OptionalPath(const Json& obj, const std::string& key, const std::string& pointer) const {
    if (!obj.contains(key) || obj.at(key).is_null()) return "";
    return Path(obj.at(key), pointer + "/" + PointerToken(key));
  }
  std::string Path(const Json& v, const std::string& pointer) const {
    if (!v.is_string()) Fail(pointer, "must be a path (string, relative to the trial folder)");
    const std::string s = v.get<std::string>();
    if (s.empty()) Fail(pointer, "is an empty path");
    if (s == "-") Fail(pointer, "'-' (stdin) is not a trial file");
    return s;
  }
  std::string RequirePath(const Json& obj, const std::string& key, const std::string& pointer) const {
    if (!obj.contains(key) || obj.at(key).is_null()) Fail(pointer, "missing field '" + key + "'");
    return Path(obj.at(key), pointer + "/" + PointerToken(key));
  }

 private:
  std::string file_;
  const JsonPositions& pos_;
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
    const std::string p = pointer + "/" + PointerToken(name);
    std::string opt = name;
    while (!opt.empty() && opt[0] == '-') opt.erase(0, 1);
    if (!ValidOptionName(opt)) c.Fail(p, "'" + name + "' is not an option name", true);
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

TrialManifest ParseManifest(const std::string& text, const std::string& manifest_path) {
  TrialManifest m;
  std::error_code ec;
  fs::path abs = fs::absolute(fs::path(manifest_path), ec).lexically_normal();
  m.manifest_path = abs.string();
  m.dir = abs.parent_path().string();
  m.text = text;
  m.json = io::ParseJson(text, manifest_path);
  m.positions = JsonPositions(text);
  const Checker c(manifest_path, m.positions);
  const Json& j = m.json;
  if (!j.is_object()) c.Fail("", "the manifest must be a JSON object");

  if (j.contains("name") && !j.at("name").is_null()) {
    if (!j.at("name").is_string() || j.at("name").get<std::string>().empty()) c.Fail("/name", "must be a non-empty string");
    m.name = j.at("name").get<std::string>();
  } else {
    m.name = abs.parent_path().filename().string();
  }
  if (j.contains("epoch_utc") && !j.at("epoch_utc").is_null()) {
    if (!j.at("epoch_utc").is_string()) c.Fail("/epoch_utc", "must be an ISO-8601 UTC time string");
    static const std::regex iso(R"(^\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}(\.\d+)?(Z|[+-]\d{2}:?\d{2})$)");
    m.epoch_utc = j.at("epoch_utc").get<std::string>();
    if (!std::regex_match(m.epoch_utc, iso)) c.Fail("/epoch_utc", "'" + m.epoch_utc + "' is not ISO-8601 (2026-11-21T08:00:00Z)");
  }
  m.station = j.contains("station") ? j.at("station") : Json(nullptr);
  if (!m.station.is_null()) {
    if (!m.station.is_object()) c.Fail("/station", "must be an object {lat_deg, lon_deg, h_m}");
    for (const char* k : {"lat_deg", "lon_deg", "h_m"}) {
      if (!m.station.contains(k)) c.Fail("/station", std::string("missing field '") + k + "'");
      if (!m.station.at(k).is_number()) c.Fail(std::string("/station/") + k, "must be a number");
    }
    const double lat = m.station.at("lat_deg").get<double>(), lon = m.station.at("lon_deg").get<double>();
    if (!(lat >= -90 && lat <= 90)) c.Fail("/station/lat_deg", "latitude must be in [-90, 90] degrees");
    if (!(lon >= -180 && lon <= 360)) c.Fail("/station/lon_deg", "longitude must be in [-180, 360] degrees");
  }

  if (!j.contains("cameras") || j.at("cameras").is_null()) {
    m.cameras.clear();
  } else {
    const Json& cams = j.at("cameras");
    if (!cams.is_object()) c.Fail("/cameras", "must be an object {name: camera}");
    for (const auto& [name, cam] : cams.items()) {
      const std::string p = "/cameras/" + PointerToken(name);
      static const std::regex name_re("^[A-Za-z0-9][A-Za-z0-9_.-]*$");
      if (!std::regex_match(name, name_re) || name == "radar" || name == "plots" || name == "steps") {
        c.Fail(p, "camera name '" + name + "' must be letters, digits, '_', '-', '.' (not radar/plots/steps)", true);
      }
      if (!cam.is_object()) c.Fail(p, "must be an object");
      CameraEntry e;
      e.name = name;
      if (!cam.contains("video")) c.Fail(p, "missing field 'video'");
      const Json& v = cam.at("video");
      if (v.is_string()) {
        e.video.push_back(c.Path(v, p + "/video"));
      } else if (v.is_array() && !v.empty()) {
        for (std::size_t i = 0; i < v.size(); ++i) e.video.push_back(c.Path(v[i], p + "/video/" + std::to_string(i)));
      } else {
        c.Fail(p + "/video", "must be a path or a non-empty list of paths");
      }
      e.frames = c.OptionalPath(cam, "frames", p);
      if (cam.contains("fps") && !cam.at("fps").is_null()) {
        if (!cam.at("fps").is_number() || !(cam.at("fps").get<double>() > 0)) c.Fail(p + "/fps", "must be a frame rate > 0 Hz");
        e.fps = cam.at("fps").get<double>();
      }
      if (cam.contains("t0_s") && !cam.at("t0_s").is_null()) {
        if (!cam.at("t0_s").is_number()) c.Fail(p + "/t0_s", "must be a number (s)");
        e.t0_s = cam.at("t0_s").get<double>();
      }
      if (e.frames.empty() && !e.fps) c.Fail(p, "give 'frames' (frame-times CSV) or 'fps'");
      if (!e.frames.empty() && e.fps) c.Fail(p + "/fps", "give either 'frames' or 'fps', not both");
      e.model = c.RequirePath(cam, "model", p);
      if (!cam.contains("role") || !cam.at("role").is_string()) c.Fail(p, "missing field 'role' (beacon, features or silhouette)");
      const std::string role = cam.at("role").get<std::string>();
      if (role == "beacon") {
        e.role = CameraRole::kBeacon;
      } else if (role == "features") {
        e.role = CameraRole::kFeatures;
      } else if (role == "silhouette") {
        e.role = CameraRole::kSilhouette;
      } else {
        c.Fail(p + "/role", "'" + role + "' is not one of beacon, features, silhouette");
      }
      e.target = c.OptionalPath(cam, "target", p);
      if (e.target.empty() && j.contains("target") && !j.at("target").is_null()) e.target = c.OptionalPath(j, "target", "");
      if (e.role != CameraRole::kBeacon && e.target.empty()) {
        c.Fail(p, std::string("a ") + role + " camera needs 'target' (target model JSON)");
      }
      if (cam.contains("boresight_deg") && !cam.at("boresight_deg").is_null()) {
        const Json& b = cam.at("boresight_deg");
        if (!b.is_array() || b.size() != 2 || !b[0].is_number() || !b[1].is_number()) {
          c.Fail(p + "/boresight_deg", "must be [azimuth_deg, elevation_deg]");
        }
        e.boresight_deg = std::make_pair(b[0].get<double>(), b[1].get<double>());
      }
      m.cameras.push_back(e);
    }
    std::sort(m.cameras.begin(), m.cameras.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  }
  m.turret = c.OptionalPath(j, "turret", "");
  m.range = c.OptionalPath(j, "range", "");
  m.theodolite = c.OptionalPath(j, "theodolite", "");
  if (j.contains("radar") && !j.at("radar").is_null()) {
    const Json& r = j.at("radar");
    if (!r.is_object()) c.Fail("/radar", "must be null or {\"plots\": ..., \"nav\": ...}");
    m.radar = RadarEntry{c.RequirePath(r, "plots", "/radar"), c.RequirePath(r, "nav", "/radar")};
  }

  m.steps = j.contains("steps") && !j.at("steps").is_null() ? j.at("steps") : Json::object();
  if (!m.steps.is_object()) c.Fail("/steps", "must be an object {step: options}");
  for (const auto& [key, value] : m.steps.items()) {
    const std::string p = "/steps/" + PointerToken(key);
    if (key == kBadRowsSetting) {
      if (!value.is_string() || (value.get<std::string>() != "error" && value.get<std::string>() != "skip")) {
        c.Fail(p, "must be \"error\" or \"skip\" (--bad-rows of every step that reads CSV)");
      }
      continue;
    }
    std::string unit, kind = key;
    const auto slash = key.find('/');
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
    if (!unit.empty()) {
      std::string unit_role;
      if (unit == "radar") {
        unit_role = "radar";
      } else {
        auto it = std::find_if(m.cameras.begin(), m.cameras.end(), [&](const auto& cam) { return cam.name == unit; });
        if (it == m.cameras.end()) c.Fail(p, "no camera named '" + unit + "' in 'cameras'", true);
        unit_role = CameraRoleName(it->role);
      }
      if (std::string(info->unit) != "*" && unit_role != info->unit) {
        c.Fail(p, "step '" + kind + "' does not apply to '" + unit + "' (a " + unit_role + " unit)", true);
      }
    }
    CheckStepValue(c, value, p, kind);
  }
  return m;
}

TrialManifest LoadManifest(const std::string& path) {
  std::error_code ec;
  std::string file = path;
  if (fs::is_directory(path, ec)) file = (fs::path(path) / "trial.json").string();
  return ParseManifest(io::ReadFile(file), file);
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
      auto it = std::find_if(s.options.begin(), s.options.end(), [&](const auto& o) { return o.first == opt; });
      if (it != s.options.end())
        it->second = value;
      else
        s.options.emplace_back(opt, value);
    }
  }
  return s;
}

std::vector<std::string> TrialManifest::AllPaths() const {
  std::vector<std::string> out;
  for (const auto& cam : cameras) {
    for (const auto& v : cam.video) out.push_back(v);
    if (!cam.frames.empty()) out.push_back(cam.frames);
    out.push_back(cam.model);
    if (!cam.target.empty()) out.push_back(cam.target);
  }
  for (const std::string* p : {&turret, &range, &theodolite}) {
    if (!p->empty()) out.push_back(*p);
  }
  if (radar) {
    out.push_back(radar->plots);
    out.push_back(radar->nav);
  }
  return out;
}

}  // namespace rk::run

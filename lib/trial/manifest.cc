// The trial manifest; format and checks in manifest.h.
#include "trial/manifest.h"

#include <algorithm>
#include <filesystem>
#include <regex>
#include <utility>

#include "io/error.h"
#include "io/file_util.h"
#include "io/utc_time.h"
#include "trial/layout.h"

namespace rk::trial {
namespace fs = std::filesystem;
using io::Json;

const char* CameraRoleName(CameraRole role) {
  switch (role) {
    case CameraRole::kBeacon: return "beacon";
    case CameraRole::kFeatures: return "features";
    case CameraRole::kSilhouette: return "silhouette";
    case CameraRole::kPoints: return "points";
  }
  return "?";
}

bool ParseCameraRole(const std::string& text, CameraRole* role) {
  for (CameraRole r : {CameraRole::kBeacon, CameraRole::kFeatures, CameraRole::kSilhouette, CameraRole::kPoints}) {
    if (text == CameraRoleName(r)) {
      *role = r;
      return true;
    }
  }
  return false;
}

CameraEntry CameraInItsFolder(const std::string& name, CameraRole role, std::vector<std::string> video) {
  CameraEntry c;
  c.name = name;
  c.video = std::move(video);
  c.frames = CameraFile(name, kFramesFile);
  c.model = CameraFile(name, kCameraModelFile);
  c.role = role;
  return c;
}

namespace {

// "a.b.c" for the JSON pointer "/a/b/c" (~1 → '/', ~0 → '~').
std::string Dotted(const std::string& pointer) {
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

// Errors that point into trial.json.
class Checker {
 public:
  Checker(const std::string& file, const io::JsonPositions& pos) : file_(file), pos_(pos) {}

  [[noreturn]] void Fail(const std::string& pointer, const std::string& what, bool at_key = false) const {
    FailAt(file_, pos_, pointer, what, at_key);
  }
  // A relative (or absolute) path string; empty = absent (null or missing).
  std::string OptionalPath(const Json& obj, const std::string& key, const std::string& pointer) const {
    if (!obj.contains(key) || obj.at(key).is_null()) return "";
    return Path(obj.at(key), pointer + "/" + io::PointerToken(key));
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
    return Path(obj.at(key), pointer + "/" + io::PointerToken(key));
  }

 private:
  std::string file_;
  const io::JsonPositions& pos_;
};


// A WGS-84 position {"lat_deg","lon_deg","h_m"} at `pointer` (checked; null passes).
void CheckPosition(const Checker& c, const Json& pos, const std::string& pointer) {
  if (pos.is_null()) return;
  if (!pos.is_object()) c.Fail(pointer, "must be an object {lat_deg, lon_deg, h_m}");
  for (const char* k : {"lat_deg", "lon_deg", "h_m"}) {
    if (!pos.contains(k)) c.Fail(pointer, std::string("missing field '") + k + "'");
    if (!pos.at(k).is_number()) c.Fail(pointer + "/" + k, "must be a number");
  }
  const double lat = pos.at("lat_deg").get<double>(), lon = pos.at("lon_deg").get<double>();
  if (!(lat >= -90 && lat <= 90)) c.Fail(pointer + "/lat_deg", "latitude must be in [-90, 90] degrees");
  if (!(lon >= -180 && lon <= 360)) c.Fail(pointer + "/lon_deg", "longitude must be in [-180, 360] degrees");
}

// One camera of "cameras" at pointer `p`; `root` gives the trial-wide "target".
CameraEntry ParseCamera(const Checker& c, const std::string& name, const Json& cam, const std::string& p,
                        const Json& root) {
  static const std::regex name_re("^[A-Za-z0-9][A-Za-z0-9_.-]*$");
  if (!std::regex_match(name, name_re) || name == "radar" || name == "plots" || name == "steps") {
    c.Fail(p, "camera name '" + name + "' may use only ASCII letters A-Z a-z, digits 0-9, '_', '-' and '.', "
              "starting with a letter or digit (it names a folder and a step on every system), and not radar/plots/steps",
           true);
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
  if (!cam.contains("role") || !cam.at("role").is_string()) c.Fail(p, "missing field 'role' (beacon, features, silhouette or points)");
  const std::string role = cam.at("role").get<std::string>();
  if (!ParseCameraRole(role, &e.role)) c.Fail(p + "/role", "'" + role + "' is not one of beacon, features, silhouette, points");
  e.target = c.OptionalPath(cam, "target", p);
  if (e.target.empty() && root.contains("target") && !root.at("target").is_null()) e.target = c.OptionalPath(root, "target", "");
  if ((e.role == CameraRole::kFeatures || e.role == CameraRole::kSilhouette) && e.target.empty()) {
    c.Fail(p, std::string("a ") + role + " camera needs 'target' (target model JSON)");
  }
  if (e.role == CameraRole::kPoints) e.seeds = c.RequirePath(cam, "seeds", p);
  if (cam.contains("boresight_deg") && !cam.at("boresight_deg").is_null()) {
    const Json& b = cam.at("boresight_deg");
    if (!b.is_array() || b.size() != 2 || !b[0].is_number() || !b[1].is_number()) {
      c.Fail(p + "/boresight_deg", "must be [azimuth_deg, elevation_deg]");
    }
    e.boresight_deg = std::make_pair(b[0].get<double>(), b[1].get<double>());
  }
  return e;
}

// What one station's part of a manifest says (the top level of a single-station manifest, pointer "", or
// "stations": {NAME: ...} at "/stations/NAME"): station position and pointing, cameras, turret/range/theodolite.
void ParseStationPart(const Checker& c, const Json& obj, const std::string& prefix, const Json& root,
                      StationEntry* out) {
  StationEntry& s = *out;
  s.station = obj.contains("station") ? obj.at("station") : Json(nullptr);
  CheckPosition(c, s.station, prefix + "/station");
  if (!s.station.is_null()) s.pointing = c.OptionalPath(s.station, "pointing", prefix + "/station");
  if (obj.contains("cameras") && !obj.at("cameras").is_null()) {
    const Json& cams = obj.at("cameras");
    if (!cams.is_object()) c.Fail(prefix + "/cameras", "must be an object {name: camera}");
    for (const auto& [name, cam] : cams.items()) {
      s.cameras.push_back(ParseCamera(c, name, cam, prefix + "/cameras/" + io::PointerToken(name), root));
    }
    std::sort(s.cameras.begin(), s.cameras.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  }
  s.turret = c.OptionalPath(obj, "turret", prefix);
  s.range = c.OptionalPath(obj, "range", prefix);
  s.theodolite = c.OptionalPath(obj, "theodolite", prefix);
}

// "stations" of a multi-station manifest (two or more, each with its position) and "origin"; the top level
// then may not carry a station's own keys.
void ParseStations(const Checker& c, const Json& j, Manifest* m) {
  for (const char* key : {"station", "cameras", "turret", "range", "theodolite"}) {
    if (j.contains(key) && !j.at(key).is_null()) {
      c.Fail(std::string("/") + key,
             std::string("a manifest with 'stations' gives '") + key + "' per station (stations.NAME." + key + ")",
             true);
    }
  }
  const Json& sts = j.at("stations");
  if (!sts.is_object()) c.Fail("/stations", "must be an object {name: station}");
  if (sts.size() < 2) c.Fail("/stations", "a multi-station trial needs at least two stations");
  static const std::regex name_re("^[A-Za-z0-9][A-Za-z0-9_-]*$");
  for (const auto& [name, st] : sts.items()) {
    const std::string p = "/stations/" + io::PointerToken(name);
    if (!std::regex_match(name, name_re) || name == "radar" || name == "plots" || name == "steps" ||
        name == kTrajectoryUnit) {
      c.Fail(p, "station name '" + name + "' must be letters, digits, '_', '-' (not radar/plots/steps/" +
                    kTrajectoryUnit + ")", true);
    }
    if (!st.is_object()) c.Fail(p, "must be an object {station, cameras, turret, range, theodolite}");
    if (!st.contains("station") || st.at("station").is_null()) {
      c.Fail(p, "missing field 'station' ({lat_deg, lon_deg, h_m}: the intersection needs every station's position)");
    }
    StationEntry e;
    e.name = name;
    ParseStationPart(c, st, p, j, &e);
    m->stations.push_back(std::move(e));
  }
  std::sort(m->stations.begin(), m->stations.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  m->origin = j.contains("origin") ? j.at("origin") : Json(nullptr);
  CheckPosition(c, m->origin, "/origin");
}

}  // namespace

void FailAt(const std::string& file, const io::JsonPositions& positions, const std::string& pointer,
            const std::string& what, bool at_key) {
  const io::TextPosition p = at_key ? positions.KeyAt(pointer) : positions.At(pointer);
  throw DataError(file, p.line, p.column, Dotted(pointer) + (pointer.empty() ? "" : ": ") + what);
}

Manifest ParseManifest(const std::string& text, const std::string& manifest_path) {
  Manifest m;
  std::error_code ec;
  fs::path abs = fs::absolute(fs::path(manifest_path), ec).lexically_normal();
  m.manifest_path = abs.string();
  m.dir = abs.parent_path().string();
  m.text = text;
  m.json = io::ParseJson(text, manifest_path);
  m.positions = io::JsonPositions(text);
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
    m.epoch_utc = j.at("epoch_utc").get<std::string>();
    io::UtcTime utc;
    std::string why;
    if (!io::ParseUtcIso(m.epoch_utc, &utc, &why)) {
      c.Fail("/epoch_utc", "'" + m.epoch_utc + "' is not an ISO-8601 UTC time: " + why);
    }
  }
  if (j.contains("stations") && !j.at("stations").is_null()) {
    ParseStations(c, j, &m);
  } else {
    m.stations.emplace_back();
    ParseStationPart(c, j, "", j, &m.stations.back());
  }
  if (j.contains("radar") && !j.at("radar").is_null()) {
    const Json& r = j.at("radar");
    if (!r.is_object()) c.Fail("/radar", "must be null or {\"plots\": ..., \"nav\": ...}");
    m.radar = RadarEntry{c.RequirePath(r, "plots", "/radar"), c.RequirePath(r, "nav", "/radar")};
  }

  m.steps = j.contains("steps") && !j.at("steps").is_null() ? j.at("steps") : Json::object();
  if (!m.steps.is_object()) c.Fail("/steps", "must be an object {step: options}");
  return m;
}

Manifest LoadManifest(const std::string& path) {
  std::error_code ec;
  std::string file = path;
  if (fs::is_directory(path, ec)) file = (fs::path(path) / kManifestFile).string();
  return ParseManifest(io::ReadFile(file), file);
}

StationEntry& Manifest::Single() {
  if (multi_station()) throw ProcessingError("a multi-station manifest has no single station");
  if (stations.empty()) stations.emplace_back();
  return stations.front();
}

const StationEntry& Manifest::Single() const {
  static const StationEntry kNone;
  if (multi_station()) throw ProcessingError("a multi-station manifest has no single station");
  return stations.empty() ? kNone : stations.front();
}

std::vector<std::string> Manifest::AllPaths() const {
  std::vector<std::string> out;
  for (const StationEntry& st : stations) {
    for (const auto& cam : st.cameras) {
      for (const auto& v : cam.video) out.push_back(v);
      if (!cam.frames.empty()) out.push_back(cam.frames);
      out.push_back(cam.model);
      if (!cam.target.empty()) out.push_back(cam.target);
      if (!cam.seeds.empty()) out.push_back(cam.seeds);
    }
    for (const std::string* p : {&st.turret, &st.range, &st.theodolite, &st.pointing}) {
      if (!p->empty()) out.push_back(*p);
    }
  }
  if (radar) {
    out.push_back(radar->plots);
    out.push_back(radar->nav);
  }
  return out;
}

namespace {

Json CamerasToJson(const std::vector<CameraEntry>& cameras) {
  Json cams = Json::object();
  for (const CameraEntry& cam : cameras) {
    Json c;
    c["video"] = cam.video;
    if (!cam.frames.empty()) c["frames"] = cam.frames;
    if (cam.fps) c["fps"] = *cam.fps;
    if (cam.t0_s) c["t0_s"] = *cam.t0_s;
    c["model"] = cam.model.empty() ? Json(nullptr) : Json(cam.model);
    c["role"] = CameraRoleName(cam.role);
    if (!cam.target.empty()) c["target"] = cam.target;
    if (!cam.seeds.empty()) c["seeds"] = cam.seeds;
    if (cam.boresight_deg) c["boresight_deg"] = {cam.boresight_deg->first, cam.boresight_deg->second};
    cams[cam.name] = c;
  }
  return cams;
}

// station, cameras, turret, range, theodolite of one station into `j`.
void StationPartToJson(const StationEntry& s, Json* j) {
  const auto path_or_null = [](const std::string& p) { return p.empty() ? Json(nullptr) : Json(p); };
  (*j)["station"] = s.station;
  (*j)["cameras"] = CamerasToJson(s.cameras);
  (*j)["turret"] = path_or_null(s.turret);
  (*j)["range"] = path_or_null(s.range);
  (*j)["theodolite"] = path_or_null(s.theodolite);
}

}  // namespace

Json ManifestToJson(const Manifest& m) {
  Json j;
  j["name"] = m.name;
  j["epoch_utc"] = m.epoch_utc;
  if (!m.multi_station()) {
    StationPartToJson(m.Single(), &j);
  } else {
    j["origin"] = m.origin;
    Json sts = Json::object();
    for (const StationEntry& st : m.stations) StationPartToJson(st, &sts[st.name]);
    j["stations"] = sts;
  }
  j["radar"] = m.radar ? Json{{"plots", m.radar->plots}, {"nav", m.radar->nav}} : Json(nullptr);
  j["steps"] = m.steps;
  for (const auto& [key, value] : m.extra.items()) j[key] = value;
  return j;
}

void WriteManifest(const std::string& path, const Manifest& manifest) { io::WriteJson(path, ManifestToJson(manifest)); }

}  // namespace rk::trial

#include "capture/station_config.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "trial/layout.h"

namespace rk::capture {
namespace fs = std::filesystem;
namespace {

std::string Resolve(const std::string& config_path, const std::string& p) {
  if (p.empty() || fs::path(p).is_absolute()) return p;
  const fs::path base = fs::path(config_path).parent_path();
  return (base / p).lexically_normal().string();
}

void WarnUnknown(const io::Json& j, const std::set<std::string>& known, const std::string& where,
                 std::vector<std::string>* warnings) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (!known.count(it.key())) warnings->push_back(where + ": unknown key '" + it.key() + "' (kept, not used)");
  }
}

bool BoolOr(const io::Json& j, const std::string& key, bool fallback, const std::string& where) {
  if (!j.contains(key) || j.at(key).is_null()) return fallback;
  if (!j.at(key).is_boolean()) throw DataError(where, 0, 0, "field '" + key + "' must be true or false");
  return j.at(key).get<bool>();
}

std::string StringOr(const io::Json& j, const std::string& key, const std::string& fallback, const std::string& where) {
  if (!j.contains(key) || j.at(key).is_null()) return fallback;
  return io::RequireString(j, key, where);
}

int IntOr(const io::Json& j, const std::string& key, int fallback, const std::string& where) {
  const double v = io::NumberOr(j, key, fallback, where);
  if (v != std::floor(v) || std::abs(v) > 1e9) throw DataError(where, 0, 0, "field '" + key + "' must be an integer");
  return static_cast<int>(v);
}

std::string ResolvePort(const std::string& config_path, const std::string& port) {
  // "/dev/ttyUSB0" stays; a relative name (an emulator's link beside the config) is resolved.
  return Resolve(config_path, port);
}

void CheckReadable(const std::string& path, const std::string& where) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw IoError(path, "cannot read (named in " + where + ")");
}

// A feature value as GenICam takes it from a string: a number in full precision, a string as is, true/false.
template <class J>
std::string FeatureText(const J& v) {
  if (v.is_string()) return v.template get<std::string>();
  if (v.is_boolean()) return v.template get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return v.dump();
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v.template get<double>());
  return buf;
}

CameraConfig CameraFromJson(const io::Json& c, const std::string& path, std::size_t index,
                            std::vector<std::string>* warnings) {
  const std::string where0 = path + ": cameras[" + std::to_string(index) + "]";
  if (!c.is_object()) throw DataError(where0, 0, 0, "must be an object");
  CameraConfig cam;
  cam.name = io::RequireString(c, "name", where0);
  const std::string where = path + ": camera '" + cam.name + "'";
  if (cam.name.empty() || cam.name.size() > 64) throw DataError(where, 0, 0, "'name' must be 1 to 64 characters");
  for (char ch : cam.name) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_' ||
                    ch == '-';
    if (!ok) throw DataError(where, 0, 0, "'name' may use letters, digits, '_' and '-' only (it names a folder)");
  }
  cam.source_text = io::RequireString(c, "source", where);
  cam.source.source = cam.source_text;
  for (const std::string prefix : {"file:", "cvfile:"}) {
    if (cam.source_text.rfind(prefix, 0) == 0) {
      const std::string file = cam.source_text.substr(prefix.size());
      if (file.empty()) throw DataError(where, 0, 0, "'source' " + prefix + " needs a path");
      cam.source.source = prefix + Resolve(path, file);
    }
  }
  cam.source.fps = io::NumberOr(c, "fps", 20.0, where);
  if (!(cam.source.fps > 0 && cam.source.fps <= 1000)) throw DataError(where, 0, 0, "'fps' must be in (0, 1000]");
  cam.source.width = IntOr(c, "width", 0, where);
  cam.source.height = IntOr(c, "height", 0, where);
  if (cam.source.width < 0 || cam.source.height < 0) throw DataError(where, 0, 0, "'width'/'height' must be >= 0");
  cam.source.fourcc = StringOr(c, "fourcc", "", where);
  if (!cam.source.fourcc.empty() && cam.source.fourcc.size() != 4)
    throw DataError(where, 0, 0, "'fourcc' must have 4 characters, e.g. \"GREY\"");
  cam.source.loop = BoolOr(c, "loop", false, where);
  cam.role = StringOr(c, "role", "beacon", where);
  if (cam.role != "beacon" && cam.role != "features" && cam.role != "silhouette")
    throw DataError(where, 0, 0, "'role' must be beacon, features or silhouette, not '" + cam.role + "'");
  cam.format = StringOr(c, "format", "y4m", where);
  if (cam.format != "y4m" && cam.format != "pgm") throw DataError(where, 0, 0, "'format' must be y4m or pgm");
  cam.queue_frames = IntOr(c, "queue_frames", 0, where);
  const int one_second = static_cast<int>(std::floor(cam.source.fps));
  if (cam.queue_frames < 0 || cam.queue_frames > std::max(2, one_second))
    throw DataError(where, 0, 0, "'queue_frames' must be 0 (auto) ... " + std::to_string(std::max(2, one_second)) +
                                     " (at most one second of frames may wait for the disk)");
  if (c.contains("model") && !c.at("model").is_null()) {
    cam.model_path = Resolve(path, io::RequireString(c, "model", where));
    CheckReadable(cam.model_path, where);
    camera::LoadCameraModel(cam.model_path);  // validated now, not after an hour of recording
  } else {
    warnings->push_back(where + ": no 'model'; the manifest will have \"model\": null");
  }
  if (c.contains("target") && !c.at("target").is_null()) {
    cam.target_path = Resolve(path, io::RequireString(c, "target", where));
    CheckReadable(cam.target_path, where);
    io::LoadJson(cam.target_path);
  }
  // GenICam features of an Aravis camera: names and scalar values (their order is taken from the file's text by
  // LoadStationConfig: nlohmann's json sorts keys).
  if (c.contains("features") && !c.at("features").is_null()) {
    const io::Json& f = c.at("features");
    if (!f.is_object()) throw DataError(where, 0, 0, "'features' must be an object of GenICam feature names and values");
    if (cam.source_text.rfind("aravis:", 0) != 0) {
      warnings->push_back(where + ": 'features' are set only on an aravis: camera; ignored");
    }
    for (const auto& [name, v] : f.items()) {
      if (!(v.is_number() || v.is_string() || v.is_boolean())) {
        throw DataError(where, 0, 0, "feature '" + name + "' must be a number, a string or true/false");
      }
      cam.source.features.emplace_back(name, FeatureText(v));
    }
  }
  cam.source.ptp = BoolOr(c, "ptp", false, where);
  // Validate the source string now (a bad synthetic: spec is a config error).
  try {
    MakeCameraSource(cam.source);
  } catch (const Error& e) {
    throw DataError(where, 0, 0, e.what());
  }
  WarnUnknown(c,
              {"name", "source", "fps", "model", "role", "target", "format", "queue_frames", "width", "height",
               "fourcc", "loop", "features", "ptp"},
              where, warnings);
  return cam;
}

DimetixOptions RangefinderFromJson(const io::Json& r, const std::string& path, std::vector<std::string>* warnings) {
  const std::string where = path + ": rangefinder";
  if (!r.is_object()) throw DataError(where, 0, 0, "must be an object");
  DimetixOptions o;
  o.serial = SerialOptionsFromJson(r, where);
  o.serial.port = ResolvePort(path, o.serial.port);
  const std::string mode = StringOr(r, "mode", "tracking", where);
  if (mode == "tracking") {
    o.mode = DimetixMode::kTracking;
  } else if (mode == "single") {
    o.mode = DimetixMode::kSingle;
  } else {
    throw DataError(where, 0, 0, "'mode' must be tracking or single, not '" + mode + "'");
  }
  o.rate_hz = io::NumberOr(r, "rate_hz", o.rate_hz, where);
  o.device_id = IntOr(r, "device_id", o.device_id, where);
  o.tracking_ms = IntOr(r, "tracking_ms", o.tracking_ms, where);
  o.timeout_s = io::NumberOr(r, "timeout_s", o.timeout_s, where);
  o.reconnect_s = io::NumberOr(r, "reconnect_s", o.reconnect_s, where);
  o.laser_off_at_end = BoolOr(r, "laser_off_at_end", o.laser_off_at_end, where);
  o.latency_s = io::NumberOr(r, "latency_s", o.latency_s, where);
  std::string why;
  if (!o.Check(&why)) throw DataError(where, 0, 0, why);
  WarnUnknown(r,
              {"port", "baud", "parity", "data_bits", "stop_bits", "mode", "rate_hz", "device_id", "tracking_ms",
               "timeout_s", "reconnect_s", "laser_off_at_end", "latency_s", "model"},
              where, warnings);
  return o;
}

PtuOptions TurretFromJson(const io::Json& t, const std::string& path, std::vector<std::string>* warnings) {
  const std::string where = path + ": turret";
  if (!t.is_object()) throw DataError(where, 0, 0, "must be an object");
  PtuOptions o;
  o.serial = SerialOptionsFromJson(t, where);
  o.serial.port = ResolvePort(path, o.serial.port);
  o.rate_hz = io::NumberOr(t, "rate_hz", o.rate_hz, where);
  o.timeout_s = io::NumberOr(t, "timeout_s", o.timeout_s, where);
  o.reconnect_s = io::NumberOr(t, "reconnect_s", o.reconnect_s, where);
  o.map.pan_zero_deg = io::NumberOr(t, "pan_zero_deg", 0.0, where);
  o.map.pan_sign = io::NumberOr(t, "pan_sign", 1.0, where);
  o.map.tilt_zero_deg = io::NumberOr(t, "tilt_zero_deg", 0.0, where);
  o.map.tilt_sign = io::NumberOr(t, "tilt_sign", 1.0, where);
  o.latency_s = io::NumberOr(t, "latency_s", o.latency_s, where);
  if (t.contains("point") && !t.at("point").is_null()) {
    const io::Json& p = t.at("point");
    if (!p.is_object()) throw DataError(where, 0, 0, "'point' must be {\"az_deg\": A, \"el_deg\": E}");
    o.point_az_deg = io::RequireNumber(p, "az_deg", where + ": point");
    o.point_el_deg = io::RequireNumber(p, "el_deg", where + ": point");
  }
  std::string why;
  if (!o.Check(&why)) throw DataError(where, 0, 0, why);
  WarnUnknown(t,
              {"port", "baud", "parity", "data_bits", "stop_bits", "rate_hz", "timeout_s", "reconnect_s",
               "pan_zero_deg", "pan_sign", "tilt_zero_deg", "tilt_sign", "point", "latency_s", "model"},
              where, warnings);
  return o;
}

}  // namespace

StationConfig StationConfigFromJson(const io::Json& j, const std::string& path) {
  if (!j.is_object()) throw DataError(path, 0, 0, "a station configuration must be a JSON object");
  StationConfig c;
  c.path = path;
  c.json = j;
  c.name = StringOr(j, "name", "", path);
  c.station = {{"lat_deg", 0.0}, {"lon_deg", 0.0}, {"h_m", 0.0}};
  if (j.contains("station") && !j.at("station").is_null()) {
    const io::Json& s = j.at("station");
    const std::string where = path + ": station";
    c.station = s;
    const double lat = io::RequireNumber(s, "lat_deg", where), lon = io::RequireNumber(s, "lon_deg", where);
    io::RequireNumber(s, "h_m", where);
    if (!(std::abs(lat) <= 90 && std::abs(lon) <= 180)) throw DataError(where, 0, 0, "latitude/longitude out of range");
    if (s.contains("pointing") && !s.at("pointing").is_null()) {
      c.pointing_path = Resolve(path, io::RequireString(s, "pointing", where));
      CheckReadable(c.pointing_path, where);
      camera::LoadPointingModel(c.pointing_path);  // validated now, not after an hour of recording
      c.station["pointing"] = trial::kPointingFile;
    }
  } else {
    c.warnings.push_back(path + ": no 'station' position; the manifest will say lat/lon/h = 0");
  }
  if (j.contains("steps") && !j.at("steps").is_null()) {
    if (!j.at("steps").is_object()) throw DataError(path, 0, 0, "'steps' must be an object");
    c.steps = j.at("steps");
  }
  c.segment_s = io::NumberOr(j, "segment_s", c.segment_s, path);
  if (!(c.segment_s >= 0.1 && c.segment_s <= 3600)) throw DataError(path, 0, 0, "'segment_s' must be in [0.1, 3600]");
  c.sync_s = io::NumberOr(j, "sync_s", c.sync_s, path);
  if (!(c.sync_s >= 0.05 && c.sync_s <= 1.0))
    throw DataError(path, 0, 0, "'sync_s' must be in [0.05, 1] (at most one second of data may be at risk)");
  c.manifest_s = io::NumberOr(j, "manifest_s", c.manifest_s, path);
  if (!(c.manifest_s >= 0.1 && c.manifest_s <= 60)) throw DataError(path, 0, 0, "'manifest_s' must be in [0.1, 60]");
  c.min_free_mb = io::NumberOr(j, "min_free_mb", c.min_free_mb, path);
  if (!(c.min_free_mb >= 0)) throw DataError(path, 0, 0, "'min_free_mb' must be >= 0");
  c.realtime_priority = IntOr(j, "realtime_priority", c.realtime_priority, path);
  if (c.realtime_priority < 0 || c.realtime_priority > 99)
    throw DataError(path, 0, 0, "'realtime_priority' must be 0 (off) ... 99");
  if (j.contains("cameras") && !j.at("cameras").is_null()) {
    const io::Json& cams = j.at("cameras");
    if (!cams.is_array()) throw DataError(path, 0, 0, "'cameras' must be an array");
    std::set<std::string> names;
    for (std::size_t i = 0; i < cams.size(); ++i) {
      CameraConfig cam = CameraFromJson(cams[i], path, i, &c.warnings);
      if (!names.insert(cam.name).second) throw DataError(path, 0, 0, "two cameras are named '" + cam.name + "'");
      c.cameras.push_back(std::move(cam));
    }
  }
  if (j.contains("rangefinder") && !j.at("rangefinder").is_null())
    c.rangefinder = RangefinderFromJson(j.at("rangefinder"), path, &c.warnings);
  if (j.contains("turret") && !j.at("turret").is_null()) c.turret = TurretFromJson(j.at("turret"), path, &c.warnings);
  if (c.rangefinder && c.turret && c.rangefinder->serial.port == c.turret->serial.port)
    throw DataError(path, 0, 0, "rangefinder and turret use the same port " + c.turret->serial.port);
  if (c.cameras.empty() && !c.rangefinder && !c.turret) throw DataError(path, 0, 0, "no cameras, rangefinder or turret to record");
  WarnUnknown(j,
              {"cameras", "rangefinder", "turret", "segment_s", "sync_s", "manifest_s", "min_free_mb", "name", "station",
               "steps", "theodolite", "radar", "realtime_priority"},
              path, &c.warnings);
  return c;
}

StationConfig LoadStationConfig(const std::string& path) {
  if (path == "-") throw UsageError("--config must name a file (paths in it are relative to it)");
  const std::string text = io::ReadFile(path);
  StationConfig c = StationConfigFromJson(io::ParseJson(text, path), path);
  // The features in the order the file gives them (two features can share a register: order matters).
  const nlohmann::ordered_json o = nlohmann::ordered_json::parse(text);
  if (o.contains("cameras") && o["cameras"].is_array()) {
    for (std::size_t i = 0; i < c.cameras.size() && i < o["cameras"].size(); ++i) {
      const auto& cam = o["cameras"][i];
      if (!cam.is_object() || !cam.contains("features") || !cam["features"].is_object()) continue;
      c.cameras[i].source.features.clear();
      for (const auto& [name, v] : cam["features"].items()) c.cameras[i].source.features.emplace_back(name, FeatureText(v));
    }
  }
  return c;
}

}  // namespace rk::capture

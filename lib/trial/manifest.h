// The trial manifest trial.json (SPEC.md §6): one struct, its reader (every field checked, errors that name
// trial.json's line and column) and its writer. rk-sim and rk-capture write it, rk-run reads it (and checks
// "steps" against its own step kinds, run/manifest.h); `rk-capture recover` repairs it as raw JSON (it must
// keep whatever a torn recording left) using the names of trial/layout.h.
//
// The manifest describes the trial's files: the station, the cameras (video, frame times, camera model,
// role, target model), the turret, range and theodolite logs and the radar files, all as paths relative to
// the trial folder; "steps" holds rk-run's per-step options (docs/rk-run.md); other keys (the writer's own
// record: "sim", "capture", an operator's notes) are kept as they are.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/json_util.h"
#include "io/json_positions.h"

namespace rk::trial {

enum class CameraRole { kBeacon, kFeatures, kSilhouette, kPoints };
const char* CameraRoleName(CameraRole role);
// "beacon", "features", "silhouette", "points" → *role; false for any other text.
bool ParseCameraRole(const std::string& text, CameraRole* role);

struct CameraEntry {
  std::string name;                // key in "cameras" (also the folder name in out/)
  std::vector<std::string> video;  // segments or image-sequence patterns, relative to the trial dir
  std::string frames;              // frame-times CSV (empty when fps is given instead)
  std::optional<double> fps;       // constant frame rate (Hz) when there is no frames CSV
  std::optional<double> t0_s;      // time of frame 0 with fps (s)
  std::string model;               // camera model JSON (written as null when empty)
  CameraRole role = CameraRole::kBeacon;
  std::string target;                                      // target model JSON (features, silhouette)
  std::string seeds;                                       // seeds CSV of rk-extract points (role points)
  std::optional<std::pair<double, double>> boresight_deg;  // fixed camera (az, el) when no turret log
};

// A camera whose frame times and model sit in its own folder under the names of trial/layout.h
// (<name>/frames.csv, <name>/camera.json), as rk-sim and rk-capture write them.
CameraEntry CameraInItsFolder(const std::string& name, CameraRole role, std::vector<std::string> video);

struct RadarEntry {
  std::string plots;  // radar plots CSV
  std::string nav;    // platform navigation CSV
};

// One station of a multi-station trial (docs/rk-run.md "Several stations"): what a single-station manifest
// says at its top level (station position and pointing model, cameras, logs), under "stations": {NAME: {...}}.
// Paths are still relative to the trial folder.
struct StationEntry {
  std::string name;                  // key in "stations" (letters, digits, '_', '-'; the folder in out/)
  io::Json station;                  // {"lat_deg","lon_deg","h_m"} (required in a multi-station manifest)
  std::string pointing;              // station.pointing, "" = none
  std::vector<CameraEntry> cameras;  // read: in name order
  std::string turret, range, theodolite;  // empty = none
  // The unit name of one of its cameras: "<station>/<camera>", or the camera's name for the single station
  // of a single-station manifest (name empty).
  std::string Unit(const CameraEntry& camera) const { return name.empty() ? camera.name : name + "/" + camera.name; }
};

struct Manifest {
  // Where it was read from (empty for a manifest being written).
  std::string manifest_path;  // absolute path of trial.json
  std::string dir;            // absolute trial directory (the manifest's folder)
  std::string text;           // the file's text (its SHA-256 is part of rk-run's report)
  io::Json json;              // the whole manifest, extra keys included
  io::JsonPositions positions;

  std::string name;  // "name", else the folder's name
  std::string epoch_utc;
  // The stations: a single-station manifest (its station, cameras and logs at the top level) has exactly one,
  // with an empty name; a multi-station one (docs/rk-run.md "Several stations": "stations" {NAME: {...}}) two or
  // more, in name order. Only the reader and ManifestToJson know the two JSON forms.
  std::vector<StationEntry> stations;
  io::Json origin;  // multi-station: the trajectory's ENU origin {"lat_deg","lon_deg","h_m"}, null = the first station
  std::optional<RadarEntry> radar;
  bool multi_station() const { return !stations.empty() && !stations.front().name.empty(); }
  // The one station of a single-station manifest (a writer's Manifest gets it on first use; a multi-station
  // manifest is a ProcessingError).
  StationEntry& Single();
  const StationEntry& Single() const;

  io::Json steps = io::Json::object();  // rk-run's "steps" object (the reader checks only that it is one)
  // Written: further top-level keys, e.g. {"sim": {...}} or {"capture": {...}} (read: see `json`).
  io::Json extra = io::Json::object();

  // Every path the manifest names (trial files), relative to dir, in a stable order.
  std::vector<std::string> AllPaths() const;
};

// Reads and checks trial.json. `path` may name the manifest or the trial directory (then
// DIR/trial.json). Throws IoError (unreadable), DataError "trial.json:LINE:COL: field: what".
Manifest LoadManifest(const std::string& path);
// The same from text (tests); `manifest_path` names the file in messages and gives the trial dir.
Manifest ParseManifest(const std::string& text, const std::string& manifest_path);

// DataError at the value (or, at_key, the key) of JSON pointer `pointer` of a manifest read from `file`:
// "file:LINE:COL: dotted.pointer: what".
[[noreturn]] void FailAt(const std::string& file, const io::JsonPositions& positions, const std::string& pointer,
                         const std::string& what, bool at_key = false);

// The manifest as written: name, epoch_utc, station, cameras (video always a list; model null when empty;
// frames, target, fps, t0_s, boresight_deg only when set), turret/range/theodolite (path or null), radar
// (object or null), steps, then the keys of `extra`. A multi-station manifest has "origin" and "stations"
// (each station's station, cameras and logs in the same form) instead of station, cameras and the logs.
io::Json ManifestToJson(const Manifest& manifest);
// ManifestToJson written atomically (io::WriteJson) to `path`.
void WriteManifest(const std::string& path, const Manifest& manifest);

}  // namespace rk::trial

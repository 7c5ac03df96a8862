// Station configuration (SPEC.md §6), the input of rk-capture:
//   {"cameras": [{"name": "az", "source": "0", "fps": 20, "model": "az_camera.json"}],
//    "rangefinder": {"port": "/dev/ttyUSB0", "baud": 115200, "parity": "none", "data_bits": 8,
//                    "stop_bits": 1, "mode": "tracking", "rate_hz": 5},
//    "turret": {"port": "/dev/ttyUSB1", "baud": 9600, ..., "rate_hz": 50},
//    "segment_s": 10}
// Any device block may be absent. Paths in the file (models, targets, "file:" sources, serial ports
// given as relative paths) are relative to the file. Extra keys of rangekit (docs/rk-capture.md) are
// optional; unknown keys are reported as warnings and kept (the whole file is copied into the
// manifest).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "capture/camera_source.h"
#include "capture/dimetix.h"
#include "capture/ptu.h"
#include "io/json_util.h"

namespace rk::capture {

struct CameraConfig {
  std::string name;              // folder in the trial: letters, digits, '_' and '-'
  std::string source_text;       // "source" as written
  CameraSourceOptions source;    // with file: / cvfile: paths resolved
  std::string model_path;        // camera model JSON (resolved), copied to <name>/camera.json; may be empty
  std::string role = "beacon";   // beacon, features, silhouette
  std::string target_path;       // target model JSON (resolved), copied to <name>/target.json; may be empty
  std::string format = "y4m";    // video form: y4m or pgm
  int queue_frames = 0;          // frames waiting for the disk, at most one second's worth (0 = that)
};

struct StationConfig {
  std::string path;              // the file read
  io::Json json;                 // the file as given
  std::string name;              // trial name ("" = the output folder's name)
  io::Json station;              // {"lat_deg", "lon_deg", "h_m"} (zeros if not given)
  // station.pointing (resolved): the turret pointing model (SPEC.md §3.1), copied to the trial's pointing.json
  // and named in its manifest as station.pointing; "" = none.
  std::string pointing_path;
  io::Json steps = io::Json::object();
  std::vector<CameraConfig> cameras;
  std::optional<DimetixOptions> rangefinder;
  std::optional<PtuOptions> turret;
  double segment_s = 10.0;       // video segment length (s)
  double sync_s = 1.0;           // fdatasync period of every file (s), ≤ 1
  double manifest_s = 1.0;       // manifest rewrite period while recording (s)
  double min_free_mb = 512.0;    // video frames are dropped (gap) when less space is left (MB)
  int realtime_priority = 10;    // SCHED_FIFO priority of the stamping threads (0 = normal scheduling)
  std::vector<std::string> warnings;  // unknown keys and other things worth telling
};

// Reads and validates; DataError("station.json: rangefinder: ...") for a bad value, IoError for a
// file that cannot be read (the config or a model it names).
StationConfig LoadStationConfig(const std::string& path);
StationConfig StationConfigFromJson(const io::Json& j, const std::string& path);

}  // namespace rk::capture

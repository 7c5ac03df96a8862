// Writes a complete synthetic beacon trial directory (SPEC.md §6) from a
// BeaconSimulator: manifest, camera model, frame times, lossless video, turret
// and range logs, and the truth files (docs/rk-sim.md).
//
// Atomic: everything is written into a temporary sibling folder
// "<parent>/.<name>.XXXXXX" which is renamed onto the output path at the end;
// a failed run leaves nothing behind. An existing non-empty output folder is
// refused (UsageError) unless `force`, in which case it is replaced as a whole.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "io/json_util.h"
#include "io/options.h"
#include "sim/beacon_scenario.h"
#include "trial/manifest.h"

namespace rk::sim {

struct TrialWriteOptions {
  std::string out_dir;                          // trial folder to create
  std::string format = "mkv";                   // "mkv" (az/video.mkv, FFV1) or "png" (az/%06d.png)
  bool force = false;                           // replace an existing non-empty out_dir
  std::string name;                             // manifest name; default: the folder's name
  std::string epoch_utc = "2026-01-01T00:00:00Z";  // trial epoch (ISO-8601 UTC)
  double station_lat_deg = 0.0, station_lon_deg = 0.0, station_h_m = 0.0;
  std::function<void(std::size_t done, std::size_t total)> progress;  // optional, called per frame

  // --force, --format of rk-sim beacon (--out, --name, --epoch-utc are registered by the app).
  static const io::OptionTable<TrialWriteOptions>& Table();
  bool Check(std::string* why) const;
};

struct TrialSummary {
  std::int64_t frames = 0;
  std::int64_t visible_frames = 0;
  std::int64_t turret_rows = 0;
  std::int64_t range_rows = 0;
  std::int64_t range_error_rows = 0;
  double min_range_m = 0, max_range_m = 0;
  double max_elevation_deg = 0;
  double min_distractor_dist_px = -1;  // < 0: no distractors
  io::Json ToJson() const;
};

// Throws UsageError (bad options / refusing to replace), IoError (cannot write).
TrialSummary WriteBeaconTrial(const BeaconSimulator& sim, const TrialWriteOptions& opt);

// One station's files of a trial, written under `trial_root`/`station`/ (the trial root itself when `station`
// is empty): <camera>/camera.json, frames.csv and the video (opt.format), turret.csv, range.csv (only with
// `range`), truth/ (beacon.csv, target.csv: the target seen from this station, turret.csv, range.csv, and
// pointing.json when the station has pointing errors). Counts in `sum`. Returns the station's manifest entry
// (name `station`, position from opt.station_*, paths relative to the trial root). Used by WriteBeaconTrial
// and by rk-sim multistation (one per station). Throws IoError.
trial::StationEntry WriteBeaconStation(const BeaconSimulator& sim, const TrialWriteOptions& opt,
                                       const std::string& trial_root, const std::string& station, bool range,
                                       TrialSummary* sum);

}  // namespace rk::sim

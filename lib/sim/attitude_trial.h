// Writes a complete synthetic attitude trial directory (SPEC.md §6) from an AttitudeSimulator:
//   trial.json            manifest: camera "att" (role features, target target.json), turret
//   target.json           target model {"points": {"<id>": [x, y, z]}} (body m)
//   turret.csv            recorded turret log t_s,az_deg,el_deg (quantised)
//   att/camera.json       attitude camera model
//   att/frames.csv        frame,t_s
//   att/video.mkv         FFV1 lossless video (or att/%06d.png with format "png")
//   truth/pose.csv        frame,t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,range_m,
//                         boresight_az_deg,boresight_el_deg   (true pose and true boresight)
//   truth/points.csv      frame,t_s,id,x_px,y_px,status,radius_px  (projected marker centres at
//                         the true boresight; status ok, or lost with empty x/y when hidden)
//   truth/turret.csv      the true boresight at the turret log times
// Atomic (sim/trial_folder.h): a failed run leaves nothing behind; an existing non-empty folder
// is refused unless force.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "io/json_util.h"
#include "io/options.h"
#include "sim/attitude_scenario.h"

namespace rk::sim {

struct AttitudeTrialWriteOptions {
  std::string out_dir;
  std::string format = "mkv";  // "mkv" | "png"
  bool force = false;
  bool video = true;           // false: truth, logs and models only (no images)
  std::string name;            // manifest name; default: the folder's name
  std::string epoch_utc = "2026-01-01T00:00:00Z";
  std::function<void(std::size_t done, std::size_t total)> progress;

  // --force, --format (--out, --no-video, --name, --epoch-utc are registered by the app).
  static const io::OptionTable<AttitudeTrialWriteOptions>& Table();
  bool Check(std::string* why) const;
};

struct AttitudeTrialSummary {
  std::int64_t frames = 0;
  std::int64_t turret_rows = 0;
  std::int64_t hidden_marker_rows = 0;
  double min_range_m = 0, max_range_m = 0;
  double min_marker_radius_px = 0, max_marker_radius_px = 0;
  double min_separation_px = 0;
  double yaw_span_deg = 0, pitch_span_deg = 0, roll_span_deg = 0;  // max − min over the run
  io::Json ToJson() const;
};

AttitudeTrialSummary WriteAttitudeTrial(const AttitudeSimulator& sim, const AttitudeTrialWriteOptions& opt);

}  // namespace rk::sim

// Writes a synthetic single-station theodolite trial (SPEC.md §6) from a TheodoliteSimulator
// (rk-sim theodolite, docs/rk-sim.md):
//   trial.json                manifest: camera "theo" with role silhouette, "theodolite": "theodolite.csv"
//   target.json               {"length_m", "diameter_m", "nose_length_m"} (rk-attitude cylinder --target)
//   theodolite.csv            t_s,az_deg,el_deg (recorded: bias, noise, encoder step as configured)
//   points.csv                frame,t_s,id,x_px,y_px: nose, tail1, tail2 per frame (exact projection, then the
//                             configured point noise and 1-pixel quantisation)
//   theo/camera.json, theo/frames.csv, and with images: theo/video.mkv (FFV1) or theo/%06d.png
//   truth/axis.csv            frame,t_s,yaw_deg,pitch_deg,alt_yaw_deg,alt_pitch_deg,range_nose_m,range_tail1_m,
//                             range_tail2_m,e_m,n_m,u_m (tail centre),view_angle_deg,image_length_px,
//                             boresight_az_deg,boresight_el_deg
//   truth/points.csv          exact projections (same columns as points.csv)
//   truth/theodolite.csv      true boresight at the log times
// Atomic (sim::TrialFolder): a failed run leaves nothing behind.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "io/json_util.h"
#include "io/options.h"
#include "sim/theodolite_render.h"
#include "sim/theodolite_scene.h"

namespace rk::sim {

struct TheodoliteWriteOptions {
  std::string out_dir;
  bool force = false;
  std::string images = "none";  // "none", "png" (theo/%06d.png) or "mkv" (theo/video.mkv, FFV1)
  SilhouetteRenderOptions render;
  std::string name;                                // manifest name; default: the folder's name
  std::string epoch_utc = "2026-01-01T00:00:00Z";
  std::function<void(std::size_t done, std::size_t total)> progress;
  // --force, --images (the render options have their own table, last in --help).
  static const io::OptionTable<TheodoliteWriteOptions>& Table();
  bool Check(std::string* why) const;
};

struct TheodoliteTrialSummary {
  std::int64_t frames = 0;
  std::int64_t theodolite_rows = 0;
  double min_view_angle_deg = 0, max_view_angle_deg = 0;
  double min_image_length_px = 0, max_image_length_px = 0;
  double bias_az_arcsec = 0, bias_el_arcsec = 0;
  io::Json ToJson() const;
};

TheodoliteTrialSummary WriteTheodoliteTrial(const TheodoliteSimulator& sim, const TheodoliteWriteOptions& opt);

}  // namespace rk::sim

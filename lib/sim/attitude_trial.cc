// Attitude trial folder; layout in attitude_trial.h.
#include "sim/attitude_trial.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "camera/camera_model.h"
#include "formats/image_points.h"
#include "formats/turret_log.h"
#include "geo/angles.h"
#include "io/utc_time.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "sim/trial_folder.h"
#include "trial/layout.h"
#include "trial/manifest.h"
#include "video/frame_sink.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace {

constexpr const char* kAttitudeCamera = "att";  // the camera's name in the manifest and its folder


}  // namespace

const io::OptionTable<AttitudeTrialWriteOptions>& AttitudeTrialWriteOptions::Table() {
  static const io::OptionTable<AttitudeTrialWriteOptions> table =
      io::OptionTable<AttitudeTrialWriteOptions>()
          .Flag("--force", &AttitudeTrialWriteOptions::force, "Replace an existing non-empty --out folder")
          .Choice("--format", &AttitudeTrialWriteOptions::format, {{"mkv", "mkv"}, {"png", "png"}},
                  "Video: mkv (att/video.mkv, FFV1) or png (att/%06d.png)");
  return table;
}

bool AttitudeTrialWriteOptions::Check(std::string* why) const {
  if (out_dir.empty() || out_dir == "-") {
    *why = "--out must name a folder";
    return false;
  }
  if (format != "mkv" && format != "png") {
    *why = "--format must be 'mkv' or 'png'";
    return false;
  }
  io::UtcTime utc_epoch;
  if (!io::ParseUtcIso(epoch_utc, &utc_epoch, nullptr)) {
    *why = "epoch must be ISO-8601 UTC, e.g. 2026-01-01T00:00:00Z";
    return false;
  }
  return true;
}

io::Json AttitudeTrialSummary::ToJson() const {
  return {{"frames", frames},
          {"turret_rows", turret_rows},
          {"hidden_marker_rows", hidden_marker_rows},
          {"min_range_m", min_range_m},
          {"max_range_m", max_range_m},
          {"min_marker_radius_px", min_marker_radius_px},
          {"max_marker_radius_px", max_marker_radius_px},
          {"min_marker_separation_px", min_separation_px},
          {"yaw_span_deg", yaw_span_deg},
          {"pitch_span_deg", pitch_span_deg},
          {"roll_span_deg", roll_span_deg}};
}

namespace {

// Frame times, truth/pose.csv and truth/points.csv; the frame counts, extremes and attitude spans of `sum`.
void WriteAttitudeTruth(const AttitudeSimulator& sim, const TrialFolder& dir, AttitudeTrialSummary* out) {
  const AttitudeSimOptions& so = sim.options();
  AttitudeTrialSummary& sum = *out;
  io::CsvWriter frames_csv({"frame", "t_s"});
  io::CsvWriter pose_csv({"frame", "t_s", "e_m", "n_m", "u_m", "yaw_deg", "pitch_deg", "roll_deg", "range_m",
                          "boresight_az_deg", "boresight_el_deg"});
  io::CsvWriter points_csv(formats::ImagePointsColumns({"radius_px"}));
  sum.min_range_m = sum.min_marker_radius_px = sum.min_separation_px = std::numeric_limits<double>::infinity();
  // Attitude spans on unwrapped sequences (yaw and roll may wrap).
  double yaw_lo = 1e300, yaw_hi = -1e300, pit_lo = 1e300, pit_hi = -1e300, rol_lo = 1e300, rol_hi = -1e300;
  double yaw_ref = 0, roll_ref = 0;
  for (const AttitudeFrameTruth& f : sim.frames()) {
    frames_csv.Add(f.frame).Add(f.t_s, kTimeDecimals).EndRow();
    const double range = f.p_enu.norm();
    pose_csv.Add(f.frame)
        .Add(f.t_s, kTimeDecimals)
        .Add(f.p_enu.x(), kMetreDecimals)
        .Add(f.p_enu.y(), kMetreDecimals)
        .Add(f.p_enu.z(), kMetreDecimals)
        .Add(geo::RadToDeg(f.attitude.yaw_rad), kAngleDecimals)
        .Add(geo::RadToDeg(f.attitude.pitch_rad), kAngleDecimals)
        .Add(geo::RadToDeg(f.attitude.roll_rad), kAngleDecimals)
        .Add(range, kMetreDecimals)
        .Add(geo::RadToDeg(f.boresight.az_rad), kAngleDecimals)
        .Add(geo::RadToDeg(f.boresight.el_rad), kAngleDecimals)
        .EndRow();
    for (std::size_t i = 0; i < so.marker_ids.size(); ++i) {
      points_csv.Add(f.frame).Add(f.t_s, kTimeDecimals).Add(so.marker_ids[i]);
      if (f.visible[i]) {
        points_csv.Add(f.marker_px[i].x(), kPixelDecimals).Add(f.marker_px[i].y(), kPixelDecimals).Add("ok");
      } else {
        points_csv.AddEmpty().AddEmpty().Add("lost");
        ++sum.hidden_marker_rows;
      }
      points_csv.Add(f.marker_radius_px[i], 3).EndRow();
      sum.min_marker_radius_px = std::min(sum.min_marker_radius_px, f.marker_radius_px[i]);
      sum.max_marker_radius_px = std::max(sum.max_marker_radius_px, f.marker_radius_px[i]);
    }
    ++sum.frames;
    sum.min_range_m = std::min(sum.min_range_m, range);
    sum.max_range_m = std::max(sum.max_range_m, range);
    if (std::isfinite(f.min_separation_px)) sum.min_separation_px = std::min(sum.min_separation_px, f.min_separation_px);
    if (f.frame == 0) {
      yaw_ref = f.attitude.yaw_rad;
      roll_ref = f.attitude.roll_rad;
    }
    yaw_ref += geo::AngleDiff(f.attitude.yaw_rad, yaw_ref);
    roll_ref += geo::AngleDiff(f.attitude.roll_rad, roll_ref);
    yaw_lo = std::min(yaw_lo, yaw_ref), yaw_hi = std::max(yaw_hi, yaw_ref);
    rol_lo = std::min(rol_lo, roll_ref), rol_hi = std::max(rol_hi, roll_ref);
    pit_lo = std::min(pit_lo, f.attitude.pitch_rad), pit_hi = std::max(pit_hi, f.attitude.pitch_rad);
  }
  if (!std::isfinite(sum.min_separation_px)) sum.min_separation_px = 0;
  sum.yaw_span_deg = geo::RadToDeg(yaw_hi - yaw_lo);
  sum.pitch_span_deg = geo::RadToDeg(pit_hi - pit_lo);
  sum.roll_span_deg = geo::RadToDeg(rol_hi - rol_lo);
  frames_csv.Write(dir.Path(trial::CameraFile(kAttitudeCamera, trial::kFramesFile)));
  pose_csv.Write(dir.Path("truth/pose.csv"));
  points_csv.Write(dir.Path("truth/points.csv"));
}

// The turret log, recorded (trial root) and true (truth/); its row count in `sum`.
void WriteTurretLogs(const AttitudeSimulator& sim, const TrialFolder& dir, AttitudeTrialSummary* out) {
  io::CsvWriter turret_csv(formats::TurretLogColumns()), turret_truth(formats::TurretLogColumns());
  for (const AttitudeTurretSample& s : sim.TurretLog()) {
    turret_csv.Add(s.t_s, kTimeDecimals).Add(geo::RadToDeg(s.az_rad), kAngleDecimals).Add(geo::RadToDeg(s.el_rad), kAngleDecimals).EndRow();
    turret_truth.Add(s.t_s, kTimeDecimals)
        .Add(geo::RadToDeg(geo::WrapTwoPi(s.true_az_rad)), kAngleDecimals)
        .Add(geo::RadToDeg(s.true_el_rad), kAngleDecimals)
        .EndRow();
    ++out->turret_rows;
  }
  turret_csv.Write(dir.Path(trial::kTurretFile));
  turret_truth.Write(dir.Path("truth/turret.csv"));
}

void WriteAttitudeManifest(const AttitudeSimulator& sim, const AttitudeTrialWriteOptions& opt, const TrialFolder& dir,
                           const std::string& video_rel, const AttitudeTrialSummary& sum) {
  const AttitudeSimOptions& so = sim.options();
  trial::Manifest m;
  m.name = opt.name.empty() ? dir.stem() : opt.name;
  m.epoch_utc = opt.epoch_utc;
  m.Single().station = {{"lat_deg", 0.0}, {"lon_deg", 0.0}, {"h_m", 0.0}};
  // Without video there is nothing for rk-extract to read: the camera is left out of the manifest
  // (SPEC.md §6 wants a non-empty video list), the model and frame times are still written.
  if (opt.video) {
    trial::CameraEntry att = trial::CameraInItsFolder(kAttitudeCamera, trial::CameraRole::kFeatures, {video_rel});
    att.target = trial::kTargetModelFile;
    m.Single().cameras = {att};
  }
  m.Single().turret = trial::kTurretFile;
  io::Json simj;
  simj["generator"] = "rk-sim attitude";
  simj["seed"] = so.seed;
  simj["format"] = opt.video ? opt.format : "none";
  simj["options"] = AttitudeSimOptionsToJson(so);
  simj["truth"] = {{"pose", "truth/pose.csv"}, {"points", "truth/points.csv"}, {"turret", "truth/turret.csv"}};
  simj["summary"] = sum.ToJson();
  m.extra["sim"] = simj;
  trial::WriteManifest(dir.Path(trial::kManifestFile), m);
}

}  // namespace

AttitudeTrialSummary WriteAttitudeTrial(const AttitudeSimulator& sim, const AttitudeTrialWriteOptions& opt) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  const AttitudeSimOptions& so = sim.options();
  TrialFolder dir(opt.out_dir, opt.force);
  io::MakeDirectories(dir.Path(kAttitudeCamera));
  io::MakeDirectories(dir.Path("truth"));

  AttitudeTrialSummary sum;
  io::WriteJson(dir.Path(trial::CameraFile(kAttitudeCamera, trial::kCameraModelFile)),
                camera::CameraModelToJson(so.camera));
  {
    io::Json pts = io::Json::object();
    for (std::size_t i = 0; i < so.marker_ids.size(); ++i) {
      pts[so.marker_ids[i]] = {so.markers_body[i].x(), so.markers_body[i].y(), so.markers_body[i].z()};
    }
    io::WriteJson(dir.Path(trial::kTargetModelFile),
                  io::Json{{"points", pts}, {"marker_radius_m", so.marker_radius_m}});
  }
  WriteAttitudeTruth(sim, dir, &sum);
  WriteTurretLogs(sim, dir, &sum);

  const std::string video_rel = trial::CameraFile(kAttitudeCamera, opt.format == "mkv" ? "video.mkv" : "%06d.png");
  if (opt.video) {
    video::FrameSink sink(dir.Path(video_rel), so.camera.width_px, so.camera.height_px, so.sensor.bit_depth, so.fps);
    for (std::size_t k = 0; k < sim.frame_count(); ++k) {
      sink.Write(sim.RenderFrame(k));
      if (opt.progress) opt.progress(k + 1, sim.frame_count());
    }
    sink.Close();
  }

  WriteAttitudeManifest(sim, opt, dir, video_rel, sum);
  dir.Commit();
  return sum;
}

}  // namespace rk::sim

#include "sim/beacon_trial.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "camera/camera_model.h"
#include "camera/pointing_model.h"
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
namespace fs = std::filesystem;
namespace {

constexpr const char* kBeaconCamera = "az";  // the camera's name in the manifest and its folder


}  // namespace

const io::OptionTable<TrialWriteOptions>& TrialWriteOptions::Table() {
  static const io::OptionTable<TrialWriteOptions> table =
      io::OptionTable<TrialWriteOptions>()
          .Flag("--force", &TrialWriteOptions::force, "Replace an existing non-empty --out folder")
          .Choice("--format", &TrialWriteOptions::format, {{"mkv", "mkv"}, {"png", "png"}},
                  "Video: mkv (az/video.mkv, FFV1) or png (az/%06d.png)");
  return table;
}

bool TrialWriteOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (out_dir.empty() || out_dir == "-") return fail("--out must name a folder");
  if (format != "mkv" && format != "png") return fail("format must be 'mkv' or 'png'");
  io::UtcTime utc_epoch;
  if (!io::ParseUtcIso(epoch_utc, &utc_epoch, nullptr)) return fail("epoch must be ISO-8601 UTC, e.g. 2026-01-01T00:00:00Z");
  if (!(std::abs(station_lat_deg) <= 90 && std::abs(station_lon_deg) <= 180 && std::isfinite(station_h_m))) {
    return fail("station latitude/longitude out of range");
  }
  return true;
}

io::Json TrialSummary::ToJson() const {
  io::Json j;
  j["frames"] = frames;
  j["visible_frames"] = visible_frames;
  j["turret_rows"] = turret_rows;
  j["range_rows"] = range_rows;
  j["range_error_rows"] = range_error_rows;
  j["min_range_m"] = min_range_m;
  j["max_range_m"] = max_range_m;
  j["max_elevation_deg"] = max_elevation_deg;
  if (min_distractor_dist_px >= 0) j["min_distractor_dist_px"] = min_distractor_dist_px;
  return j;
}

namespace {

// Frame times (camera folder) and truth/beacon.csv, truth/target.csv; the frame counts and extremes of `sum`.
void WriteFrameTruth(const BeaconSimulator& sim, const fs::path& root, TrialSummary* out) {
  TrialSummary& sum = *out;
  io::CsvWriter frames_csv({"frame", "t_s"});
  io::CsvWriter beacon_csv({"frame", "t_s", "x_px", "y_px", "visible", "distractor_min_dist_px"});
  io::CsvWriter target_csv(
      {"frame", "t_s", "az_deg", "el_deg", "range_m", "e_m", "n_m", "u_m", "boresight_az_deg", "boresight_el_deg"});
  sum.min_range_m = std::numeric_limits<double>::infinity();
  sum.max_range_m = 0;
  sum.max_elevation_deg = -90;
  // A camera with a latency stamps its frames that much before their mid-exposure time (SPEC.md §3).
  const double latency_s = sim.options().camera.time_offset_s;
  for (const FrameTruth& f : sim.frames()) {
    frames_csv.Add(f.frame).Add(f.t_s - latency_s, kTimeDecimals).EndRow();
    beacon_csv.Add(f.frame).Add(f.t_s - latency_s, kTimeDecimals);
    if (f.visible) {
      beacon_csv.Add(f.centre_px.x(), kPixelDecimals).Add(f.centre_px.y(), kPixelDecimals).Add(1);
    } else {
      beacon_csv.AddEmpty().AddEmpty().Add(0);
    }
    if (f.distractor_min_dist_px >= 0) {
      beacon_csv.Add(f.distractor_min_dist_px, kPixelDecimals);
      sum.min_distractor_dist_px = sum.min_distractor_dist_px < 0
                                       ? f.distractor_min_dist_px
                                       : std::min(sum.min_distractor_dist_px, f.distractor_min_dist_px);
    } else {
      beacon_csv.AddEmpty();
    }
    beacon_csv.EndRow();
    target_csv.Add(f.frame)
        .Add(f.t_s, kTimeDecimals)
        .Add(geo::RadToDeg(f.az_rad), kAngleDecimals)
        .Add(geo::RadToDeg(f.el_rad), kAngleDecimals)
        .Add(f.range_m, kMetreDecimals)
        .Add(f.p_enu.x(), kMetreDecimals)
        .Add(f.p_enu.y(), kMetreDecimals)
        .Add(f.p_enu.z(), kMetreDecimals)
        .Add(geo::RadToDeg(f.boresight_az_rad), kAngleDecimals)
        .Add(geo::RadToDeg(f.boresight_el_rad), kAngleDecimals)
        .EndRow();
    ++sum.frames;
    if (f.visible) ++sum.visible_frames;
    sum.min_range_m = std::min(sum.min_range_m, f.range_m);
    sum.max_range_m = std::max(sum.max_range_m, f.range_m);
    sum.max_elevation_deg = std::max(sum.max_elevation_deg, geo::RadToDeg(f.el_rad));
  }
  frames_csv.Write((root / trial::CameraFile(kBeaconCamera, trial::kFramesFile)).string());
  beacon_csv.Write((root / "truth" / "beacon.csv").string());
  target_csv.Write((root / "truth" / "target.csv").string());
}

// Turret and range logs (the range log only with `range`), recorded (trial root) and true (truth/); their row
// counts in `sum`.
void WriteLogs(const BeaconSimulator& sim, const fs::path& root, bool range, TrialSummary* out) {
  TrialSummary& sum = *out;
  io::CsvWriter turret_csv(formats::TurretLogColumns()), turret_truth(formats::TurretLogColumns());
  for (const TurretSample& s : sim.TurretLog()) {
    turret_csv.Add(s.t_s, kTimeDecimals).Add(geo::RadToDeg(s.az_rad), kAngleDecimals).Add(geo::RadToDeg(s.el_rad), kAngleDecimals).EndRow();
    turret_truth.Add(s.t_s, kTimeDecimals)
        .Add(geo::RadToDeg(s.true_az_rad), kAngleDecimals)
        .Add(geo::RadToDeg(s.true_el_rad), kAngleDecimals)
        .EndRow();
    ++sum.turret_rows;
  }
  turret_csv.Write((root / trial::kTurretFile).string());
  turret_truth.Write((root / "truth" / "turret.csv").string());
  if (!range) return;
  io::CsvWriter range_csv({"t_s", "range_m", "status"}), range_truth({"t_s", "range_m"});
  for (const RangeSample& s : sim.RangeLog()) {
    range_csv.Add(s.t_s, kTimeDecimals);
    if (s.status == 0) {
      range_csv.Add(s.range_m, kMetreDecimals);
    } else {
      range_csv.AddEmpty();
      ++sum.range_error_rows;
    }
    range_csv.Add(s.status).EndRow();
    range_truth.Add(s.t_s, kTimeDecimals).Add(s.true_range_m, kMetreDecimals).EndRow();
    ++sum.range_rows;
  }
  range_csv.Write((root / trial::kRangeFile).string());
  range_truth.Write((root / "truth" / "range.csv").string());
}

// The rendered frames; returns the video's path in the trial folder.
std::string WriteVideo(const BeaconSimulator& sim, const TrialWriteOptions& opt, const fs::path& root) {
  const BeaconSimOptions& so = sim.options();
  const std::string video_rel = trial::CameraFile(kBeaconCamera, opt.format == "mkv" ? "video.mkv" : "%06d.png");
  {
    video::FrameSink sink((root / video_rel).string(), so.camera.width_px, so.camera.height_px, so.sensor.bit_depth,
                          so.fps);
    for (std::size_t k = 0; k < sim.frame_count(); ++k) {
      sink.Write(sim.RenderFrame(k));
      if (opt.progress) opt.progress(k + 1, sim.frame_count());
    }
    sink.Close();
  }
  return video_rel;
}

void WriteBeaconManifest(const BeaconSimulator& sim, const TrialWriteOptions& opt, const fs::path& root,
                         const std::string& stem, trial::StationEntry station, const TrialSummary& sum) {
  const BeaconSimOptions& so = sim.options();
  trial::Manifest m;
  m.name = opt.name.empty() ? stem : opt.name;
  m.epoch_utc = opt.epoch_utc;
  m.stations = {std::move(station)};
  io::Json simj;
  simj["generator"] = "rk-sim beacon";
  simj["seed"] = so.seed;
  simj["format"] = opt.format;
  simj["options"] = BeaconSimOptionsToJson(so);
  simj["truth"] = {{"beacon", "truth/beacon.csv"},
                   {"target", "truth/target.csv"},
                   {"turret", "truth/turret.csv"},
                   {"range", "truth/range.csv"}};
  if (!so.station_pointing.IsZero()) simj["truth"]["pointing"] = "truth/pointing.json";
  simj["summary"] = sum.ToJson();
  m.extra["sim"] = simj;
  trial::WriteManifest((root / trial::kManifestFile).string(), m);
}

}  // namespace

trial::StationEntry WriteBeaconStation(const BeaconSimulator& sim, const TrialWriteOptions& opt,
                                       const std::string& trial_root, const std::string& station, bool range,
                                       TrialSummary* sum) {
  const std::string prefix = station.empty() ? "" : station + "/";
  const fs::path root = fs::path(trial_root) / prefix;
  io::MakeDirectories((root / kBeaconCamera).string());
  io::MakeDirectories((root / "truth").string());
  // Camera model and frame times.
  io::WriteJson((root / trial::CameraFile(kBeaconCamera, trial::kCameraModelFile)).string(),
                camera::CameraModelToJson(sim.options().camera));
  WriteFrameTruth(sim, root, sum);
  WriteLogs(sim, root, range, sum);
  if (!sim.options().station_pointing.IsZero()) {
    // The station's true pointing model, as rk-calibrate pointing would write it (without σ).
    camera::PointingModel truth;
    truth.terms = sim.options().station_pointing;
    io::Json j = camera::PointingModelToJson(truth);
    j.erase("sigma");
    io::WriteJson((root / "truth" / "pointing.json").string(), j);
  }
  const std::string video_rel = WriteVideo(sim, opt, root);

  trial::StationEntry e;
  e.name = station;
  e.station = {{"lat_deg", opt.station_lat_deg}, {"lon_deg", opt.station_lon_deg}, {"h_m", opt.station_h_m}};
  trial::CameraEntry cam = trial::CameraInItsFolder(kBeaconCamera, trial::CameraRole::kBeacon, {prefix + video_rel});
  cam.frames = prefix + cam.frames;
  cam.model = prefix + cam.model;
  e.cameras = {cam};
  e.turret = prefix + trial::kTurretFile;
  if (range) e.range = prefix + trial::kRangeFile;
  return e;
}

TrialSummary WriteBeaconTrial(const BeaconSimulator& sim, const TrialWriteOptions& opt) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);

  TrialFolder folder(opt.out_dir, opt.force);
  const std::string stem = fs::path(folder.out()).filename().string();
  const fs::path root(folder.Path(""));
  TrialSummary sum;
  trial::StationEntry station = WriteBeaconStation(sim, opt, root.string(), "", true, &sum);
  WriteBeaconManifest(sim, opt, root, stem, std::move(station), sum);
  folder.Commit();
  return sum;
}

}  // namespace rk::sim

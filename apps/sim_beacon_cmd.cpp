// rk-sim beacon: beacon-camera tracking trial (seed 001): video, turret, range, truth.
// Thin edge: CLI11 options → rk::sim::BeaconSimOptions → rk::sim::WriteBeaconTrial; docs/rk-sim.md.
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "camera/camera_model.h"
#include "geo/angles.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "sim/beacon_scenario.h"
#include "sim/beacon_trial.h"
#include "sim_commands.h"

namespace rk::app {
namespace {

// Options as given on the command line: the library's (bound by their tables) and the values the
// app resolves itself (camera, trajectory defaults, optional geometry, intervals).
struct BeaconCli {
  rk::sim::TrialWriteOptions w;
  rk::sim::BeaconSimOptions o;
  std::string preset = "default", trajectory = "default", camera_path;
  int width = 0, height = 0;
  double range_m = NAN, speed_mps = NAN, azimuth_deg = NAN, elevation_deg = NAN, turn_rate_deg_s = NAN;
  bool range_given = false;  // --range-m on the command line (NaN there is refused)
  std::vector<std::string> occlusions, servo_holds;
  // Station errors (docs/rk-sim.md "Station errors"): the turret's true pointing model and the camera's latency.
  double az_offset_deg = 0, tilt_north_deg = 0, tilt_east_deg = 0, el_axis_tilt_deg = 0, time_offset_s = 0;
};

void ResolveCamera(const BeaconCli& c, rk::sim::BeaconSimOptions* o) {
  if (!c.camera_path.empty()) {
    o->camera = rk::camera::LoadCameraModel(c.camera_path);
    o->camera_preset = "file";
  } else {
    rk::sim::CameraPreset(c.preset, &o->camera);
    o->camera_preset = c.preset;
  }
  if (c.width > 0 || c.height > 0) {
    if (c.width > 0) o->camera.width_px = c.width;
    if (c.height > 0) o->camera.height_px = c.height;
    o->camera.principal_point_px = {0.5 * (o->camera.width_px - 1), 0.5 * (o->camera.height_px - 1)};
    o->camera_preset += "-resized";
  }
}

// The trajectory kind's defaults, then the optional geometry given on the command line; the
// trajectory's table options (--max-el-deg) are kept.
void ResolveTrajectory(const BeaconCli& c, rk::sim::BeaconSimOptions* o) {
  using rk::geo::DegToRad;
  rk::sim::TrajectoryKind kind;
  rk::sim::ParseTrajectoryKind(c.trajectory, &kind);
  if (c.range_given && !std::isfinite(c.range_m)) throw rk::UsageError("--range-m must be finite");
  const double max_elevation_deg = o->trajectory.max_elevation_deg;
  o->trajectory = rk::sim::DefaultTrajectoryOptions(kind, c.range_m);  // range_m NaN: trajectory default
  o->trajectory.max_elevation_deg = max_elevation_deg;
  if (!std::isnan(c.speed_mps)) o->trajectory.speed_mps = c.speed_mps;
  if (!std::isnan(c.azimuth_deg)) o->trajectory.azimuth_rad = DegToRad(c.azimuth_deg);
  if (!std::isnan(c.elevation_deg)) o->trajectory.elevation_rad = DegToRad(c.elevation_deg);
  if (!std::isnan(c.turn_rate_deg_s)) o->trajectory.turn_rate_rad_s = DegToRad(c.turn_rate_deg_s);
}

std::vector<rk::sim::OcclusionInterval> ParseIntervals(const std::vector<std::string>& texts, const std::string& flag) {
  std::vector<rk::sim::OcclusionInterval> out;
  for (const auto& text : texts) {
    rk::sim::OcclusionInterval occ;
    std::string why;
    if (!rk::sim::ParseOcclusion(text, &occ, &why)) throw rk::UsageError(flag + ": " + why);
    out.push_back(occ);
  }
  return out;
}

int RunBeacon(BeaconCli c, const Context& ctx) {
  const auto& common = ctx.common;
  rk::sim::BeaconSimOptions& o = c.o;
  ResolveCamera(c, &o);
  ResolveTrajectory(c, &o);
  o.occlusions = ParseIntervals(c.occlusions, "--occlusion");
  o.servo_holds = ParseIntervals(c.servo_holds, "--servo-hold");
  o.station_pointing = {rk::geo::DegToRad(c.az_offset_deg), rk::geo::DegToRad(c.tilt_north_deg),
                        rk::geo::DegToRad(c.tilt_east_deg), rk::geo::DegToRad(c.el_axis_tilt_deg)};
  if (c.time_offset_s != 0.0) o.camera.time_offset_s = c.time_offset_s;
  std::string why;
  if (!o.Check(&why)) throw rk::UsageError(why);
  if (!c.w.Check(&why)) throw rk::UsageError(why);
  if (!common.report_path.empty()) rk::io::CheckOutputNotInput(common.report_path, {c.camera_path});

  const rk::sim::BeaconSimulator sim(o);
  if (rk::cli::ShowProgress(common)) {
    c.w.progress = [&ctx](std::size_t done, std::size_t total) {
      if (done % 10 == 0 || done == total) {
        std::cerr << "\r" << ctx.tool << ": frame " << done << "/" << total << (done == total ? "\n" : "")
                  << std::flush;
      }
    };
  }
  const rk::sim::TrialSummary sum = rk::sim::WriteBeaconTrial(sim, c.w);
  if (!common.report_path.empty()) {
    rk::io::Json r = rk::cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    if (!c.camera_path.empty()) rk::cli::AddReportInput(&r, "camera", c.camera_path);
    r["subcommand"] = "beacon";
    r["out"] = c.w.out_dir;
    r["options"] = o.ToJson();
    r["summary"] = sum.ToJson();
    rk::cli::WriteReport(common.report_path, r);
  }
  return 0;
}

}  // namespace

Command AddBeaconCommand(CLI::App& parent) {
  CLI::App* beacon = parent.add_subcommand(
      "beacon",
      "Beacon-tracking trial: lamp-cluster target, turret with lag and jitter, 5 Hz range log, truth");
  auto a = std::make_shared<BeaconCli>();
  BeaconCli& c = *a;

  beacon
      ->add_option("--out,-o", c.w.out_dir, "Trial folder to create (refused if it exists and is not empty)")
      ->required();
  rk::cli::AddOptions(beacon, &c.w, rk::sim::TrialWriteOptions::Table());
  beacon->add_option("--name", c.w.name, "Trial name in trial.json (default: the folder name)");
  beacon->add_option("--epoch-utc", c.w.epoch_utc, "Trial epoch, ISO-8601 UTC")->capture_default_str();
  beacon->add_option("--preset", c.preset, "Camera: default (2448x2048, 3.45 um, 50 mm) or small (640x512)")
      ->check(CLI::IsMember({"default", "small"}))
      ->capture_default_str();
  beacon->add_option("--width", c.width, "Image width (px), overrides the preset; principal point stays centred")
      ->check(CLI::Range(32, 100000));
  beacon->add_option("--height", c.height, "Image height (px), overrides the preset")->check(CLI::Range(32, 100000));
  beacon->add_option("--camera", c.camera_path, "Camera model JSON (SPEC.md section 3) instead of a preset")
      ->check(CLI::ExistingFile);
  beacon->add_option("--trajectory", c.trajectory, "Target motion: default, straight, turning, overhead, static")
      ->check(CLI::IsMember({"default", "straight", "turning", "overhead", "static"}))
      ->capture_default_str();
  const auto geometry = [beacon, &c] {
    beacon->add_option("--range-m", c.range_m, "Nominal / closest-approach range (m), 20..10000 (default per trajectory)");
    beacon->add_option("--speed-mps", c.speed_mps, "Target speed (m/s) (default per trajectory, scaled with --range-m)");
    beacon->add_option("--azimuth-deg", c.azimuth_deg, "Nominal azimuth of the target (deg) (default 30)");
    beacon->add_option("--elevation-deg", c.elevation_deg, "Nominal elevation of the target (deg) (default 5)");
  };
  const auto turn_rate = [beacon, &c] {
    beacon->add_option("--turn-rate-deg-s", c.turn_rate_deg_s, "turning: turn rate (deg/s) (default 5.73)");
  };
  const auto intervals = [beacon, &c] {
    beacon->add_option(
        "--occlusion", c.occlusions,
        "Hide the lamps: START_S:DURATION_S after frame 0 (DURATION_S may be short=0.5 or long=5); repeatable");
    beacon->add_option(
        "--servo-hold", c.servo_holds,
        "Stop the turret: START_S:DURATION_S after frame 0, then it catches up (image motion reverses); "
        "repeatable");
  };
  // Hand-registered options go just before the table option they precede in --help.
  rk::cli::AddOptions(beacon, &c.o, rk::sim::BeaconSimOptions::Table(),
                      {{"--max-el-deg", geometry}, {"--seed", turn_rate}, {"--range-noise-mm", intervals}});
  beacon->add_option("--az-offset-deg", c.az_offset_deg,
                     "Station error: true azimuth = logged + this (deg, SPEC.md 3.1); writes truth/pointing.json");
  beacon->add_option("--tilt-north-deg", c.tilt_north_deg, "Station error: azimuth axis leans north (deg), within 10");
  beacon->add_option("--tilt-east-deg", c.tilt_east_deg, "Station error: azimuth axis leans east (deg), within 10");
  beacon->add_option("--el-axis-tilt-deg", c.el_axis_tilt_deg,
                     "Station error: elevation axis tilt, + lowers its right end (deg), within 10");
  beacon->add_option("--time-offset-s", c.time_offset_s,
                     "Camera latency (s): frames.csv stamps = mid-exposure - this; camera.json gets time_offset_s");
  return {beacon, [a, beacon](const Context& ctx) {
            BeaconCli c = *a;
            c.range_given = beacon->count("--range-m") > 0;
            return RunBeacon(std::move(c), ctx);
          }};
}

}  // namespace rk::app

// rk-sim: synthesize trials with ground truth (SPEC.md §1). Subcommands:
//   beacon     beacon-camera tracking trial (seed 001): video, turret, range, truth.
//   posetrack  6-DOF pose measurements with truth at sample and mid-times (seed 000).
// Thin edge: CLI11 options → rk::sim::BeaconSimOptions → rk::sim::WriteBeaconTrial, and
// rk::sim::PoseTrackOptions → rk::sim::WritePoseTrack.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>

#include "camera/camera_model.h"
#include "geo/angles.h"
#include "io/cli.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "sim/beacon_scenario.h"
#include "sim/beacon_trial.h"
#include "sim/posetrack.h"

namespace {

constexpr const char* kTool = "rk-sim";

// rk-sim posetrack: options as given on the command line (NaN = scenario default).
struct PosetrackCli {
  rk::sim::PoseTrackWriteOptions w;
  std::string scenario = "turntable";
  double duration_s = NAN, fps = 20, t0_s = 0, noise_deg = 0.0724, noise_m = 0.5e-3, rate_deg_s = NAN,
         yaw0_deg = NAN, dropout = 0, dropout_value = 0;
  std::uint64_t seed = 1;
};

void AddPosetrackCommand(CLI::App& app, PosetrackCli* p, CLI::App** sub) {
  CLI::App* s = app.add_subcommand(
      "posetrack", "6-DOF pose measurements (x,y,z,yaw,pitch,roll) with truth at sample and mid-times (seed 000)");
  *sub = s;
  s->add_option("--out,-o", p->w.out_dir, "Folder to create (refused if it exists and is not empty)")->required();
  s->add_flag("--force", p->w.force, "Replace an existing non-empty --out folder");
  s->add_option("--scenario", p->scenario,
                "turntable (seed 000: yaw at 10 deg/s, 20 fps, 0-9 s) or head (maneuvering 6-DOF head motion)")
      ->capture_default_str();
  s->add_option("--duration", p->duration_s, "Length (s); samples cover [t0, t0 + duration] (default: turntable 9, head 20)");
  s->add_option("--fps", p->fps, "Sample rate (Hz)")->capture_default_str();
  s->add_option("--t0", p->t0_s, "Time of sample 0 since the epoch (s)")->capture_default_str();
  s->add_option("--seed", p->seed, "Random seed (same seed, same files)")->capture_default_str();
  s->add_option("--noise-deg", p->noise_deg, "Measurement noise std of the three angles (deg)")->capture_default_str();
  s->add_option("--noise-m", p->noise_m, "Measurement noise std of x, y, z (m)")->capture_default_str();
  s->add_option("--rate-deg-s", p->rate_deg_s, "turntable: yaw rate (deg/s) (default 10)");
  s->add_option("--yaw0-deg", p->yaw0_deg, "turntable: yaw at t0 (deg) (default 20)");
  s->add_option("--dropout", p->dropout, "Probability that a measurement row is missing (all values empty)")
      ->capture_default_str();
  s->add_option("--dropout-value", p->dropout_value, "Probability that a single measured value is missing")
      ->capture_default_str();
}

int RunPosetrack(const PosetrackCli& p, const CLI::App& sub, const rk::cli::CommonOptions& common, int argc,
                 char** argv) {
  using rk::geo::DegToRad;
  rk::sim::PoseScenario scenario;
  if (!rk::sim::ParsePoseScenario(p.scenario, &scenario)) {
    throw rk::UsageError("--scenario must be 'turntable' or 'head', not '" + p.scenario + "'");
  }
  rk::sim::PoseTrackOptions o = rk::sim::DefaultPoseTrackOptions(scenario);
  if (scenario != rk::sim::PoseScenario::kTurntable) {
    for (const char* opt : {"--rate-deg-s", "--yaw0-deg"}) {
      if (sub.count(opt) > 0) throw rk::UsageError(std::string(opt) + " applies to --scenario turntable only");
    }
  }
  if (sub.count("--duration") > 0) o.duration_s = p.duration_s;
  o.fps = p.fps;
  o.t0_s = p.t0_s;
  o.seed = p.seed;
  o.noise_angle_rad = DegToRad(p.noise_deg);
  o.noise_position_m = p.noise_m;
  if (sub.count("--rate-deg-s") > 0) o.rate_rad_s = DegToRad(p.rate_deg_s);
  if (sub.count("--yaw0-deg") > 0) o.yaw0_rad = DegToRad(p.yaw0_deg);
  o.dropout = p.dropout;
  o.dropout_value = p.dropout_value;
  std::string why;
  if (!o.Check(&why)) throw rk::UsageError(why);
  if (!p.w.Check(&why)) throw rk::UsageError(why);
  const rk::sim::PoseTrackSimulator sim(o);
  const rk::sim::PoseTrackSummary sum = rk::sim::WritePoseTrack(sim, p.w);
  if (!common.report_path.empty()) {
    rk::io::Json r = rk::cli::MakeReport(kTool, argc, argv);
    r["subcommand"] = "posetrack";
    r["out"] = p.w.out_dir;
    r["options"] = rk::sim::PoseTrackOptionsToJson(o);
    r["summary"] = sum.ToJson();
    rk::io::WriteJson(common.report_path, r);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using rk::geo::DegToRad;
  CLI::App app("rk-sim: synthesize trials with ground truth (video, turret and range logs, truth files)", kTool);
  rk::cli::CommonOptions common;
  rk::cli::AddCommonOptions(app, kTool, &common);
  app.require_subcommand(1);

  CLI::App* beacon = app.add_subcommand(
      "beacon", "Beacon-tracking trial: lamp-cluster target, turret with lag and jitter, 5 Hz range log, truth");
  rk::sim::TrialWriteOptions w;
  std::string preset = "default", trajectory = "default", camera_path;
  int width = 0, height = 0;
  double duration_s = 10, fps = 20, t0_s = 1.0, range_m = NAN, speed_mps = NAN, azimuth_deg = NAN,
         elevation_deg = NAN, max_el_deg = 80, turn_rate_deg_s = NAN;
  std::uint64_t seed = 1;
  int bit_depth = 8, lamps = 5, distractors = 0;
  double peak_dn = 160, read_noise_dn = 2, background_dn = 10, gain = 40, psf_sigma_px = 1.2, span_m = 0.03,
         margin_px = 120;
  std::vector<std::string> occlusions;
  double range_noise_mm = 0.35, range_error_rate = 0.01, range_rate_hz = 5, range_offset_s = 0.071;
  double turret_rate_hz = 50, turret_offset_s = 0.0037, turret_res_deg = 0.003, turret_noise_std_deg = 0;
  double lag_s = 0.15, jitter_arcsec = 5, jitter_min_hz = 0.5, jitter_max_hz = 5;

  beacon->add_option("--out,-o", w.out_dir, "Trial folder to create (refused if it exists and is not empty)")
      ->required();
  beacon->add_flag("--force", w.force, "Replace an existing non-empty --out folder");
  beacon->add_option("--format", w.format, "Video: mkv (az/video.mkv, FFV1) or png (az/%06d.png)")
      ->check(CLI::IsMember({"mkv", "png"}))
      ->capture_default_str();
  beacon->add_option("--name", w.name, "Trial name in trial.json (default: the folder name)");
  beacon->add_option("--epoch-utc", w.epoch_utc, "Trial epoch, ISO-8601 UTC")->capture_default_str();
  beacon->add_option("--preset", preset, "Camera: default (2448x2048, 3.45 um, 50 mm) or small (640x512)")
      ->check(CLI::IsMember({"default", "small"}))
      ->capture_default_str();
  beacon->add_option("--width", width, "Image width (px), overrides the preset; principal point stays centred")
      ->check(CLI::Range(32, 100000));
  beacon->add_option("--height", height, "Image height (px), overrides the preset")->check(CLI::Range(32, 100000));
  beacon->add_option("--camera", camera_path, "Camera model JSON (SPEC.md §3) instead of a preset")
      ->check(CLI::ExistingFile);
  beacon
      ->add_option("--trajectory", trajectory, "Target motion: default, straight, turning, overhead, static")
      ->check(CLI::IsMember({"default", "straight", "turning", "overhead", "static"}))
      ->capture_default_str();
  beacon->add_option("--duration", duration_s, "Trial length (s)")->capture_default_str();
  beacon->add_option("--fps", fps, "Frame rate (Hz)")->capture_default_str();
  beacon->add_option("--t0", t0_s, "Time of frame 0 since the epoch (s)")->capture_default_str();
  beacon->add_option("--range-m", range_m, "Nominal / closest-approach range (m), 20..10000 (default per trajectory)");
  beacon->add_option("--speed-mps", speed_mps, "Target speed (m/s) (default per trajectory, scaled with --range-m)");
  beacon->add_option("--azimuth-deg", azimuth_deg, "Nominal azimuth of the target (deg) (default 30)");
  beacon->add_option("--elevation-deg", elevation_deg, "Nominal elevation of the target (deg) (default 5)");
  beacon->add_option("--max-el-deg", max_el_deg, "overhead: elevation at closest approach (deg)")
      ->capture_default_str();
  beacon->add_option("--turn-rate-deg-s", turn_rate_deg_s, "turning: turn rate (deg/s) (default 5.73)");
  beacon->add_option("--seed", seed, "Random seed (same seed, same trial)")->capture_default_str();
  beacon->add_option("--bit-depth", bit_depth, "8 or 16 (16-bit: every DN x256)")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  beacon->add_option("--peak-dn", peak_dn, "Brightest lamp amplitude above background (8-bit DN)")
      ->capture_default_str();
  beacon->add_option("--background-dn", background_dn, "Background level (8-bit DN)")->capture_default_str();
  beacon->add_option("--read-noise-dn", read_noise_dn, "Read noise std (8-bit DN)")->capture_default_str();
  beacon->add_option("--gain-e-per-dn", gain, "Photo-electrons per 8-bit DN (shot noise); 0 = none")
      ->capture_default_str();
  beacon->add_option("--psf-sigma-px", psf_sigma_px, "Lamp PSF std (px)")->capture_default_str();
  beacon->add_option("--lamps", lamps, "Lamps in the cluster (>= 5)")->capture_default_str();
  beacon->add_option("--cluster-span-m", span_m, "Lamp cluster diameter (m)")->capture_default_str();
  beacon->add_option("--distractors", distractors, "Bright glints in the image")->capture_default_str();
  beacon->add_option("--distractor-margin-px", margin_px, "Glints start at least this far from the beacon (px)")
      ->capture_default_str();
  beacon->add_option("--occlusion", occlusions,
                     "Hide the lamps: START_S:DURATION_S after frame 0 (DURATION_S may be short=0.5 or long=5); "
                     "repeatable");
  beacon->add_option("--range-noise-mm", range_noise_mm, "Range noise std (mm)")->capture_default_str();
  beacon->add_option("--range-error-rate", range_error_rate, "Probability of a device-error row (status 255)")
      ->capture_default_str();
  beacon->add_option("--range-rate-hz", range_rate_hz, "Range log rate (Hz)")->capture_default_str();
  beacon->add_option("--range-offset-s", range_offset_s, "Range sample time offset from the frame grid (s)")
      ->capture_default_str();
  beacon->add_option("--turret-rate-hz", turret_rate_hz, "Turret log rate (Hz)")->capture_default_str();
  beacon->add_option("--turret-offset-s", turret_offset_s, "Turret sample time offset from the frame grid (s)")
      ->capture_default_str();
  beacon->add_option("--turret-noise-deg", turret_res_deg,
                     "Turret encoder quantisation step (deg), PTU-D48E 0.003; 0 = exact angles")
      ->capture_default_str();
  beacon->add_option("--turret-noise-std-deg", turret_noise_std_deg, "Extra Gaussian encoder noise std (deg)")
      ->capture_default_str();
  beacon->add_option("--turret-lag-s", lag_s, "Turret servo time constant (s); 0 = no lag")->capture_default_str();
  beacon->add_option("--jitter-arcsec", jitter_arcsec, "Turret jitter RMS per axis (arcsec); 0 = none")
      ->capture_default_str();
  beacon->add_option("--jitter-min-hz", jitter_min_hz, "Lowest jitter frequency (Hz)")->capture_default_str();
  beacon->add_option("--jitter-max-hz", jitter_max_hz, "Highest jitter frequency (Hz)")->capture_default_str();

  PosetrackCli posetrack_cli;
  CLI::App* posetrack = nullptr;
  AddPosetrackCommand(app, &posetrack_cli, &posetrack);

  return rk::cli::Run(app, kTool, argc, argv, [&]() -> int {
    if (posetrack->parsed()) return RunPosetrack(posetrack_cli, *posetrack, common, argc, argv);
    rk::sim::BeaconSimOptions o;
    if (!camera_path.empty()) {
      o.camera = rk::camera::LoadCameraModel(camera_path);
      o.camera_preset = "file";
    } else {
      rk::sim::CameraPreset(preset, &o.camera);
      o.camera_preset = preset;
    }
    if (width > 0 || height > 0) {
      if (width > 0) o.camera.width_px = width;
      if (height > 0) o.camera.height_px = height;
      o.camera.principal_point_px = {0.5 * (o.camera.width_px - 1), 0.5 * (o.camera.height_px - 1)};
      o.camera_preset += "-resized";
    }
    rk::sim::TrajectoryKind kind;
    rk::sim::ParseTrajectoryKind(trajectory, &kind);
    if (beacon->count("--range-m") > 0 && !std::isfinite(range_m)) throw rk::UsageError("--range-m must be finite");
    o.trajectory = rk::sim::DefaultTrajectoryOptions(kind, range_m);  // range_m NaN: trajectory default
    if (!std::isnan(speed_mps)) o.trajectory.speed_mps = speed_mps;
    if (!std::isnan(azimuth_deg)) o.trajectory.azimuth_rad = DegToRad(azimuth_deg);
    if (!std::isnan(elevation_deg)) o.trajectory.elevation_rad = DegToRad(elevation_deg);
    if (!std::isnan(turn_rate_deg_s)) o.trajectory.turn_rate_rad_s = DegToRad(turn_rate_deg_s);
    o.trajectory.max_elevation_rad = DegToRad(max_el_deg);
    o.duration_s = duration_s;
    o.fps = fps;
    o.t0_s = t0_s;
    o.lamps = lamps;
    o.cluster_span_m = span_m;
    o.psf_sigma_px = psf_sigma_px;
    o.peak_dn = peak_dn;
    o.sensor.background_dn = background_dn;
    o.sensor.read_noise_dn = read_noise_dn;
    o.sensor.gain_e_per_dn = gain;
    o.sensor.bit_depth = bit_depth;
    o.distractors = distractors;
    o.distractor_margin_px = margin_px;
    for (const auto& text : occlusions) {
      rk::sim::OcclusionInterval occ;
      std::string why;
      if (!rk::sim::ParseOcclusion(text, &occ, &why)) throw rk::UsageError("--occlusion: " + why);
      o.occlusions.push_back(occ);
    }
    o.servo.lag_s = lag_s;
    o.servo.jitter_rms_rad = jitter_arcsec / rk::geo::kArcsecPerRad;
    o.servo.jitter_min_hz = jitter_min_hz;
    o.servo.jitter_max_hz = jitter_max_hz;
    o.turret_rate_hz = turret_rate_hz;
    o.turret_offset_s = turret_offset_s;
    o.turret_resolution_rad = DegToRad(turret_res_deg);
    o.turret_noise_rad = DegToRad(turret_noise_std_deg);
    o.range_rate_hz = range_rate_hz;
    o.range_offset_s = range_offset_s;
    o.range_noise_m = range_noise_mm * 1e-3;
    o.range_error_rate = range_error_rate;
    o.seed = seed;
    std::string why;
    if (!o.Check(&why)) throw rk::UsageError(why);
    if (!w.Check(&why)) throw rk::UsageError(why);
    if (!common.report_path.empty()) rk::io::CheckOutputNotInput(common.report_path, {camera_path});

    const rk::sim::BeaconSimulator sim(o);
    const bool progress = rk::cli::ShowProgress(common);
    if (progress) {
      w.progress = [](std::size_t done, std::size_t total) {
        if (done % 10 == 0 || done == total) {
          std::cerr << "\rrk-sim: frame " << done << "/" << total << (done == total ? "\n" : "") << std::flush;
        }
      };
    }
    const rk::sim::TrialSummary sum = rk::sim::WriteBeaconTrial(sim, w);
    if (!common.report_path.empty()) {
      rk::io::Json r = rk::cli::MakeReport(kTool, argc, argv);
      if (!camera_path.empty()) rk::cli::AddReportInput(&r, "camera", camera_path);
      r["subcommand"] = "beacon";
      r["out"] = w.out_dir;
      r["options"] = rk::sim::BeaconSimOptionsToJson(o);
      r["summary"] = sum.ToJson();
      rk::io::WriteJson(common.report_path, r);
    }
    return 0;
  });
}

// rk-sim beacon: beacon-camera tracking trial (seed 001): video, turret, range, truth.
// Thin edge: CLI11 options → rk::sim::BeaconSimOptions → rk::sim::WriteBeaconTrial; docs/rk-sim.md.
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <string>
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

// Options as given on the command line.
struct BeaconCli {
  rk::sim::TrialWriteOptions w;
  std::string preset = "default", trajectory = "default", camera_path;
  int width = 0, height = 0;
  double duration_s = 10, fps = 20, t0_s = 1.0, range_m = NAN, speed_mps = NAN, azimuth_deg = NAN,
         elevation_deg = NAN, max_el_deg = 80, turn_rate_deg_s = NAN;
  std::uint64_t seed = 1;
  int bit_depth = 8, lamps = 5, distractors = 0;
  double peak_dn = 160, read_noise_dn = 2, background_dn = 10, gain = 40, psf_sigma_px = 1.2, span_m = 0.03,
         margin_px = 120;
  std::vector<std::string> occlusions, servo_holds;
  double range_noise_mm = 0.35, range_error_rate = 0.01, range_rate_hz = 5, range_offset_s = 0.071;
  double turret_rate_hz = 50, turret_offset_s = 0.0037, turret_res_deg = 0.003, turret_noise_std_deg = 0;
  double lag_s = 0.15, jitter_arcsec = 5, jitter_min_hz = 0.5, jitter_max_hz = 5;
};

}  // namespace

Command AddBeaconCommand(CLI::App& parent) {
  using rk::geo::DegToRad;
  CLI::App* beacon = parent.add_subcommand(
      "beacon",
      "Beacon-tracking trial: lamp-cluster target, turret with lag and jitter, 5 Hz range log, truth");
  auto a = std::make_shared<BeaconCli>();
  BeaconCli& c = *a;

  beacon
      ->add_option("--out,-o", c.w.out_dir, "Trial folder to create (refused if it exists and is not empty)")
      ->required();
  beacon->add_flag("--force", c.w.force, "Replace an existing non-empty --out folder");
  beacon->add_option("--format", c.w.format, "Video: mkv (az/video.mkv, FFV1) or png (az/%06d.png)")
      ->check(CLI::IsMember({"mkv", "png"}))
      ->capture_default_str();
  beacon->add_option("--name", c.w.name, "Trial name in trial.json (default: the folder name)");
  beacon->add_option("--epoch-utc", c.w.epoch_utc, "Trial epoch, ISO-8601 UTC")->capture_default_str();
  beacon->add_option("--preset", c.preset, "Camera: default (2448x2048, 3.45 um, 50 mm) or small (640x512)")
      ->check(CLI::IsMember({"default", "small"}))
      ->capture_default_str();
  beacon
      ->add_option("--width", c.width,
                   "Image width (px), overrides the preset; principal point stays centred")
      ->check(CLI::Range(32, 100000));
  beacon->add_option("--height", c.height, "Image height (px), overrides the preset")
      ->check(CLI::Range(32, 100000));
  beacon->add_option("--camera", c.camera_path, "Camera model JSON (SPEC.md §3) instead of a preset")
      ->check(CLI::ExistingFile);
  beacon
      ->add_option("--trajectory", c.trajectory,
                   "Target motion: default, straight, turning, overhead, static")
      ->check(CLI::IsMember({"default", "straight", "turning", "overhead", "static"}))
      ->capture_default_str();
  beacon->add_option("--duration", c.duration_s, "Trial length (s)")->capture_default_str();
  beacon->add_option("--fps", c.fps, "Frame rate (Hz)")->capture_default_str();
  beacon->add_option("--t0", c.t0_s, "Time of frame 0 since the epoch (s)")->capture_default_str();
  beacon->add_option("--range-m", c.range_m,
                     "Nominal / closest-approach range (m), 20..10000 (default per trajectory)");
  beacon->add_option("--speed-mps", c.speed_mps,
                     "Target speed (m/s) (default per trajectory, scaled with --range-m)");
  beacon->add_option("--azimuth-deg", c.azimuth_deg, "Nominal azimuth of the target (deg) (default 30)");
  beacon->add_option("--elevation-deg", c.elevation_deg, "Nominal elevation of the target (deg) (default 5)");
  beacon->add_option("--max-el-deg", c.max_el_deg, "overhead: elevation at closest approach (deg)")
      ->capture_default_str();
  beacon->add_option("--turn-rate-deg-s", c.turn_rate_deg_s, "turning: turn rate (deg/s) (default 5.73)");
  beacon->add_option("--seed", c.seed, "Random seed (same seed, same trial)")->capture_default_str();
  beacon->add_option("--bit-depth", c.bit_depth, "8 or 16 (16-bit: every DN x256)")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  beacon->add_option("--peak-dn", c.peak_dn, "Brightest lamp amplitude above background (8-bit DN)")
      ->capture_default_str();
  beacon->add_option("--background-dn", c.background_dn, "Background level (8-bit DN)")
      ->capture_default_str();
  beacon->add_option("--read-noise-dn", c.read_noise_dn, "Read noise std (8-bit DN)")->capture_default_str();
  beacon->add_option("--gain-e-per-dn", c.gain, "Photo-electrons per 8-bit DN (shot noise); 0 = none")
      ->capture_default_str();
  beacon->add_option("--psf-sigma-px", c.psf_sigma_px, "Lamp PSF std (px)")->capture_default_str();
  beacon->add_option("--lamps", c.lamps, "Lamps in the cluster (>= 5)")->capture_default_str();
  beacon->add_option("--cluster-span-m", c.span_m, "Lamp cluster diameter (m)")->capture_default_str();
  beacon->add_option("--distractors", c.distractors, "Bright glints in the image")->capture_default_str();
  beacon
      ->add_option("--distractor-margin-px", c.margin_px,
                   "Glints start at least this far from the beacon (px)")
      ->capture_default_str();
  beacon->add_option(
      "--occlusion", c.occlusions,
      "Hide the lamps: START_S:DURATION_S after frame 0 (DURATION_S may be short=0.5 or long=5); "
      "repeatable");
  beacon->add_option(
      "--servo-hold", c.servo_holds,
      "Stop the turret: START_S:DURATION_S after frame 0, then it catches up (image motion reverses); "
      "repeatable");
  beacon->add_option("--range-noise-mm", c.range_noise_mm, "Range noise std (mm)")->capture_default_str();
  beacon
      ->add_option("--range-error-rate", c.range_error_rate, "Probability of a device-error row (status 255)")
      ->capture_default_str();
  beacon->add_option("--range-rate-hz", c.range_rate_hz, "Range log rate (Hz)")->capture_default_str();
  beacon->add_option("--range-offset-s", c.range_offset_s, "Range sample time offset from the frame grid (s)")
      ->capture_default_str();
  beacon->add_option("--turret-rate-hz", c.turret_rate_hz, "Turret log rate (Hz)")->capture_default_str();
  beacon
      ->add_option("--turret-offset-s", c.turret_offset_s,
                   "Turret sample time offset from the frame grid (s)")
      ->capture_default_str();
  beacon
      ->add_option("--turret-noise-deg", c.turret_res_deg,
                   "Turret encoder quantisation step (deg), PTU-D48E 0.003; 0 = exact angles")
      ->capture_default_str();
  beacon
      ->add_option("--turret-noise-std-deg", c.turret_noise_std_deg, "Extra Gaussian encoder noise std (deg)")
      ->capture_default_str();
  beacon->add_option("--turret-lag-s", c.lag_s, "Turret servo time constant (s); 0 = no lag")
      ->capture_default_str();
  beacon->add_option("--jitter-arcsec", c.jitter_arcsec, "Turret jitter RMS per axis (arcsec); 0 = none")
      ->capture_default_str();
  beacon->add_option("--jitter-min-hz", c.jitter_min_hz, "Lowest jitter frequency (Hz)")
      ->capture_default_str();
  beacon->add_option("--jitter-max-hz", c.jitter_max_hz, "Highest jitter frequency (Hz)")
      ->capture_default_str();

  return {beacon, [a, beacon](const Context& ctx) -> int {
            using rk::geo::DegToRad;
            BeaconCli c = *a;
            const auto& common = ctx.common;
            const int argc = ctx.argc;
            char** const argv = ctx.argv;
            rk::sim::BeaconSimOptions o;
            if (!c.camera_path.empty()) {
              o.camera = rk::camera::LoadCameraModel(c.camera_path);
              o.camera_preset = "file";
            } else {
              rk::sim::CameraPreset(c.preset, &o.camera);
              o.camera_preset = c.preset;
            }
            if (c.width > 0 || c.height > 0) {
              if (c.width > 0) o.camera.width_px = c.width;
              if (c.height > 0) o.camera.height_px = c.height;
              o.camera.principal_point_px = {0.5 * (o.camera.width_px - 1), 0.5 * (o.camera.height_px - 1)};
              o.camera_preset += "-resized";
            }
            rk::sim::TrajectoryKind kind;
            rk::sim::ParseTrajectoryKind(c.trajectory, &kind);
            if (beacon->count("--range-m") > 0 && !std::isfinite(c.range_m))
              throw rk::UsageError("--range-m must be finite");
            o.trajectory =
                rk::sim::DefaultTrajectoryOptions(kind, c.range_m);  // range_m NaN: trajectory default
            if (!std::isnan(c.speed_mps)) o.trajectory.speed_mps = c.speed_mps;
            if (!std::isnan(c.azimuth_deg)) o.trajectory.azimuth_rad = DegToRad(c.azimuth_deg);
            if (!std::isnan(c.elevation_deg)) o.trajectory.elevation_rad = DegToRad(c.elevation_deg);
            if (!std::isnan(c.turn_rate_deg_s)) o.trajectory.turn_rate_rad_s = DegToRad(c.turn_rate_deg_s);
            o.trajectory.max_elevation_rad = DegToRad(c.max_el_deg);
            o.duration_s = c.duration_s;
            o.fps = c.fps;
            o.t0_s = c.t0_s;
            o.lamps = c.lamps;
            o.cluster_span_m = c.span_m;
            o.psf_sigma_px = c.psf_sigma_px;
            o.peak_dn = c.peak_dn;
            o.sensor.background_dn = c.background_dn;
            o.sensor.read_noise_dn = c.read_noise_dn;
            o.sensor.gain_e_per_dn = c.gain;
            o.sensor.bit_depth = c.bit_depth;
            o.distractors = c.distractors;
            o.distractor_margin_px = c.margin_px;
            for (const auto& text : c.occlusions) {
              rk::sim::OcclusionInterval occ;
              std::string why;
              if (!rk::sim::ParseOcclusion(text, &occ, &why)) throw rk::UsageError("--occlusion: " + why);
              o.occlusions.push_back(occ);
            }
            for (const auto& text : c.servo_holds) {
              rk::sim::OcclusionInterval hold;
              std::string why;
              if (!rk::sim::ParseOcclusion(text, &hold, &why)) throw rk::UsageError("--servo-hold: " + why);
              o.servo_holds.push_back(hold);
            }
            o.servo.lag_s = c.lag_s;
            o.servo.jitter_rms_rad = c.jitter_arcsec / rk::geo::kArcsecPerRad;
            o.servo.jitter_min_hz = c.jitter_min_hz;
            o.servo.jitter_max_hz = c.jitter_max_hz;
            o.turret_rate_hz = c.turret_rate_hz;
            o.turret_offset_s = c.turret_offset_s;
            o.turret_resolution_rad = DegToRad(c.turret_res_deg);
            o.turret_noise_rad = DegToRad(c.turret_noise_std_deg);
            o.range_rate_hz = c.range_rate_hz;
            o.range_offset_s = c.range_offset_s;
            o.range_noise_m = c.range_noise_mm * 1e-3;
            o.range_error_rate = c.range_error_rate;
            o.seed = c.seed;
            std::string why;
            if (!o.Check(&why)) throw rk::UsageError(why);
            if (!c.w.Check(&why)) throw rk::UsageError(why);
            if (!common.report_path.empty()) rk::io::CheckOutputNotInput(common.report_path, {c.camera_path});

            const rk::sim::BeaconSimulator sim(o);
            const bool progress = rk::cli::ShowProgress(common);
            if (progress) {
              c.w.progress = [&ctx](std::size_t done, std::size_t total) {
                if (done % 10 == 0 || done == total) {
                  std::cerr << "\r" << ctx.tool << ": frame " << done << "/" << total
                            << (done == total ? "\n" : "") << std::flush;
                }
              };
            }
            const rk::sim::TrialSummary sum = rk::sim::WriteBeaconTrial(sim, c.w);
            if (!common.report_path.empty()) {
              rk::io::Json r = rk::cli::MakeReport(ctx.tool, argc, argv);
              if (!c.camera_path.empty()) rk::cli::AddReportInput(&r, "camera", c.camera_path);
              r["subcommand"] = "beacon";
              r["out"] = c.w.out_dir;
              r["options"] = rk::sim::BeaconSimOptionsToJson(o);
              r["summary"] = sum.ToJson();
              rk::cli::WriteReport(common.report_path, r);
            }
            return 0;
          }};
}

}  // namespace rk::app

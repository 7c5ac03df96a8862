// rk-sim attitude: attitude-camera trial of seed 001's dynamic test with truth (target with
// markers on a moving, rotating gantry, 100 mm camera on the tracking turret). Method:
// lib/sim/attitude_scenario.h, files: lib/sim/attitude_trial.h; user page docs/rk-sim.md.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "camera/camera_model.h"
#include "geo/angles.h"
#include "io/cli.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "sim/attitude_scenario.h"
#include "sim/attitude_trial.h"
#include "sim_commands.h"
#include "target/feature_model.h"

namespace rk::app {
namespace {

struct AttitudeCli {
  sim::AttitudeTrialWriteOptions w;
  sim::AttitudeSimOptions o;
  std::string camera_path, target_path;
  std::vector<std::string> hides;
  bool no_video = false;
  double az_deg = 30, el_deg = 3, path_deg = 30, yaw0 = 300, pitch0 = 5, roll0 = 0, dyaw = 10, dpitch = 7, droll = 5;
  double jitter_arcsec = 5.0, turret_step_deg = 0.003, turret_noise_std_deg = 0.0;
};

int RunAttitude(AttitudeCli& c, const Context& ctx) {
  using geo::DegToRad;
  sim::AttitudeSimOptions& o = c.o;
  if (!c.camera_path.empty()) o.camera = camera::LoadCameraModel(c.camera_path);
  if (!c.target_path.empty()) {
    const target::FeatureModel m = target::LoadFeatureModel(c.target_path);
    o.marker_ids = m.ids;
    o.markers_body = m.p_body;
  } else {
    sim::DefaultAttitudeMarkers(&o.marker_ids, &o.markers_body);
  }
  for (const std::string& h : c.hides) {
    sim::MarkerHide mh;
    std::string why;
    if (!sim::ParseMarkerHide(h, &mh, &why)) throw UsageError(why);
    o.hides.push_back(mh);
  }
  o.azimuth_rad = DegToRad(c.az_deg);
  o.elevation_rad = DegToRad(c.el_deg);
  o.path_angle_rad = DegToRad(c.path_deg);
  o.yaw0_rad = DegToRad(c.yaw0);
  o.pitch0_rad = DegToRad(c.pitch0);
  o.roll0_rad = DegToRad(c.roll0);
  o.dyaw_rad = DegToRad(c.dyaw);
  o.dpitch_rad = DegToRad(c.dpitch);
  o.droll_rad = DegToRad(c.droll);
  o.servo.jitter_rms_rad = c.jitter_arcsec / geo::kArcsecPerRad;
  o.turret_resolution_rad = DegToRad(c.turret_step_deg);
  o.turret_noise_rad = DegToRad(c.turret_noise_std_deg);
  c.w.video = !c.no_video;
  std::string why;
  if (!o.Check(&why)) throw UsageError(why);
  if (!c.w.Check(&why)) throw UsageError(why);
  if (!ctx.common.report_path.empty() && !c.camera_path.empty()) {
    io::CheckOutputNotInput(ctx.common.report_path, {c.camera_path});
  }
  const sim::AttitudeSimulator simulator(o);
  const bool progress = cli::ShowProgress(ctx.common);
  if (progress) {
    c.w.progress = [&ctx](std::size_t done, std::size_t total) {
      std::cerr << "\r" << ctx.tool << ": frame " << done << "/" << total << std::flush;
    };
  }
  const sim::AttitudeTrialSummary sum = sim::WriteAttitudeTrial(simulator, c.w);
  if (progress) std::cerr << "\n";
  if (!ctx.common.report_path.empty()) {
    io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "attitude";
    if (!c.camera_path.empty()) cli::AddReportInput(&r, "camera", c.camera_path);
    if (!c.target_path.empty()) cli::AddReportInput(&r, "target", c.target_path);
    r["out"] = c.w.out_dir;
    r["options"] = sim::AttitudeSimOptionsToJson(simulator.options());
    r["summary"] = sum.ToJson();
    cli::WriteReport(ctx.common.report_path, r);
  }
  return 0;
}

}  // namespace

Command AddAttitudeCommand(CLI::App& parent) {
  auto c = std::make_shared<AttitudeCli>();
  CLI::App* s = parent.add_subcommand(
      "attitude",
      "Attitude-camera trial of seed 001's dynamic test: a target with >= 4 markers approaching 6 m and "
      "returning 5 m while turning (yaw 10, pitch 7, roll 5 deg), 100 mm camera on the tracking turret; video, "
      "turret log, target model and truth pose/points");
  s->add_option("--out,-o", c->w.out_dir, "Trial folder to create (refused if it exists and is not empty)")
      ->required();
  s->add_flag("--force", c->w.force, "Replace an existing non-empty --out folder");
  s->add_option("--format", c->w.format, "Video: mkv (att/video.mkv, FFV1) or png (att/%06d.png)")
      ->capture_default_str();
  s->add_flag("--no-video", c->no_video, "Write truth, logs and models only (no images)");
  s->add_option("--name", c->w.name, "Trial name in trial.json (default: the folder name)");
  s->add_option("--epoch-utc", c->w.epoch_utc, "Trial epoch, ISO-8601 UTC")->capture_default_str();
  s->add_option("--camera", c->camera_path,
                "Camera model JSON (SPEC.md section 3) instead of the attitude camera (2448x2048, 3.45 um, 100 mm)");
  s->add_option("--target", c->target_path,
                "Target model JSON {\"points\": {...}} instead of the default 8-marker layout");
  s->add_option("--duration", c->o.duration_s, "Trial length (s); the default 22 s covers the approach and the return")
      ->capture_default_str();
  s->add_option("--fps", c->o.fps, "Frame rate (Hz)")->capture_default_str();
  s->add_option("--t0", c->o.t0_s, "Time of frame 0 since the epoch (s)")->capture_default_str();
  s->add_option("--seed", c->o.seed, "Random seed (same seed, same trial)")->capture_default_str();
  s->add_option("--range-m", c->o.range_m, "Initial range of the body origin (m)")->capture_default_str();
  s->add_option("--azimuth-deg", c->az_deg, "Initial azimuth of the target (deg)")->capture_default_str();
  s->add_option("--elevation-deg", c->el_deg, "Initial elevation of the target (deg)")->capture_default_str();
  s->add_option("--approach-m", c->o.approach_m, "Distance moved toward the station on the way in (m)")
      ->capture_default_str();
  s->add_option("--return-m", c->o.return_m, "Distance moved back on the way out (m)")->capture_default_str();
  s->add_option("--leg-in-s", c->o.leg_in_s, "Duration of the approach (s), from the first frame")
      ->capture_default_str();
  s->add_option("--leg-out-s", c->o.leg_out_s, "Duration of the return (s), after the approach")
      ->capture_default_str();
  s->add_option("--path-angle-deg", c->path_deg,
                "Angle of the (horizontal) motion from the line of sight to the station (deg)")
      ->capture_default_str();
  s->add_option("--yaw0-deg", c->yaw0, "Initial yaw (deg, clockwise from north)")->capture_default_str();
  s->add_option("--pitch0-deg", c->pitch0, "Initial pitch (deg)")->capture_default_str();
  s->add_option("--roll0-deg", c->roll0, "Initial roll (deg)")->capture_default_str();
  s->add_option("--dyaw-deg", c->dyaw, "Yaw change on the way in (deg), undone on the way out")
      ->capture_default_str();
  s->add_option("--dpitch-deg", c->dpitch, "Pitch change on the way in (deg)")->capture_default_str();
  s->add_option("--droll-deg", c->droll, "Roll change on the way in (deg)")->capture_default_str();
  s->add_option("--marker-radius-m", c->o.marker_radius_m, "Marker sphere radius (m)")->capture_default_str();
  s->add_option("--marker-dn", c->o.marker_dn, "Marker level above background (8-bit DN)")->capture_default_str();
  s->add_option("--body-dn", c->o.body_dn, "Target body level above background (8-bit DN); 0 = no body")
      ->capture_default_str();
  s->add_option("--psf-sigma-px", c->o.psf_sigma_px, "PSF std (px)")->capture_default_str();
  s->add_option("--bit-depth", c->o.sensor.bit_depth, "8 or 16 (16-bit: every DN x256)")->capture_default_str();
  s->add_option("--background-dn", c->o.sensor.background_dn, "Background level (8-bit DN)")->capture_default_str();
  s->add_option("--read-noise-dn", c->o.sensor.read_noise_dn, "Read noise std (8-bit DN)")->capture_default_str();
  s->add_option("--gain-e-per-dn", c->o.sensor.gain_e_per_dn, "Photo-electrons per 8-bit DN; 0 = no shot noise")
      ->capture_default_str();
  s->add_option("--hide", c->hides, "Hide a marker: ID:START_S:DURATION_S (START from frame 0; repeatable)");
  s->add_option("--turret-rate-hz", c->o.turret_rate_hz, "Turret log rate (Hz)")->capture_default_str();
  s->add_option("--turret-offset-s", c->o.turret_offset_s, "Turret sample time offset from the frame grid (s)")
      ->capture_default_str();
  s->add_option("--turret-noise-deg", c->turret_step_deg,
                "Turret encoder step (deg): recorded angles are quantised to it; 0 = exact (as rk-sim beacon)")
      ->capture_default_str();
  s->add_option("--turret-noise-std-deg", c->turret_noise_std_deg, "Extra Gaussian turret angle noise std (deg)")
      ->capture_default_str();
  s->add_option("--turret-lag-s", c->o.servo.lag_s, "Turret servo time constant (s); 0 = no lag")
      ->capture_default_str();
  s->add_option("--jitter-arcsec", c->jitter_arcsec, "Turret jitter RMS per axis (arcsec)")->capture_default_str();
  return {s, [c](const Context& ctx) { return RunAttitude(*c, ctx); }};
}

}  // namespace rk::app

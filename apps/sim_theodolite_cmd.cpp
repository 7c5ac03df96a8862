// rk-sim theodolite: single-station theodolite trial of a cylindrical target (seed 004) with truth.
// Thin edge: CLI11 options → rk::sim::TheodoliteSimOptions / TheodoliteWriteOptions → WriteTheodoliteTrial;
// docs/rk-sim.md.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "camera/camera_model.h"
#include "io/error.h"
#include "io/json_util.h"
#include "sim/theodolite_trial.h"
#include "sim_commands.h"

namespace rk::app {
namespace {

struct TheodoliteCli {
  sim::TheodoliteSimOptions s;
  sim::TheodoliteWriteOptions w;
  std::string camera_path, angle_budget = "none";
  int sensor_px = 0;
};

}  // namespace

Command AddTheodoliteCommand(CLI::App& parent) {
  auto p = std::make_shared<TheodoliteCli>();
  auto& s = p->s;
  auto& w = p->w;
  CLI::App* c = parent.add_subcommand(
      "theodolite",
      "Single-station theodolite trial of a cylindrical target (seed 004: f 1500 mm, 0.011 mm pixels, 16.9 mm "
      "sensor): theodolite log, nose/tail1/tail2 image points, optional rendered images, truth");
  c->add_option("--out,-o", w.out_dir, "Folder to create (refused if it exists and is not empty)")->required();
  c->add_flag("--force", w.force, "Replace an existing non-empty --out folder");
  c->add_option("--images", w.images, "Rendered frames: none, png (theo/%06d.png) or mkv (theo/video.mkv, FFV1)")
      ->capture_default_str();
  c->add_option("--camera", p->camera_path, "Camera model JSON instead of seed 004's 1536x1536, 0.011 mm, 1500 mm");
  c->add_option("--sensor-px", p->sensor_px,
                "Square sensor of this many pixels (same pixel size and focal length, principal point centred)");
  c->add_option("--length-m", s.shape.length_m, "Target length, nose tip to tail plane (m)")->capture_default_str();
  c->add_option("--diameter-m", s.shape.diameter_m, "Target diameter (m)")->capture_default_str();
  c->add_option("--nose-length-m", s.shape.nose_length_m, "Conical nose length (m), for the images")->capture_default_str();
  c->add_option("--range-m", s.range_m, "Range to the target mid-point at mid-trial (m)")->capture_default_str();
  c->add_option("--az-deg", s.az_deg, "Azimuth of the target at mid-trial (deg)")->capture_default_str();
  c->add_option("--el-deg", s.el_deg, "Elevation of the target at mid-trial = theodolite elevation (deg)")
      ->capture_default_str();
  c->add_option("--yaw-deg", s.yaw_deg, "Axis yaw at mid-trial (deg, clockwise from north)")->capture_default_str();
  c->add_option("--pitch-deg", s.pitch_deg, "Axis pitch at mid-trial (deg)")->capture_default_str();
  c->add_option("--speed-mps", s.speed_mps, "Speed along the axis (m/s)")->capture_default_str();
  c->add_option("--yaw-rate-deg-s", s.yaw_rate_deg_s, "Yaw rate (deg/s)")->capture_default_str();
  c->add_option("--pitch-rate-deg-s", s.pitch_rate_deg_s, "Pitch rate (deg/s)")->capture_default_str();
  c->add_option("--duration", s.duration_s, "Trial length (s); frames at t0 + k/fps over [t0, t0 + duration]")
      ->capture_default_str();
  c->add_option("--fps", s.fps, "Frame rate (Hz)")->capture_default_str();
  c->add_option("--t0", s.t0_s, "Time of frame 0 since the epoch (s)")->capture_default_str();
  c->add_option("--track-error-px", s.track_error_px, "Amplitude of the theodolite tracking error in the image (px)")
      ->capture_default_str();
  c->add_option("--theodolite-rate-hz", s.theodolite_rate_hz, "Theodolite log rate (Hz)")->capture_default_str();
  c->add_option("--theodolite-offset", s.theodolite_offset_s, "Theodolite log time offset from the frame grid (s)")
      ->capture_default_str();
  c->add_option("--angle-bias-arcsec", s.angle_bias_arcsec, "Std of the per-trial bias of each theodolite angle (arcsec)")
      ->capture_default_str();
  c->add_option("--angle-noise-arcsec", s.angle_noise_arcsec, "Std of the per-sample noise of each angle (arcsec)")
      ->capture_default_str();
  c->add_option("--angle-budget", p->angle_budget,
                "seed004: seed 004 section 4's angle errors (static 5.099' as bias, dynamic 1.093' as noise; RSS 5.215')")
      ->check(CLI::IsMember({"none", "seed004"}))
      ->capture_default_str();
  c->add_option("--encoder-step-arcsec", s.encoder_step_arcsec, "Quantisation of the recorded angles (arcsec); 0 = none")
      ->capture_default_str();
  c->add_option("--point-noise-px", s.point_noise_px, "Gaussian noise added to the written image points (px)")
      ->capture_default_str();
  c->add_flag("--quantise", s.quantise, "Round the written image points to whole pixels (the paper's 1-pixel reading)");
  c->add_option("--seed", s.seed, "Random seed (same seed, same files)")->capture_default_str();
  c->add_option("--sky-dn", w.render.sky_dn, "Images: sky level (8-bit DN)")->capture_default_str();
  c->add_option("--sky-gradient-dn", w.render.sky_gradient_dn, "Images: sky brightening top to bottom (DN)")
      ->capture_default_str();
  c->add_option("--body-dn", w.render.body_dn, "Images: target level (DN); above --sky-dn for a sunlit target")
      ->capture_default_str();
  c->add_option("--shading-dn", w.render.shading_dn, "Images: +- change of the target level across its width (DN)")
      ->capture_default_str();
  c->add_option("--psf-sigma-px", w.render.psf_sigma_px, "Images: Gaussian PSF std (px)")->capture_default_str();
  c->add_option("--read-noise-dn", w.render.sensor.read_noise_dn, "Images: read noise std (DN)")->capture_default_str();
  c->add_option("--gain", w.render.sensor.gain_e_per_dn, "Images: electrons per DN for shot noise; 0 = none")
      ->capture_default_str();
  c->add_option("--bit-depth", w.render.sensor.bit_depth, "Images: 8 or 16")->capture_default_str();

  return {c, [p, c](const Context& ctx) -> int {
            sim::TheodoliteSimOptions s = p->s;
            sim::TheodoliteWriteOptions w = p->w;
            if (!p->camera_path.empty()) {
              if (p->sensor_px > 0) throw UsageError("--camera and --sensor-px exclude each other");
              s.camera = camera::LoadCameraModel(p->camera_path);
            } else if (c->count("--sensor-px") > 0) {
              if (p->sensor_px < 64 || p->sensor_px > 20000) throw UsageError("--sensor-px must be in [64, 20000]");
              s.camera.width_px = s.camera.height_px = p->sensor_px;
              s.camera.principal_point_px = {0.5 * (p->sensor_px - 1), 0.5 * (p->sensor_px - 1)};
            }
            if (p->angle_budget == "seed004") {
              if (c->count("--angle-bias-arcsec") > 0 || c->count("--angle-noise-arcsec") > 0)
                throw UsageError("--angle-budget seed004 sets the angle bias and noise; do not give them too");
              // Static: levelling 1', crosshair 5', horizontal axis 2", encoder 2". Dynamic: thermal 0.44',
              // wind 1', axis dynamic 2", image motion 0.024'. RSS of all eight: 5.215' (seed 004 §4.1).
              s.angle_bias_arcsec = 60.0 * std::sqrt(1.0 + 25.0 + 2.0 * std::pow(2.0 / 60.0, 2));
              s.angle_noise_arcsec = 60.0 * std::sqrt(0.44 * 0.44 + 1.0 + std::pow(2.0 / 60.0, 2) + 0.024 * 0.024);
            }
            std::string why;
            if (!s.Check(&why)) throw UsageError(why);
            if (!w.Check(&why)) throw UsageError(why);
            const bool progress = cli::ShowProgress(ctx.common);
            if (progress) {
              w.progress = [&ctx](std::size_t done, std::size_t total) {
                std::cerr << "\r" << ctx.tool << ": frame " << done << "/" << total << std::flush;
              };
            }
            const sim::TheodoliteSimulator simulator(s);
            const sim::TheodoliteTrialSummary sum = sim::WriteTheodoliteTrial(simulator, w);
            if (progress) std::cerr << "\n";
            if (!ctx.common.report_path.empty()) {
              io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
              r["subcommand"] = "theodolite";
              r["out"] = w.out_dir;
              r["options"] = sim::TheodoliteSimOptionsToJson(s);
              r["images"] = w.images;
              r["summary"] = sum.ToJson();
              cli::WriteReport(ctx.common.report_path, r);
            }
            return 0;
          }};
}

}  // namespace rk::app

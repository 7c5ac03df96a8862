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
  cli::AddOptions(c, &w, sim::TheodoliteWriteOptions::Table());
  c->add_option("--camera", p->camera_path, "Camera model JSON instead of seed 004's 1536x1536, 0.011 mm, 1500 mm");
  c->add_option("--sensor-px", p->sensor_px,
                "Square sensor of this many pixels (same pixel size and focal length, principal point centred)");
  const auto angle_budget = [c, p] {
    c->add_option("--angle-budget", p->angle_budget,
                  "seed004: seed 004 section 4's angle errors (static 5.099' as bias, dynamic 1.093' as noise; RSS "
                  "5.215')")
        ->check(CLI::IsMember({"none", "seed004"}))
        ->capture_default_str();
  };
  // Hand-registered options go just before the table option they precede in --help.
  cli::AddOptions(c, &s, sim::TheodoliteSimOptions::Table(), {{"--encoder-step-arcsec", angle_budget}});
  cli::AddOptions(c, &w.render, sim::SilhouetteRenderOptions::Table());

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
              io::Json options = sim::TheodoliteSimOptions::Table().ToJson(s);
              options.update(sim::SilhouetteRenderOptions::Table().ToJson(w.render));
              options["camera"] = camera::CameraModelToJson(s.camera);
              r["options"] = options;
              r["images"] = w.images;
              r["summary"] = sum.ToJson();
              cli::WriteReport(ctx.common.report_path, r);
            }
            return 0;
          }};
}

}  // namespace rk::app

// rk-sim attitude: attitude-camera trial of seed 001's dynamic test with truth (target with
// markers on a moving, rotating gantry, 100 mm camera on the tracking turret). Method:
// lib/sim/attitude_scenario.h, files: lib/sim/attitude_trial.h; user page docs/rk-sim.md.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "camera/camera_model.h"
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
};

int RunAttitude(AttitudeCli& c, const Context& ctx) {
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
    r["options"] = simulator.options().ToJson();
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
  cli::AddOptions(s, &c->w, sim::AttitudeTrialWriteOptions::Table());
  s->add_flag("--no-video", c->no_video, "Write truth, logs and models only (no images)");
  s->add_option("--name", c->w.name, "Trial name in trial.json (default: the folder name)");
  s->add_option("--epoch-utc", c->w.epoch_utc, "Trial epoch, ISO-8601 UTC")->capture_default_str();
  s->add_option("--camera", c->camera_path,
                "Camera model JSON (SPEC.md section 3) instead of the attitude camera (2448x2048, 3.45 um, 100 mm)");
  s->add_option("--target", c->target_path,
                "Target model JSON {\"points\": {...}} instead of the default 8-marker layout");
  const auto hide = [s, &c = *c] {
    s->add_option("--hide", c.hides, "Hide a marker: ID:START_S:DURATION_S (START from frame 0; repeatable)");
  };
  // Hand-registered options go just before the table option they precede in --help.
  cli::AddOptions(s, &c->o, sim::AttitudeSimOptions::Table(), {{"--turret-rate-hz", hide}});
  return {s, [c](const Context& ctx) { return RunAttitude(*c, ctx); }};
}

}  // namespace rk::app

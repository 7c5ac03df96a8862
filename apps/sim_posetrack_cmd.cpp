// rk-sim posetrack: 6-DOF pose measurements with truth at sample and mid-times (seed 000).
// Thin edge: CLI11 options → rk::sim::PoseTrackOptions → rk::sim::WritePoseTrack; docs/rk-sim.md.
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "geo/angles.h"
#include "io/error.h"
#include "io/json_util.h"
#include "sim/posetrack.h"
#include "sim_commands.h"

namespace rk::app {
namespace {

// rk-sim posetrack: options as given on the command line (NaN = scenario default).
struct PosetrackCli {
  rk::sim::PoseTrackWriteOptions w;
  std::string scenario = "turntable";
  double duration_s = NAN, fps = 20, t0_s = 0, noise_deg = 0.0724, noise_m = 0.5e-3, rate_deg_s = NAN,
         yaw0_deg = NAN, dropout = 0, dropout_value = 0;
  std::uint64_t seed = 1;
};

void AddPosetrackOptions(CLI::App& app, PosetrackCli* p, CLI::App** sub) {
  CLI::App* s = app.add_subcommand(
      "posetrack",
      "6-DOF pose measurements (x,y,z,yaw,pitch,roll) with truth at sample and mid-times (seed 000)");
  *sub = s;
  s->add_option("--out,-o", p->w.out_dir, "Folder to create (refused if it exists and is not empty)")
      ->required();
  s->add_flag("--force", p->w.force, "Replace an existing non-empty --out folder");
  s->add_option(
       "--scenario", p->scenario,
       "turntable (seed 000: yaw at 10 deg/s, 20 fps, 0-9 s) or head (maneuvering 6-DOF head motion)")
      ->capture_default_str();
  s->add_option("--duration", p->duration_s,
                "Length (s); samples cover [t0, t0 + duration] (default: turntable 9, head 20)");
  s->add_option("--fps", p->fps, "Sample rate (Hz)")->capture_default_str();
  s->add_option("--t0", p->t0_s, "Time of sample 0 since the epoch (s)")->capture_default_str();
  s->add_option("--seed", p->seed, "Random seed (same seed, same files)")->capture_default_str();
  s->add_option("--noise-deg", p->noise_deg, "Measurement noise std of the three angles (deg)")
      ->capture_default_str();
  s->add_option("--noise-m", p->noise_m, "Measurement noise std of x, y, z (m)")->capture_default_str();
  s->add_option("--rate-deg-s", p->rate_deg_s, "turntable: yaw rate (deg/s) (default 10)");
  s->add_option("--yaw0-deg", p->yaw0_deg, "turntable: yaw at t0 (deg) (default 20)");
  s->add_option("--dropout", p->dropout, "Probability that a measurement row is missing (all values empty)")
      ->capture_default_str();
  s->add_option("--dropout-value", p->dropout_value, "Probability that a single measured value is missing")
      ->capture_default_str();
}

int RunPosetrack(const PosetrackCli& p, const CLI::App& sub, const Context& ctx) {
  using rk::geo::DegToRad;
  rk::sim::PoseScenario scenario;
  if (!rk::sim::ParsePoseScenario(p.scenario, &scenario)) {
    throw rk::UsageError("--scenario must be 'turntable' or 'head', not '" + p.scenario + "'");
  }
  rk::sim::PoseTrackOptions o = rk::sim::DefaultPoseTrackOptions(scenario);
  if (scenario != rk::sim::PoseScenario::kTurntable) {
    for (const char* opt : {"--rate-deg-s", "--yaw0-deg"}) {
      if (sub.count(opt) > 0)
        throw rk::UsageError(std::string(opt) + " applies to --scenario turntable only");
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
  if (!ctx.common.report_path.empty()) {
    rk::io::Json r = rk::cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "posetrack";
    r["out"] = p.w.out_dir;
    r["options"] = rk::sim::PoseTrackOptionsToJson(o);
    r["summary"] = sum.ToJson();
    rk::cli::WriteReport(ctx.common.report_path, r);
  }
  return 0;
}

}  // namespace

Command AddPosetrackCommand(CLI::App& parent) {
  auto p = std::make_shared<PosetrackCli>();
  CLI::App* sub = nullptr;
  AddPosetrackOptions(parent, p.get(), &sub);
  return {sub, [p, sub](const Context& ctx) { return RunPosetrack(*p, *sub, ctx); }};
}

}  // namespace rk::app

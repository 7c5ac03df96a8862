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

// rk-sim posetrack: the library's options (bound by their tables) and the optional values whose
// defaults come from the scenario (NaN = not given).
struct PosetrackCli {
  rk::sim::PoseTrackWriteOptions w;
  rk::sim::PoseTrackOptions o;
  double duration_s = NAN, rate_deg_s = NAN, yaw0_deg = NAN;
};

void AddPosetrackOptions(CLI::App& app, PosetrackCli* p, CLI::App** sub) {
  CLI::App* s = app.add_subcommand(
      "posetrack",
      "6-DOF pose measurements (x,y,z,yaw,pitch,roll) with truth at sample and mid-times (seed 000)");
  *sub = s;
  s->add_option("--out,-o", p->w.out_dir, "Folder to create (refused if it exists and is not empty)")
      ->required();
  rk::cli::AddOptions(s, &p->w, rk::sim::PoseTrackWriteOptions::Table());
  const auto duration = [s, p] {
    s->add_option("--duration", p->duration_s,
                  "Length (s); samples cover [t0, t0 + duration] (default: turntable 9, head 20)");
  };
  const auto turntable = [s, p] {
    s->add_option("--rate-deg-s", p->rate_deg_s, "turntable: yaw rate (deg/s) (default 10)");
    s->add_option("--yaw0-deg", p->yaw0_deg, "turntable: yaw at t0 (deg) (default 20)");
  };
  // Hand-registered options go just before the table option they precede in --help.
  rk::cli::AddOptions(s, &p->o, rk::sim::PoseTrackOptions::Table(), {{"--fps", duration}, {"--dropout", turntable}});
}

int RunPosetrack(const PosetrackCli& p, const CLI::App& sub, const Context& ctx) {
  using rk::geo::DegToRad;
  rk::sim::PoseTrackOptions o = p.o;
  if (o.scenario != rk::sim::PoseScenario::kTurntable) {
    for (const char* opt : {"--rate-deg-s", "--yaw0-deg"}) {
      if (sub.count(opt) > 0)
        throw rk::UsageError(std::string(opt) + " applies to --scenario turntable only");
    }
  }
  o.duration_s = sub.count("--duration") > 0 ? p.duration_s : rk::sim::DefaultPoseTrackOptions(o.scenario).duration_s;
  if (sub.count("--rate-deg-s") > 0) o.rate_rad_s = DegToRad(p.rate_deg_s);
  if (sub.count("--yaw0-deg") > 0) o.yaw0_rad = DegToRad(p.yaw0_deg);
  std::string why;
  if (!o.Check(&why)) throw rk::UsageError(why);
  if (!p.w.Check(&why)) throw rk::UsageError(why);
  const rk::sim::PoseTrackSimulator sim(o);
  const rk::sim::PoseTrackSummary sum = rk::sim::WritePoseTrack(sim, p.w);
  if (!ctx.common.report_path.empty()) {
    rk::io::Json r = rk::cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "posetrack";
    r["out"] = p.w.out_dir;
    r["options"] = o.ToJson();
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

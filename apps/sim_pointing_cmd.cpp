// rk-sim pointing: a station-calibration session with truth (issue 17): turret log, image points of landmarks
// and stars, the nominal camera, and the true pointing model and camera. Thin edge: CLI11 options →
// rk::sim::PointingSimOptions → rk::sim::SimulatePointingSession, WritePointingTrial; docs/rk-sim.md.
#include <memory>
#include <string>

#include "geo/angles.h"
#include "io/error.h"
#include "io/json_util.h"
#include "sim/pointing_scenario.h"
#include "sim/pointing_trial.h"
#include "station_option.h"
#include "target/calibration_targets.h"
#include "sim_commands.h"

namespace rk::app {
namespace {

struct PointingSimCli {
  rk::sim::PointingSimOptions o;
  std::string out, station;
  bool force = false;
};

int RunPointingSim(PointingSimCli& p, const Context& ctx) {
  if (p.out.empty() || p.out == "-") throw UsageError("--out must name a folder");
  if (!p.station.empty()) {
    const rk::geo::Geodetic g = rk::cli::ParseStationOption(p.station);
    p.o.lat_deg = g.lat_deg;
    p.o.lon_deg = g.lon_deg;
    p.o.h_m = g.h_m;
  }
  const rk::sim::PointingSession s = rk::sim::SimulatePointingSession(p.o);
  const rk::sim::PointingTrialSummary sum = rk::sim::WritePointingTrial(p.o, s, p.out, p.force);
  if (!ctx.common.report_path.empty()) {
    io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "pointing";
    r["out"] = p.out;
    r["options"] = p.o.ToJson();
    r["summary"] = sum.ToJson();
    cli::WriteReport(ctx.common.report_path, r);
  }
  return 0;
}

}  // namespace

Command AddPointingCommand(CLI::App& app) {
  auto p = std::make_shared<PointingSimCli>();
  CLI::App* s = app.add_subcommand(
      "pointing",
      "Station-calibration session with truth: turret with a known pointing model slewing between landmarks and "
      "stars, camera with mount, focal error and latency; image points, turret log, target files, truth");
  s->add_option("--out,-o", p->out, "Folder to create (refused if it exists and is not empty)")->required();
  s->add_flag("--force", p->force, "Replace an existing output folder");
  s->add_option("--epoch-utc", p->o.epoch_utc, "UTC of t_s = 0 (ISO-8601)")->capture_default_str();
  s->add_option("--station", p->station, "Station WGS-84 position LAT,LON,H (deg, deg, m); default 32.5,-106.6,1300");
  rk::cli::AddOptions(s, &p->o, rk::sim::PointingSimOptions::Table());
  return {s, [p](const Context& ctx) { return RunPointingSim(*p, ctx); }};
}

}  // namespace rk::app

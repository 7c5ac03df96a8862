// rk-sim radar: two mobile radars with biases, noise, clutter and missed detections observing
// common targets (seed 002 scenarios 1–3). Thin edge: CLI11 options → rk::sim::RadarSimOptions →
// rk::sim::WriteRadarTrial; docs/rk-sim.md.
#include <cmath>
#include <memory>
#include <string>

#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/json_util.h"
#include "sim/radar_scenario.h"
#include "sim_commands.h"

namespace rk::app {
namespace {

struct RadarCli {
  rk::sim::RadarSimOptions o;
  rk::sim::RadarTrialWriteOptions w;
  std::string origin = "25,110,0", index_unit = "second", names = "a,b";
  double attitude_noise_deg = 0, clutter_margin_deg = 5;
};

int RunRadar(RadarCli& p, const Context& ctx) {
  rk::sim::RadarSimOptions o = p.o;
  const std::vector<std::string> org = io::SplitList(p.origin);
  if (org.size() != 3) throw UsageError("--origin: give lat_deg,lon_deg,h_m");
  double v[3];
  for (int i = 0; i < 3; ++i) {
    try {
      std::size_t used = 0;
      v[i] = std::stod(org[i], &used);
      if (used != org[i].size() || !std::isfinite(v[i])) throw std::invalid_argument(org[i]);
    } catch (const std::exception&) {
      throw UsageError("--origin: '" + org[i] + "' is not a number");
    }
  }
  o.origin_lat_deg = v[0];
  o.origin_lon_deg = v[1];
  o.origin_h_m = v[2];
  o.index_unit = p.index_unit == "second" ? rk::sim::RadarIndexUnit::kSecond : rk::sim::RadarIndexUnit::kStep;
  const std::vector<std::string> names = io::SplitList(p.names);
  if (names.size() != 2) throw UsageError("--names: give two radar names, e.g. a,b");
  o.names = {names[0], names[1]};
  o.attitude_noise_rad = geo::DegToRad(p.attitude_noise_deg);
  o.clutter_margin_rad = geo::DegToRad(p.clutter_margin_deg);
  std::string why;
  if (!o.Check(&why)) throw UsageError(why);
  if (p.w.out_dir.empty() || p.w.out_dir == "-") throw UsageError("--out must name a folder");
  const rk::sim::RadarSimulator sim(o);
  const rk::sim::RadarTrialSummary sum = rk::sim::WriteRadarTrial(sim, p.w);
  if (!ctx.common.report_path.empty()) {
    io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "radar";
    r["out"] = p.w.out_dir;
    r["options"] = rk::sim::RadarSimOptionsToJson(o);
    r["summary"] = sum.ToJson();
    cli::WriteReport(ctx.common.report_path, r);
  }
  return 0;
}

}  // namespace

Command AddRadarCommand(CLI::App& app) {
  auto p = std::make_shared<RadarCli>();
  CLI::App* s = app.add_subcommand(
      "radar",
      "Two mobile radars with range/azimuth/elevation and platform attitude biases observing common targets, "
      "with clutter and missed detections (seed 002 scenarios 1-3): plots, nav, truth");
  s->add_option("--out,-o", p->w.out_dir, "Folder to create (refused if it exists and is not empty)")->required();
  s->add_flag("--force", p->w.force, "Replace an existing non-empty --out folder");
  s->add_option("--scenario", p->o.scenario,
                "1 (attitude rates 2e-3 rad/s), 2 (slow attitude: 8e-4 rad/s), 3 (scenario 1 + "
                "Poisson clutter, mean 5 per radar per scan)")
      ->check(CLI::Range(1, 3))
      ->capture_default_str();
  s->add_option("--steps", p->o.steps, "Scans per radar")->capture_default_str();
  s->add_option("--dt", p->o.dt_s, "Scan interval (s)")->capture_default_str();
  s->add_option("--t0", p->o.t0_s, "Time of scan 0 since the epoch (s)")->capture_default_str();
  s->add_option("--targets", p->o.targets, "Number of targets (the first five are the paper's; more are random)")
      ->capture_default_str();
  s->add_option("--clutter", p->o.clutter_rate,
                "Mean clutter plots per radar per scan (Poisson); default 5 for scenario 3, else 0");
  s->add_option("--pd", p->o.detection_probability, "Detection probability of each target per scan")
      ->capture_default_str();
  s->add_option("--seed", p->o.seed, "Random seed (same seed, same files)")->capture_default_str();
  s->add_option("--origin", p->origin, "WGS-84 origin of the common ENU frame: lat_deg,lon_deg,h_m")
      ->capture_default_str();
  s->add_option("--time-offset-b", p->o.time_offset_b_s, "Radar b scans this many seconds after radar a")
      ->capture_default_str();
  s->add_option("--nav-rate", p->o.nav_rate_hz, "Nav log rate (Hz); 0 = nav rows at the plot times")
      ->capture_default_str();
  s->add_option("--attitude-noise-deg", p->attitude_noise_deg, "1-sigma noise of the nav attitude angles (deg)")
      ->capture_default_str();
  s->add_option("--index-unit", p->index_unit,
                "Reading of k in the paper's platform motion s(k) and attitudes v(k): second (k = t - t0 in s, the paper's m/s and rad/s) or step (k = scan index)")
      ->check(CLI::IsMember({"step", "second"}))
      ->capture_default_str();
  s->add_option("--clutter-margin-m", p->o.clutter_margin_m, "Clutter box margin in range around the targets (m)")
      ->capture_default_str();
  s->add_option("--clutter-margin-deg", p->clutter_margin_deg,
                "Clutter box margin in azimuth and elevation around the targets (deg)")
      ->capture_default_str();
  s->add_option("--names", p->names, "The two radar names, as written in the files")->capture_default_str();
  return {s, [p](const Context& ctx) { return RunRadar(*p, ctx); }};
}

}  // namespace rk::app

// rk-sim radar: two mobile radars with biases, noise, clutter and missed detections observing
// common targets (seed 002 scenarios 1–3). Thin edge: CLI11 options → rk::sim::RadarSimOptions →
// rk::sim::WriteRadarTrial; docs/rk-sim.md.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

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
  std::string origin = "25,110,0", names = "a,b";
  std::string two_d;                  // --2d: radar names, empty = the second radar
  CLI::Option* two_d_opt = nullptr;
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
  const std::vector<std::string> names = io::SplitList(p.names);
  if (names.size() != 2) throw UsageError("--names: give two radar names, e.g. a,b");
  o.names = {names[0], names[1]};
  if (p.two_d_opt != nullptr && p.two_d_opt->count() > 0) {
    const std::vector<std::string> flat = io::SplitList(p.two_d.empty() ? o.names[1] : p.two_d);
    for (const std::string& n : flat) {
      if (n == o.names[0]) {
        o.two_d[0] = true;
      } else if (n == o.names[1]) {
        o.two_d[1] = true;
      } else {
        throw UsageError("--2d: '" + n + "' is not a radar name (" + o.names[0] + "," + o.names[1] + ")");
      }
    }
  }
  std::string why;
  if (!o.Check(&why)) throw UsageError(why);
  if (p.w.out_dir.empty() || p.w.out_dir == "-") throw UsageError("--out must name a folder");
  const rk::sim::RadarSimulator sim(o);
  const rk::sim::RadarTrialSummary sum = rk::sim::WriteRadarTrial(sim, p.w);
  if (!ctx.common.report_path.empty()) {
    io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "radar";
    r["out"] = p.w.out_dir;
    r["options"] = o.ToJson();
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
  rk::cli::AddOptions(s, &p->w, rk::sim::RadarTrialWriteOptions::Table());
  const auto clutter = [s, &p = *p] {
    s->add_option("--clutter", p.o.clutter_rate,
                  "Mean clutter plots per radar per scan (Poisson); default 5 for scenario 3, else 0");
  };
  const auto origin = [s, &p = *p] {
    s->add_option("--origin", p.origin, "WGS-84 origin of the common ENU frame: lat_deg,lon_deg,h_m")
        ->capture_default_str();
  };
  // Hand-registered options go just before the table option they precede in --help.
  rk::cli::AddOptions(s, &p->o, rk::sim::RadarSimOptions::Table(), {{"--pd", clutter}, {"--time-offset-b", origin}});
  s->add_option("--names", p->names, "The two radar names, as written in the files")->capture_default_str();
  p->two_d_opt = s->add_option("--2d", p->two_d,
                               "2-D radars: their plots are written with an empty el_deg (truth unchanged); "
                               "a list of radar names, or alone for the second radar")
                     ->expected(0, 1);
  return {s, [p](const Context& ctx) { return RunRadar(*p, ctx); }};
}

}  // namespace rk::app

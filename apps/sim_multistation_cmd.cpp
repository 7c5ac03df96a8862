// rk-sim multistation: two to four stations observing one target, each with its own frame times, noisy
// angles (± range) with their 1σ columns; stations.json and truth for rk-intersect (issue 18); with --video
// also a multi-station trial folder for rk-run (rendered frames per station). Thin edge:
// CLI11 options → rk::sim::MultistationOptions → rk::sim::WriteMultistationTrial; docs/rk-sim.md.
#include <memory>
#include <string>

#include "io/error.h"
#include "sim/multistation_scenario.h"
#include "sim_commands.h"

namespace rk::app {
namespace {

struct MultistationCli {
  rk::sim::MultistationOptions o;
  std::string out;
  bool force = false;
};

int RunMultistation(const MultistationCli& p, const Context& ctx) {
  std::string why;
  if (!p.o.Check(&why)) throw UsageError(why);
  if (p.out.empty() || p.out == "-") throw UsageError("--out must name a folder");
  const rk::sim::MultistationScenario sim(p.o);
  rk::sim::WriteMultistationTrial(sim, p.out, p.force);
  if (!ctx.common.report_path.empty()) {
    io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "multistation";
    r["out"] = p.out;
    r["options"] = p.o.ToJson();
    io::Json st = io::Json::object();
    for (const auto& s : sim.stations()) {
      st[s.name] = {{"rows", s.t_s.size()}, {"has_range", s.has_range}, {"time_offset_s", s.time_offset_s}};
    }
    r["summary"] = {{"stations", st}};
    cli::WriteReport(ctx.common.report_path, r);
  }
  return 0;
}

}  // namespace

Command AddMultistationCommand(CLI::App& app) {
  auto p = std::make_shared<MultistationCli>();
  CLI::App* s = app.add_subcommand(
      "multistation",
      "Two to four stations kilometres apart observing a ballistic arc, a crossing aircraft or a climbing turn: "
      "each station's located.csv (own frame times and clock, noisy angles with 1 sigma, optional range), "
      "stations.json, truth.csv; with "
      "--video also the rendered trial rk-run runs (trial.json, frames, turret logs)");
  s->add_option("--out,-o", p->out, "Folder to create (refused if it exists and is not empty)")->required();
  s->add_flag("--force", p->force, "Replace an existing output folder");
  rk::cli::AddOptions(s, &p->o, rk::sim::MultistationOptions::Table());
  s->add_option("--time-offsets", p->o.time_offsets,
                "Station clock offsets (s), e.g. s2:0.0043,s3:-0.0117: that station's t_s reads the true time minus "
                "the offset (SPEC.md section 7: t_s + offset is the common clock); others 0");
  return {s, [p](const Context& ctx) { return RunMultistation(*p, ctx); }};
}

}  // namespace rk::app

// rk-sim points: a non-cooperative target with exact image truth for rk-extract points (issue 31).
// Thin edge: CLI11 options → rk::sim::PointsSceneOptions → rk::sim::WritePointsTrial; docs/rk-sim.md.
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/error.h"
#include "io/json_util.h"
#include "sim/points_scene.h"
#include "sim_commands.h"

namespace rk::app {
namespace {

struct PointsSimCli {
  rk::sim::PointsSceneOptions o;
  rk::sim::PointsWriteOptions w;
  std::string out;
  bool no_clouds = false;
  std::vector<std::string> reseeds;
};

// "ID:FRAME" → (id, frame).
std::pair<std::string, int> ParseReseed(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) {
    throw UsageError("--reseed must be ID:FRAME, got '" + text + "'");
  }
  std::size_t used = 0;
  int frame = -1;
  try {
    frame = std::stoi(text.substr(colon + 1), &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() - colon - 1 || frame < 0) throw UsageError("--reseed must be ID:FRAME, got '" + text + "'");
  return {text.substr(0, colon), frame};
}

int RunPointsSim(PointsSimCli p, const Context& ctx) {
  if (p.out.empty() || p.out == "-") throw UsageError("--out must name a folder");
  p.o.clouds = !p.no_clouds;
  for (const std::string& r : p.reseeds) p.w.reseeds.push_back(ParseReseed(r));
  std::string why;
  if (!p.o.Check(&why)) throw UsageError(why);
  if (rk::cli::ShowProgress(ctx.common)) {
    p.w.progress = [&ctx](int done, int total) {
      if (done % 10 == 0 || done == total) {
        std::cerr << "\r" << ctx.tool << ": frame " << done << "/" << total << (done == total ? "\n" : "") << std::flush;
      }
    };
  }
  const rk::sim::PointsTrialSummary sum = rk::sim::WritePointsTrial(p.o, p.out, p.w);
  if (!ctx.common.report_path.empty()) {
    io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "points";
    r["out"] = p.out;
    r["options"] = p.o.ToJson();
    r["summary"] = sum.ToJson();
    cli::WriteReport(ctx.common.report_path, r);
  }
  return 0;
}

}  // namespace

Command AddPointsCommand(CLI::App& app) {
  auto p = std::make_shared<PointsSimCli>();
  CLI::App* s = app.add_subcommand(
      "points",
      "Non-cooperative target with exact image truth for rk-extract points: aircraft silhouette with quadrant, "
      "circle, lamp, dark-spot and textured markers, sky gradient, clouds in front, PSF, motion blur, noise");
  s->add_option("--out,-o", p->out, "Folder to create (refused if it exists and is not empty)")->required();
  s->add_flag("--force", p->w.force, "Replace an existing output folder");
  rk::cli::AddOptions(s, &p->o, rk::sim::PointsSceneOptions::Table());
  s->add_flag("--no-clouds", p->no_clouds, "No clouds (nothing hidden, no look-alike shown)");
  s->add_option("--reseed", p->reseeds,
                "Extra seeds.csv row: ID:FRAME re-seeds that marker at its truth at that frame; repeatable");
  return {s, [p](const Context& ctx) { return RunPointsSim(*p, ctx); }};
}

}  // namespace rk::app

// rk-extract points: user-seeded points on a non-cooperative target tracked through a recording, each by
// the method its seed names (correlation, centroid-dark, centroid-bright, quadrant, circle). Method:
// lib/extract/points_tracker.h, point_measure.h; user page docs/rk-extract.md "points".
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "extract/points_run.h"
#include "extract_commands.h"
#include "formats/seeds.h"
#include "io/cli.h"
#include "io/csv.h"
#include "io/csv_stream.h"
#include "io/error.h"

namespace rk::app {
namespace {

struct PointsArgs {
  extract::PointsTrackOptions opt;
  VideoInputArgs in;
  std::string out_path, seeds_path;
};

int RunPointsCmd(const PointsArgs& a, const Context& ctx) {
  std::string why;
  if (!a.opt.Check(&why)) throw UsageError(why);
  a.in.CheckFrameTimes();
  std::vector<cli::NamedPath> inputs = a.in.Inputs();
  inputs.push_back({"--seeds", a.seeds_path});
  cli::CheckStreams(ctx.common, inputs, {{"-o", a.out_path}});
  const formats::Seeds seeds = formats::ReadSeeds(a.seeds_path);
  const formats::FrameClock clock = a.in.Clock();
  const bool progress = cli::ShowProgress(ctx.common);
  cli::ProgressMeter meter(ctx.tool, "frames", VideoInputArgs::ExpectedFrames(clock), progress);
  // Rows go out as they are made when -o is stdout (docs/conventions.md "Streaming"), from the last seed
  // frame on (a seed past the end or outside the image is an error before any row).
  io::CsvWriter csv = extract::PointsTrackCsv({}, seeds);
  io::CsvStream out(csv, a.out_path);
  const extract::PointsRunResult res = extract::RunPoints(
      a.in.videos, clock, seeds, a.opt, [&](std::int64_t n) { meter.Update(n); },
      [&](const extract::PointsFrameResult& r) {
        extract::AppendPointsTrackRows(&csv, r, seeds);
        out.Flush();
      });
  meter.Finish();
  const io::RunSummary summary = res.Summary(a.opt);
  cli::WarnAll(ctx.tool, ctx.common, summary);
  out.Finish();
  if (!ctx.common.report_path.empty()) {
    io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    a.in.AddReportInputs(&rep);
    cli::AddReportInput(&rep, "seeds", a.seeds_path);
    rep["subcommand"] = "points";
    rep["output"] = a.out_path;
    AddReportTimes(&rep, res.frames, res.wall_s, res.extract_s);
    rep["frame_times"] = a.in.FrameTimesJson();
    cli::WriteReport(ctx.common.report_path, rep, summary);
  }
  if (progress) {
    std::cerr << ctx.tool << ": " << res.frames << " frames, " << seeds.ids.size() << " points\n";
  }
  return 0;
}

}  // namespace

Command AddPointsCommand(CLI::App& parent) {
  auto a = std::make_shared<PointsArgs>();
  CLI::App* s = parent.add_subcommand(
      "points",
      "User-seeded points on any target tracked through the recording, each by its seed's method: correlation "
      "(affine least-squares matching to the seed's patch), centroid-dark/centroid-bright (blob centroid), "
      "quadrant (checkerboard saddle fit) or circle (rim fit); Singer prediction, re-acquisition after an "
      "occlusion, look-alikes refused by their surroundings. Writes frame,t_s,id,x_px,y_px,status,sigma_x_px,"
      "sigma_y_px,score (one row per frame and point id).");
  a->in.Add(s);
  s->add_option("--seeds", a->seeds_path,
                "Seeds CSV id,frame,x_px,y_px,method (+ size_px, search_px); later rows of an id re-seed it")
      ->required();
  s->add_option("-o,--output", a->out_path, "Points track CSV ('-' = stdout)")->required();
  cli::AddOptions(s, &a->opt, extract::PointsTrackOptions::Table());
  return {s, [a](const Context& ctx) { return RunPointsCmd(*a, ctx); }};
}

}  // namespace rk::app

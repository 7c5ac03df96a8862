// rk-extract features: target feature points (markers) in attitude-camera video, found by
// correlation, with ids from the target model (seed 001 §2.3). Method:
// lib/extract/features_detect.h, features_identify.h, features_tracker.h; user page
// docs/rk-extract.md.
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "extract/features_run.h"
#include "extract_commands.h"
#include "io/cli.h"
#include "io/csv.h"
#include "io/csv_stream.h"
#include "io/error.h"
#include "io/file_util.h"
#include "target/feature_model.h"

namespace rk::app {
namespace {

struct FeaturesArgs {
  extract::FeatureTrackOptions opt;
  VideoInputArgs in;
  std::string out_path, target_path;
};

int RunFeaturesCmd(const FeaturesArgs& a, const Context& ctx) {
  const extract::FeatureTrackOptions& opt = a.opt;
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  a.in.CheckFrameTimes();
  std::vector<cli::NamedPath> inputs = a.in.Inputs();
  inputs.push_back({"--target", a.target_path});
  cli::CheckStreams(ctx.common, inputs, {{"-o", a.out_path}});
  const target::FeatureModel model = target::LoadFeatureModel(a.target_path);
  const formats::FrameClock clock = a.in.Clock();
  const bool progress = cli::ShowProgress(ctx.common);
  cli::ProgressMeter meter(ctx.tool, "frames", VideoInputArgs::ExpectedFrames(clock), progress);
  // Each frame's rows go out as they are made when -o is stdout (docs/conventions.md "Streaming").
  io::CsvWriter csv = extract::FeaturePointsCsv({}, model);
  io::CsvStream out(csv, a.out_path);
  const extract::FeatureRunResult res = extract::RunFeatures(
      a.in.videos, clock, model, opt, [&](std::int64_t n) { meter.Update(n); },
      [&](const extract::FeatureFrameResult& r) {
        extract::AppendFeaturePointRows(&csv, r, model);
        out.Flush();
      });
  meter.Finish();
  const auto& s = res.summary;
  const io::RunSummary summary = res.Summary(model, opt);
  cli::WarnAll(ctx.tool, ctx.common, summary);
  out.Finish();

  if (!ctx.common.report_path.empty()) {
    io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    a.in.AddReportInputs(&rep);
    cli::AddReportInput(&rep, "target", a.target_path);
    rep["subcommand"] = "features";
    rep["output"] = a.out_path;
    AddReportTimes(&rep, res.frames, res.wall_s, res.extract_s);
    rep["frame_times"] = a.in.FrameTimesJson();
    cli::WriteReport(ctx.common.report_path, rep, summary);
  }
  if (progress) {
    std::cerr << ctx.tool << ": " << res.frames << " frames, " << s.frames_with_4 << " with >= 4 markers, "
              << s.acquisitions_ok << " identifications\n";
  }
  return 0;
}

}  // namespace

Command AddFeaturesCommand(CLI::App& parent) {
  auto a = std::make_shared<FeaturesArgs>();
  CLI::App* s = parent.add_subcommand(
      "features",
      "Target feature points (markers) in attitude-camera video: correlation search and least-squares "
      "correlation, identities from the target model (affine-camera hypotheses) kept by tracking. Writes "
      "frame,t_s,id,x_px,y_px,status,sigma_px,ncc,radius_px (one row per frame and marker id).");
  a->in.Add(s);
  s->add_option("--target", a->target_path, "Target model JSON {\"points\": {\"<id>\": [x, y, z], ...}} (body m)")
      ->required();
  s->add_option("-o,--output", a->out_path, "Image points CSV ('-' = stdout)")->required();
  cli::AddOptions(s, &a->opt, extract::FeatureTrackOptions::Table());
  return {s, [a](const Context& ctx) { return RunFeaturesCmd(*a, ctx); }};
}

}  // namespace rk::app

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
  std::vector<std::string> inputs = a.in.Inputs();
  inputs.push_back(a.target_path);
  io::CheckOutputNotInput(a.out_path, inputs);
  if (!ctx.common.report_path.empty()) {
    io::CheckOutputNotInput(ctx.common.report_path, inputs);
    if (io::IsStdStream(ctx.common.report_path) && io::IsStdStream(a.out_path)) {
      throw UsageError("--report and -o cannot both be stdout");
    }
  }
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
  if (s.ambiguous > 0) {
    cli::Warn(ctx.tool, ctx.common,
              std::to_string(s.ambiguous) +
                  " frames had an ambiguous identification and got no points "
                  "(a symmetric marker layout cannot be identified without tracking)");
  }
  out.Finish();

  if (!ctx.common.report_path.empty()) {
    io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    a.in.AddReportInputs(&rep);
    cli::AddReportInput(&rep, "target", a.target_path);
    rep["subcommand"] = "features";
    rep["output"] = a.out_path;
    rep["video"] = {{"width_px", res.width_px}, {"height_px", res.height_px}, {"bit_depth", res.bit_depth}};
    rep["frames"] = res.frames;
    rep["markers"] = model.size();
    io::Json st = io::Json::object();
    for (int k = 0; k < 5; ++k) st[RowStatusName(static_cast<RowStatus>(k))] = s.rows_by_status[static_cast<std::size_t>(k)];
    rep["status_counts"] = st;
    rep["acquisitions"] = {{"tried", s.acquisitions}, {"ok", s.acquisitions_ok}, {"ambiguous", s.ambiguous}};
    rep["rejected_by_constellation"] = s.rejected;
    rep["frames_with_4_points"] = s.frames_with_4;
    rep["mean_ncc"] = s.mean_ncc;
    rep["summary"] = res.SummaryJson();
    AddReportTimes(&rep, res.frames, res.wall_s, res.extract_s);
    rep["options"] = opt.ToJson();
    rep["frame_times"] = a.in.FrameTimesJson();
    cli::WriteReport(ctx.common.report_path, rep);
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

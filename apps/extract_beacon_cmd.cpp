// rk-extract beacon: IR lamp cluster track (seed 001 §2.1–2.2); method in
// lib/extract/beacon_detect.h and beacon_tracker.h, user page docs/rk-extract.md.
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "extract/beacon_run.h"
#include "extract_commands.h"
#include "io/csv.h"
#include "io/csv_stream.h"
#include "io/error.h"
#include "io/file_util.h"

namespace rk::app {
namespace {

struct BeaconArgs {
  extract::BeaconTrackOptions opt;
  VideoInputArgs in;
  std::string out_path;
  bool decode_only = false;
};

int RunBeaconCmd(const BeaconArgs& a, const Context& ctx) {
  const auto& opt = a.opt;
  const auto& common = ctx.common;
  std::string why;
  if (!opt.Check(&why)) throw rk::UsageError(why);
  if (a.decode_only) {
    const rk::extract::DecodeResult r = rk::extract::DecodeOnly(a.in.videos);
    std::cerr << ctx.tool << ": decoded " << r.frames << " frames in " << r.wall_s << " s ("
              << (r.frames ? 1e3 * r.wall_s / static_cast<double>(r.frames) : 0.0) << " ms/frame)\n";
    return 0;
  }
  if (a.out_path.empty()) throw rk::UsageError("-o/--output is required (or --decode-only)");
  a.in.CheckFrameTimes();
  rk::cli::CheckStreams(common, a.in.Inputs(), {{"-o", a.out_path}});

  const rk::formats::FrameClock clock = a.in.Clock();
  const bool progress = rk::cli::ShowProgress(common);
  rk::cli::ProgressMeter meter(ctx.tool, "frames", VideoInputArgs::ExpectedFrames(clock), progress);
  // Each frame's row goes out as it is made when -o is stdout (docs/conventions.md "Streaming").
  rk::io::CsvWriter csv = rk::extract::BeaconTrackCsv({}, 0);
  rk::io::CsvStream out(csv, a.out_path);
  const rk::extract::BeaconRunResult res = rk::extract::RunBeacon(
      a.in.videos, clock, opt, [&](std::int64_t n) { meter.Update(n); },
      [&](const rk::extract::BeaconFrameResult& r) {
        rk::extract::AppendBeaconTrackRow(&csv, r);
        out.Flush();
      });
  meter.Finish();
  out.Finish();

  const auto& s = res.summary;
  if (!common.report_path.empty()) {
    rk::io::Json rep = rk::cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    a.in.AddReportInputs(&rep);
    rep["subcommand"] = "beacon";
    rep["output"] = a.out_path;
    AddReportTimes(&rep, res.frames, res.wall_s, res.extract_s);
    rep["frame_times"] = a.in.FrameTimesJson();
    rk::cli::WriteReport(common.report_path, rep, res.Summary(opt));
  }
  if (progress) {
    std::cerr << ctx.tool << ": " << res.frames << " frames: " << s.ok << " ok, " << s.reacquired << " reacquired, "
              << s.lost << " lost, " << s.predicted << " predicted, " << s.invalid << " invalid\n";
  }
  return 0;
}

}  // namespace

Command AddBeaconCommand(CLI::App& parent) {
  auto a = std::make_shared<BeaconArgs>();
  CLI::App* beacon = parent.add_subcommand(
      "beacon",
      "Track the cooperative IR lamp cluster: grey projection, region growing, sub-pixel grey-weighted "
      "centroid (per lamp when the lamps resolve), "
      "template (NCC) validation, Singer-model Kalman prediction and gating. Writes "
      "frame,t_s,x_px,y_px,peak,area_px,status,ncc,sigma_x_px,sigma_y_px (one row per frame).");
  a->in.Add(beacon);
  beacon->add_option("-o,--output", a->out_path, "Output track CSV ('-' = stdout)");
  beacon->add_flag(
      "--decode-only", a->decode_only,
      "Only decode all frames and report their number and the time on stderr (no extraction, no output)");
  cli::AddOptions(beacon, &a->opt, extract::BeaconTrackOptions::Table());
  return {beacon, [a](const Context& ctx) { return RunBeaconCmd(*a, ctx); }};
}

}  // namespace rk::app

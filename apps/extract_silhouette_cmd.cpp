// rk-extract silhouette: nose tip and tail-rim points of a cylindrical target per frame (seed 004 §3.1,
// SPEC.md §1.1); method in lib/extract/silhouette.h, user page docs/rk-extract.md.
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "extract/silhouette_run.h"
#include "extract_commands.h"
#include "io/csv.h"
#include "io/csv_stream.h"
#include "io/error.h"
#include "io/file_util.h"

namespace rk::app {
namespace {

struct SilhouetteArgs {
  extract::SilhouetteOptions opt;
  VideoInputArgs in;
  std::string out_path;
};

}  // namespace

Command AddSilhouetteCommand(CLI::App& parent) {
  auto a = std::make_shared<SilhouetteArgs>();
  CLI::App* c = parent.add_subcommand(
      "silhouette",
      "Nose tip and the two ends of the tail-rim diameter of a cylindrical target against the sky, sub-pixel, "
      "per frame (seed 004): sky plane, coverage profiles across the image axis, side-line, tail-ellipse and "
      "nose-cone fits. Writes frame,t_s,id,x_px,y_px,status,detail,width_px,length_px (ids nose, tail1, tail2).");
  a->in.Add(c);
  c->add_option("-o,--output", a->out_path, "Output image points CSV ('-' = stdout)")->required();
  cli::AddOptions(c, &a->opt, extract::SilhouetteOptions::Table());

  return {c, [a](const Context& ctx) -> int {
            std::string why;
            if (!a->opt.Check(&why)) throw UsageError(why);
            a->in.CheckFrameTimes();
            cli::CheckStreams(ctx.common, a->in.Inputs(), {{"-o", a->out_path}});
            const formats::FrameClock clock = a->in.Clock();
            const bool progress = cli::ShowProgress(ctx.common);
            cli::ProgressMeter meter(ctx.tool, "frames", VideoInputArgs::ExpectedFrames(clock), progress);
            // Each frame's rows go out as they are made when -o is stdout (docs/conventions.md "Streaming").
            io::CsvWriter csv = extract::SilhouettePointsCsv({});
            io::CsvStream out(csv, a->out_path);
            const extract::SilhouetteRunResult res = extract::RunSilhouette(
                a->in.videos, clock, a->opt, [&](std::int64_t n) { meter.Update(n); },
                [&](const extract::SilhouetteFrameRow& r) {
                  extract::AppendSilhouettePointRows(&csv, r);
                  out.Flush();
                });
            meter.Finish();
            out.Finish();
            const io::RunSummary summary = res.Summary(a->opt);
            cli::WarnAll(ctx.tool, ctx.common, summary);
            if (!ctx.common.report_path.empty()) {
              io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
              a->in.AddReportInputs(&rep);
              rep["subcommand"] = "silhouette";
              rep["output"] = a->out_path;
              rep["time_s"] = {{"total", res.wall_s}, {"extraction", res.extract_s}};
              cli::WriteReport(ctx.common.report_path, rep, summary);
            }
            if (progress) {
              const std::int64_t ok = res.by_status[static_cast<std::size_t>(extract::SilhouetteStatus::kOk)];
              std::cerr << ctx.tool << ": " << res.frames << " frames: " << ok << " with points, " << res.frames - ok
                        << " without\n";
            }
            return 0;
          }};
}

}  // namespace rk::app

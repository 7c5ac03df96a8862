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
#include "io/error.h"
#include "io/file_util.h"

namespace rk::app {
namespace {

struct SilhouetteArgs {
  extract::SilhouetteOptions opt;
  std::vector<std::string> videos;
  std::string frames_path, out_path;
  io::BadRows bad_rows = io::BadRows::kError;  // --frames rows
  std::optional<double> fps, t0;
};

}  // namespace

Command AddSilhouetteCommand(CLI::App& parent) {
  auto a = std::make_shared<SilhouetteArgs>();
  CLI::App* c = parent.add_subcommand(
      "silhouette",
      "Nose tip and the two ends of the tail-rim diameter of a cylindrical target against the sky, sub-pixel, "
      "per frame (seed 004): sky plane, coverage profiles across the image axis, side-line, tail-ellipse and "
      "nose-cone fits. Writes frame,t_s,id,x_px,y_px,status,detail,width_px,length_px (ids nose, tail1, tail2).");
  c->add_option("--video", a->videos,
                "Video file (ffmpeg-readable, 8/16-bit mono) or image-sequence pattern dir/%06d.png; repeat for "
                "segments, read in the order given")
      ->required();
  auto* o_frames = c->add_option("--frames", a->frames_path, "Frame times CSV with columns frame,t_s");
  auto* o_fps = c->add_option("--fps", a->fps, "Constant frame rate (Hz): t = t0 + frame / fps");
  c->add_option("--t0", a->t0, "Time of frame 0 (s) with --fps [default 0]")->needs(o_fps);
  o_frames->excludes(o_fps);
  cli::AddBadRowsOption(c, &a->bad_rows);
  c->add_option("-o,--output", a->out_path, "Output image points CSV ('-' = stdout)")->required();
  c->add_option("--k-detect", a->opt.k_detect, "Detection threshold in sky-noise sigmas")->capture_default_str();
  c->add_option("--min-area", a->opt.min_area_px, "Smallest target region (px)")->capture_default_str();
  c->add_option("--border", a->opt.border_px, "Frame border band used for the sky plane (px)")->capture_default_str();
  c->add_option("--psf-sigma", a->opt.psf_sigma_px, "Optics blur sigma assumed for the margins (px)")
      ->capture_default_str();
  c->add_option("--min-width", a->opt.min_width_px, "Narrower bodies are not measured (px)")->capture_default_str();
  c->add_option("--min-length-ratio", a->opt.min_length_ratio,
                "Image length / width below this (near tail chase) is not measured")
      ->capture_default_str();

  return {c, [a](const Context& ctx) -> int {
            std::string why;
            if (!a->opt.Check(&why)) throw UsageError(why);
            if (a->frames_path.empty() && !a->fps)
              throw UsageError("give the frame times: --frames F.csv or --fps HZ [--t0 S]");
            std::vector<std::string> inputs = a->videos;
            if (!a->frames_path.empty()) inputs.push_back(a->frames_path);
            io::CheckOutputNotInput(a->out_path, inputs);
            if (!ctx.common.report_path.empty()) io::CheckOutputNotInput(ctx.common.report_path, inputs);
            const extract::FrameClock clock = a->frames_path.empty()
                                                  ? extract::FrameClock::FromRate(*a->fps, a->t0.value_or(0.0))
                                                  : extract::FrameClock::FromCsv(a->frames_path, a->bad_rows);
            const bool progress = cli::ShowProgress(ctx.common);
            const extract::SilhouetteRunResult res =
                extract::RunSilhouette(a->videos, clock, a->opt, [&](std::int64_t n) {
                  if (progress) std::cerr << "\r" << ctx.tool << ": " << n << " frames" << std::flush;
                });
            if (progress) std::cerr << "\r";
            extract::SilhouettePointsCsv(res.rows).Write(a->out_path);
            using S = extract::SilhouetteStatus;
            const auto n = [&](S s) { return res.by_status[static_cast<std::size_t>(s)]; };
            const std::int64_t bad = res.frames - n(S::kOk);
            if (bad > 0) {
              cli::Warn(ctx.tool, ctx.common,
                        std::to_string(bad) + " of " + std::to_string(res.frames) +
                            " frames without points (not_found " + std::to_string(n(S::kNotFound)) +
                            ", touches_border " + std::to_string(n(S::kTouchesBorder)) + ", too_small " +
                            std::to_string(n(S::kTooSmall)) + ", bad_fit " + std::to_string(n(S::kBadFit)) +
                            ")");
            }
            if (!ctx.common.report_path.empty()) {
              io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
              for (std::size_t i = 0; i < a->videos.size(); ++i)
                cli::AddReportInput(&rep, "video_" + std::to_string(i), a->videos[i]);
              if (!a->frames_path.empty()) cli::AddReportInput(&rep, "frames", a->frames_path);
              rep["subcommand"] = "silhouette";
              rep["output"] = a->out_path;
              rep["video"] = {{"width_px", res.width_px}, {"height_px", res.height_px}, {"bit_depth", res.bit_depth}};
              rep["frames"] = res.frames;
              io::Json counts = io::Json::object();
              for (int s = 0; s < 5; ++s)
                counts[extract::SilhouetteStatusName(static_cast<S>(s))] = res.by_status[static_cast<std::size_t>(s)];
              rep["status_counts"] = counts;
              rep["summary"] = res.SummaryJson();
              rep["time_s"] = {{"total", res.wall_s}, {"extraction", res.extract_s}};
              rep["options"] = {{"k_detect", a->opt.k_detect},     {"min_area_px", a->opt.min_area_px},
                                {"border_px", a->opt.border_px},   {"psf_sigma_px", a->opt.psf_sigma_px},
                                {"min_width_px", a->opt.min_width_px}, {"min_length_ratio", a->opt.min_length_ratio}};
              cli::WriteReport(ctx.common.report_path, rep);
            }
            return 0;
          }};
}

}  // namespace rk::app

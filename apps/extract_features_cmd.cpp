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
#include "io/error.h"
#include "io/file_util.h"
#include "target/feature_model.h"

namespace rk::app {
namespace {

struct FeaturesArgs {
  extract::FeatureTrackOptions opt;
  std::vector<std::string> videos;
  std::string frames_path, out_path, target_path, polarity = "bright";
  io::BadRows bad_rows = io::BadRows::kError;  // --frames rows
  std::optional<double> fps, t0;
};

int RunFeaturesCmd(const FeaturesArgs& a, const Context& ctx) {
  extract::FeatureTrackOptions opt = a.opt;
  if (a.polarity != "bright" && a.polarity != "dark") throw UsageError("--polarity must be bright or dark");
  opt.detect.dark = a.polarity == "dark";
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  if (a.frames_path.empty() && !a.fps) throw UsageError("give the frame times: --frames F.csv or --fps HZ [--t0 S]");
  std::vector<std::string> inputs = a.videos;
  inputs.push_back(a.target_path);
  if (!a.frames_path.empty()) inputs.push_back(a.frames_path);
  io::CheckOutputNotInput(a.out_path, inputs);
  if (!ctx.common.report_path.empty()) {
    io::CheckOutputNotInput(ctx.common.report_path, inputs);
    if (io::IsStdStream(ctx.common.report_path) && io::IsStdStream(a.out_path)) {
      throw UsageError("--report and -o cannot both be stdout");
    }
  }
  const target::FeatureModel model = target::LoadFeatureModel(a.target_path);
  const extract::FrameClock clock = a.frames_path.empty() ? extract::FrameClock::FromRate(*a.fps, a.t0.value_or(0.0))
                                                          : extract::FrameClock::FromCsv(a.frames_path, a.bad_rows);
  const bool progress = cli::ShowProgress(ctx.common);
  const extract::FeatureRunResult res =
      extract::RunFeatures(a.videos, clock, model, opt, [&](std::int64_t n) {
        if (progress) std::cerr << "\r" << ctx.tool << ": " << n << " frames" << std::flush;
      });
  if (progress) std::cerr << "\r";
  const auto& s = res.summary;
  if (s.ambiguous > 0) {
    cli::Warn(ctx.tool, ctx.common,
              std::to_string(s.ambiguous) +
                  " frames had an ambiguous identification and got no points "
                  "(a symmetric marker layout cannot be identified without tracking)");
  }
  extract::FeaturePointsCsv(res.rows, model).Write(a.out_path);

  if (!ctx.common.report_path.empty()) {
    io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    for (std::size_t i = 0; i < a.videos.size(); ++i) cli::AddReportInput(&rep, "video_" + std::to_string(i), a.videos[i]);
    cli::AddReportInput(&rep, "target", a.target_path);
    if (!a.frames_path.empty()) cli::AddReportInput(&rep, "frames", a.frames_path);
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
    rep["time_s"] = {{"total", res.wall_s}, {"extraction", res.extract_s}};
    rep["time_per_frame_ms"] = {
        {"total", res.frames ? 1e3 * res.wall_s / static_cast<double>(res.frames) : 0.0},
        {"extraction", res.frames ? 1e3 * res.extract_s / static_cast<double>(res.frames) : 0.0}};
    const auto& d = opt.detect;
    const auto& id = opt.identify;
    rep["options"] = {{"polarity", a.polarity},
                      {"min_radius_px", d.min_radius_px},
                      {"max_radius_px", d.max_radius_px},
                      {"downsample", d.downsample},
                      {"k_detect", d.k_detect},
                      {"ncc_min", d.ncc_min},
                      {"min_contrast_dn", d.min_contrast_dn},
                      {"max_candidates", d.max_candidates},
                      {"search_px", opt.search_px},
                      {"gate", opt.gate_frac},
                      {"min_track", opt.min_track},
                      {"min_identified", id.min_identified},
                      {"id_tolerance", id.tol_frac},
                      {"ambiguity_ratio", id.ambiguity_ratio}};
    rep["frame_times"] = clock.from_file() ? io::Json{{"source", "frames"}}
                                           : io::Json{{"source", "fps"}, {"fps_hz", *a.fps}, {"t0_s", a.t0.value_or(0.0)}};
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
  s->add_option("--video", a->videos,
                "Video file (ffmpeg-readable, 8/16-bit mono) or image-sequence pattern dir/%06d.png; repeat for "
                "segments, read in the order given")
      ->required();
  auto* o_frames = s->add_option("--frames", a->frames_path, "Frame times CSV with columns frame,t_s");
  auto* o_fps = s->add_option("--fps", a->fps, "Constant frame rate (Hz): t = t0 + frame / fps");
  s->add_option("--t0", a->t0, "Time of frame 0 (s) with --fps [default 0]")->needs(o_fps);
  o_frames->excludes(o_fps);
  cli::AddBadRowsOption(s, &a->bad_rows);
  s->add_option("--target", a->target_path, "Target model JSON {\"points\": {\"<id>\": [x, y, z], ...}} (body m)")
      ->required();
  s->add_option("-o,--output", a->out_path, "Image points CSV ('-' = stdout)")->required();
  auto& o = a->opt;
  s->add_option("--polarity", a->polarity, "Markers brighter (bright) or darker (dark) than their surroundings")
      ->capture_default_str();
  s->add_option("--min-radius-px", o.detect.min_radius_px, "Smallest marker image radius (px)")->capture_default_str();
  s->add_option("--max-radius-px", o.detect.max_radius_px, "Largest marker image radius (px)")->capture_default_str();
  s->add_option("--downsample", o.detect.downsample, "Full-frame detection on frames averaged down by this (1..8)")
      ->capture_default_str();
  s->add_option("--k-detect", o.detect.k_detect, "Detection threshold in noise sigmas (full-frame search)")
      ->capture_default_str();
  s->add_option("--min-contrast", o.detect.min_contrast_dn,
                "Smallest marker contrast accepted (DN); 0 = 5 noise sigmas")
      ->capture_default_str();
  s->add_option("--ncc-min", o.detect.ncc_min, "Correlation score needed to accept a marker")->capture_default_str();
  s->add_option("--max-candidates", o.detect.max_candidates, "Full-frame search keeps this many strongest blobs")
      ->capture_default_str();
  s->add_option("--search-px", o.search_px, "Search half-size around a predicted marker (px)")->capture_default_str();
  s->add_option("--gate", o.gate_frac,
                "Constellation check: a marker farther than this fraction of the smallest marker separation from "
                "the fitted affine camera is rejected")
      ->capture_default_str();
  s->add_option("--min-track", o.min_track, "Fewer tracked markers than this start a new identification")
      ->capture_default_str();
  s->add_option("--min-identified", o.identify.min_identified,
                "Markers an identification must explain (>= 5 non-planar, >= 4 planar targets)")
      ->capture_default_str();
  s->add_option("--id-tolerance", o.identify.tol_frac,
                "Identification: a marker matches a prediction within this fraction of the smallest separation")
      ->capture_default_str();
  s->add_option("--ambiguity-ratio", o.identify.ambiguity_ratio,
                "Identification refused when a different assignment fits within this factor of the best RMS")
      ->capture_default_str();
  return {s, [a](const Context& ctx) { return RunFeaturesCmd(*a, ctx); }};
}

}  // namespace rk::app

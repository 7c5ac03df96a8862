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
#include "io/error.h"
#include "io/file_util.h"

namespace rk::app {
namespace {

struct BeaconArgs {
  extract::BeaconTrackOptions opt;
  std::vector<std::string> videos;
  std::string frames_path, out_path;
  std::optional<double> fps, t0;
  bool decode_only = false;
  io::BadRows bad_rows = io::BadRows::kError;  // --frames rows
  std::string estimator = "auto";
};

}  // namespace

Command AddBeaconCommand(CLI::App& parent) {
  auto a = std::make_shared<BeaconArgs>();
  auto& opt = a->opt;
  auto& videos = a->videos;
  auto& frames_path = a->frames_path;
  auto& out_path = a->out_path;
  auto& fps = a->fps;
  auto& t0 = a->t0;
  auto& decode_only = a->decode_only;

  CLI::App* beacon = parent.add_subcommand(
      "beacon",
      "Track the cooperative IR lamp cluster: grey projection, region growing, sub-pixel grey-weighted "
      "centroid (per lamp when the lamps resolve), "
      "template (NCC) validation, Singer-model Kalman prediction and gating. Writes "
      "frame,t_s,x_px,y_px,peak,area_px,status,ncc,sigma_x_px,sigma_y_px (one row per frame).");
  beacon
      ->add_option(
          "--video", videos,
          "Video file (ffmpeg-readable, 8/16-bit mono) or image-sequence pattern dir/%06d.png; repeat for "
          "segments, read in the order given")
      ->required();
  auto* o_frames = beacon->add_option("--frames", frames_path, "Frame times CSV with columns frame,t_s");
  auto* o_fps = beacon->add_option("--fps", fps, "Constant frame rate (Hz): t = t0 + frame / fps");
  beacon->add_option("--t0", t0, "Time of frame 0 (s) with --fps [default 0]")->needs(o_fps);
  o_frames->excludes(o_fps);
  cli::AddBadRowsOption(beacon, &a->bad_rows);
  beacon->add_option("-o,--output", out_path, "Output track CSV ('-' = stdout)");
  beacon->add_flag(
      "--decode-only", decode_only,
      "Only decode all frames and report their number and the time on stderr (no extraction, no output)");
  auto& d = opt.detect;
  beacon->add_option("--k-detect", d.k_detect, "Seed threshold in noise sigmas above the local background")
      ->capture_default_str();
  beacon->add_option("--k-grow", d.k_grow, "Region-growing threshold in noise sigmas")->capture_default_str();
  beacon->add_option("--gap", d.gap_px, "Region-growing gap tolerance (px), merges the lamps")
      ->capture_default_str();
  beacon->add_option("--cluster-gap", d.cluster_gap_px, "Regions this close (px) merge into one lamp cluster")
      ->capture_default_str();
  beacon->add_option("--max-extent", d.max_extent_px, "Largest distance of a region pixel from its seed (px)")
      ->capture_default_str();
  beacon->add_option("--max-area", d.max_area_px, "Regions with more pixels are rejected")
      ->capture_default_str();
  beacon->add_option("--margin", d.margin_px, "Centroid window: region + this margin (px)")
      ->capture_default_str();
  beacon->add_option("--ring", d.ring_px, "Width of the local-background ring (px)")->capture_default_str();
  beacon->add_flag("--bg-plane", d.background_plane,
                   "Fit a background plane to the ring (for sky gradients) instead of a level");
  beacon
      ->add_option("--projection-peaks", d.projection_peaks, "Peaks per grey projection in full-frame search")
      ->capture_default_str();
  beacon->add_option("--maneuver-time", opt.maneuver_time_s, "Singer maneuver time constant 1/a (s)")
      ->capture_default_str();
  beacon->add_option("--accel-sigma", opt.accel_sigma_px_s2, "Singer RMS image acceleration (px/s^2)")
      ->capture_default_str();
  beacon->add_option("--meas-sigma", opt.meas_sigma_px, "Centroid noise assumed by the filter (px)")
      ->capture_default_str();
  beacon->add_option("--gate-sigma", opt.gate_sigma, "Search window half size in predicted sigmas")
      ->capture_default_str();
  beacon
      ->add_option("--gate-chi2", opt.gate_chi2,
                   "Mahalanobis gate (2 dof): full-frame search while tracking; a re-acquisition beyond it "
                   "restarts the filter")
      ->capture_default_str();
  beacon->add_option("--window-min", opt.min_window_px, "Smallest search window half size (px)")
      ->capture_default_str();
  beacon
      ->add_option("--window-max", opt.max_window_px,
                   "Largest search window half size (px); beyond it the whole frame is searched")
      ->capture_default_str();
  beacon->add_option("--ncc-track", opt.ncc_track, "NCC with the template needed while tracking")
      ->capture_default_str();
  beacon->add_option("--ncc-reacquire", opt.ncc_reacquire, "NCC needed to re-acquire after a loss")
      ->capture_default_str();
  beacon->add_option("--ncc-update", opt.ncc_template_update, "Template refreshed when NCC >= this")
      ->capture_default_str();
  beacon->add_option("--size-ratio", opt.size_ratio, "Candidate/template size ratio allowed, [1/r, r]")
      ->capture_default_str();
  beacon->add_option("--flux-ratio", opt.flux_ratio, "Re-acquisition: candidate/template flux ratio allowed, [1/r, r]")
      ->capture_default_str();
  beacon->add_option("--long-loss", opt.long_loss_s, "Losses this long (s): no window search, the filter restarts")
      ->capture_default_str();
  beacon->add_option("--min-flux", opt.min_flux_dn, "Acquisition: minimum flux (DN*px), 0 = any")
      ->capture_default_str();
  beacon
      ->add_option("--fill-gaps", opt.fill_gaps_s,
                   "Fill the first S seconds of a gap with the prediction (status predicted); 0 = off")
      ->capture_default_str();
  beacon
      ->add_option("--estimator", a->estimator,
                   "Position: auto (per-lamp centroids with averaged flux shares when the lamps resolve, "
                   "else the cluster centroid) or cluster (always the cluster centroid)")
      ->check(CLI::IsMember({"auto", "cluster"}))
      ->capture_default_str();

  return {beacon, [a](const Context& ctx) -> int {
            a->opt.per_lamp = a->estimator == "auto";
            const auto& opt = a->opt;
            const auto& d = opt.detect;
            const auto& videos = a->videos;
            const auto& frames_path = a->frames_path;
            const auto& out_path = a->out_path;
            const auto& fps = a->fps;
            const auto& t0 = a->t0;
            const auto& common = ctx.common;
            const int argc = ctx.argc;
            char** const argv = ctx.argv;
            std::string why;
            if (!opt.Check(&why)) throw rk::UsageError(why);
            if (a->decode_only) {
              const rk::extract::DecodeResult r = rk::extract::DecodeOnly(videos);
              std::cerr << ctx.tool << ": decoded " << r.frames << " frames in " << r.wall_s << " s ("
                        << (r.frames ? 1e3 * r.wall_s / static_cast<double>(r.frames) : 0.0)
                        << " ms/frame)\n";
              return 0;
            }
            if (out_path.empty()) throw rk::UsageError("-o/--output is required (or --decode-only)");
            if (frames_path.empty() && !fps)
              throw rk::UsageError("give the frame times: --frames F.csv or --fps HZ [--t0 S]");
            std::vector<std::string> inputs = videos;
            if (!frames_path.empty()) inputs.push_back(frames_path);
            rk::io::CheckOutputNotInput(out_path, inputs);
            if (!common.report_path.empty()) rk::io::CheckOutputNotInput(common.report_path, inputs);

            const rk::extract::FrameClock clock =
                frames_path.empty() ? rk::extract::FrameClock::FromRate(*fps, t0.value_or(0.0))
                                    : rk::extract::FrameClock::FromCsv(frames_path, a->bad_rows);
            const bool progress = rk::cli::ShowProgress(common);
            const rk::extract::BeaconRunResult res =
                rk::extract::RunBeacon(videos, clock, opt, [&](std::int64_t n) {
                  if (progress) std::cerr << "\r" << ctx.tool << ": " << n << " frames" << std::flush;
                });
            if (progress) std::cerr << "\r";
            rk::extract::BeaconTrackCsv(res.rows, res.bit_depth).Write(out_path);

            const auto& s = res.summary;
            if (!common.report_path.empty()) {
              rk::io::Json rep = rk::cli::MakeReport(ctx.tool, argc, argv);
              for (std::size_t i = 0; i < videos.size(); ++i)
                rk::cli::AddReportInput(&rep, "video_" + std::to_string(i), videos[i]);
              if (!frames_path.empty()) rk::cli::AddReportInput(&rep, "frames", frames_path);
              rep["subcommand"] = "beacon";
              rep["output"] = out_path;
              rep["video"] = {
                  {"width_px", res.width_px}, {"height_px", res.height_px}, {"bit_depth", res.bit_depth}};
              rep["frames"] = res.frames;
              rep["status_counts"] = {{"ok", s.ok},
                                      {"reacquired", s.reacquired},
                                      {"lost", s.lost},
                                      {"predicted", s.predicted},
                                      {"invalid", s.invalid}};
              rep["acquisitions"] = s.acquisitions;
              rep["full_frame_searches"] = s.full_frame_searches;
              rep["mean_ncc"] = s.mean_ncc();
              rep["summary"] = res.SummaryJson();
              rep["restarts"] = s.restarts;
              rep["centroid_estimator"] = {{"per_lamp", s.per_lamp},
                                           {"cluster", s.ok + s.reacquired - s.per_lamp}};
              rep["time_s"] = {{"total", res.wall_s}, {"extraction", res.extract_s}};
              rep["time_per_frame_ms"] = {
                  {"total", res.frames ? 1e3 * res.wall_s / static_cast<double>(res.frames) : 0.0},
                  {"extraction", res.frames ? 1e3 * res.extract_s / static_cast<double>(res.frames) : 0.0}};
              rep["options"] = {{"k_detect", d.k_detect},
                                {"k_grow", d.k_grow},
                                {"gap_px", d.gap_px},
                                {"cluster_gap_px", d.cluster_gap_px},
                                {"max_extent_px", d.max_extent_px},
                                {"max_area_px", d.max_area_px},
                                {"margin_px", d.margin_px},
                                {"ring_px", d.ring_px},
                                {"bg_plane", d.background_plane},
                                {"projection_peaks", d.projection_peaks},
                                {"maneuver_time_s", opt.maneuver_time_s},
                                {"accel_sigma_px_s2", opt.accel_sigma_px_s2},
                                {"meas_sigma_px", opt.meas_sigma_px},
                                {"gate_sigma", opt.gate_sigma},
                                {"gate_chi2", opt.gate_chi2},
                                {"window_min_px", opt.min_window_px},
                                {"window_max_px", opt.max_window_px},
                                {"ncc_track", opt.ncc_track},
                                {"ncc_reacquire", opt.ncc_reacquire},
                                {"ncc_update", opt.ncc_template_update},
                                {"size_ratio", opt.size_ratio},
                                {"flux_ratio", opt.flux_ratio},
                                {"estimator", a->estimator},
                                {"long_loss_s", opt.long_loss_s},
                                {"min_flux_dn", opt.min_flux_dn},
                                {"fill_gaps_s", opt.fill_gaps_s}};
              if (clock.from_file()) {
                rep["frame_times"] = {{"source", "frames"}};
              } else {
                rep["frame_times"] = {{"source", "fps"}, {"fps_hz", *fps}, {"t0_s", t0.value_or(0.0)}};
              }
              rk::cli::WriteReport(common.report_path, rep);
            }
            if (progress) {
              std::cerr << ctx.tool << ": " << res.frames << " frames: " << s.ok << " ok, " << s.reacquired
                        << " reacquired, " << s.lost << " lost, " << s.predicted << " predicted, "
                        << s.invalid << " invalid\n";
            }
            return 0;
          }};
}

}  // namespace rk::app

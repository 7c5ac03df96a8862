// rk-import frames: a recording's own frame times as frames.csv (SPEC.md §1.1 "Recordings", §2.1 video frame
// times with time_source, exposure_s, camera_ts_s). Method: lib/video/recording_times.h; page docs/rk-import.md.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "formats/frame_times.h"
#include "import_commands.h"
#include "io/cli.h"
#include "io/error.h"
#include "io/utc_time.h"
#include "video/recording_times.h"
#include "video/stdin_video.h"

namespace rk::app {
namespace {

struct FramesArgs {
  std::vector<std::string> videos;
  std::string epoch_utc, output;
  std::optional<double> fps;
};

int RunFrames(const FramesArgs& a, const Context& ctx) {
  video::RefuseStdinVideo(a.videos);
  if (a.fps && !(*a.fps > 0)) throw UsageError("--fps must be > 0 Hz");
  std::vector<cli::NamedPath> inputs;
  for (const std::string& v : a.videos) inputs.push_back({"--video", v});
  cli::CheckStreams(ctx.common, inputs, {{"-o", a.output}});
  video::FrameTimesOptions o;
  o.epoch_unix_s = io::ParseEpochOption(a.epoch_utc);
  o.fps_hz = a.fps;
  const video::RecordingFrameTimes times = video::ReadFrameTimes(a.videos, o);

  std::vector<formats::FrameTimeRow> rows;
  rows.reserve(times.frames.size());
  for (const video::FrameTime& f : times.frames) {
    rows.push_back({f.frame, f.t_s, video::TimeSourceName(f.source), f.exposure_s, f.camera_ts_s});
  }
  std::vector<std::string> comments;
  for (const std::string& s : times.sources) comments.push_back("times of " + s);
  comments.push_back(times.relative_to_epoch ? "t_s: seconds since the epoch" + (a.epoch_utc.empty() ? std::string() : " " + a.epoch_utc)
                                             : "t_s: seconds since the first frame");
  const io::RunSummary summary = video::FrameTimesSummary(times);
  formats::WriteFrameTimes(a.output, rows, comments);
  if (!ctx.common.report_path.empty()) {
    io::Json report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    for (std::size_t i = 0; i < a.videos.size(); ++i) cli::AddReportInput(&report, "video_" + std::to_string(i), a.videos[i]);
    report["subcommand"] = "frames";
    report["output"] = a.output;
    if (!a.epoch_utc.empty()) report["epoch_utc"] = a.epoch_utc;
    cli::WriteReport(ctx.common.report_path, report, summary);
  }
  cli::WarnAll(ctx.tool, ctx.common, summary);
  return 0;
}

}  // namespace

Command AddFramesCommand(CLI::App& app) {
  auto a = std::make_shared<FramesArgs>();
  CLI::App* sub = app.add_subcommand(
      "frames",
      "Write a recording's own frame times as frames.csv (frame,t_s,time_source,exposure_s,camera_ts_s): "
      "CINE time blocks (irig/camera), rk-capture's frames.csv (host), container times (container), else the "
      "stated rate (nominal); backwards times and gaps over 1.5 intervals are reported (docs/rk-import.md)");
  sub->add_option("--video", a->videos,
                  "Recording: Phantom .cine, Photron .mraw (or its .cihx/.cih), a video file or an image-sequence "
                  "pattern dir/%06d.png; repeat for segments, read in the order given")
      ->required();
  sub->add_option("--epoch-utc", a->epoch_utc,
                  "Trial epoch, ISO-8601 UTC: t_s of UTC-stamped frames (IRIG, camera clock) counts from it "
                  "[default: from the first frame]");
  sub->add_option("--fps", a->fps, "Frame rate (Hz) of a recording that states none (an image sequence)");
  sub->add_option("-o,--output", a->output, "Output frames CSV ('-' = stdout)")->required();
  return {sub, [a](const Context& ctx) { return RunFrames(*a, ctx); }};
}

}  // namespace rk::app

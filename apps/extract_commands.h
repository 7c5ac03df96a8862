// rk-extract's subcommands (apps/subcommand.h) and the video input options they share.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/frame_times.h"
#include "io/cli.h"
#include "io/error.h"
#include "subcommand.h"
#include "video/stdin_video.h"

namespace rk::app {

Command AddBeaconCommand(CLI::App& app);      // extract_beacon_cmd.cpp
Command AddFeaturesCommand(CLI::App& app);    // extract_features_cmd.cpp
Command AddSilhouetteCommand(CLI::App& app);  // extract_silhouette_cmd.cpp

// --video, --frames | --fps [--t0], --bad-rows: the recording and its frame times (formats/frame_times.h).
// Paths and optional values, so registered here rather than from an option table.
struct VideoInputArgs {
  std::vector<std::string> videos;
  std::string frames_path;
  std::optional<double> fps, t0;
  io::BadRows bad_rows = io::BadRows::kError;  // --frames rows

  void Add(CLI::App* app) {
    app->add_option("--video", videos,
                    "Video file (ffmpeg-readable, 8/16-bit mono) or image-sequence pattern dir/%06d.png; repeat "
                    "for segments, read in the order given. Not '-': a video is not read from stdin")
        ->required();
    auto* o_frames = app->add_option("--frames", frames_path, "Frame times CSV with columns frame,t_s");
    auto* o_fps = app->add_option("--fps", fps, "Constant frame rate (Hz): t = t0 + frame / fps");
    app->add_option("--t0", t0, "Time of frame 0 (s) with --fps [default 0]")->needs(o_fps);
    o_frames->excludes(o_fps);
    cli::AddBadRowsOption(app, &bad_rows);
  }
  // UsageError unless the frame times are given.
  void CheckFrameTimes() const {
    video::RefuseStdinVideo(videos);
    if (frames_path.empty() && !fps) throw UsageError("give the frame times: --frames F.csv or --fps HZ [--t0 S]");
  }
  // The videos, then the frames file if any.
  std::vector<cli::NamedPath> Inputs() const {
    std::vector<cli::NamedPath> inputs;
    for (const std::string& v : videos) inputs.push_back({"--video", v});
    inputs.push_back({"--frames", frames_path});
    return inputs;
  }
  formats::FrameClock Clock() const {
    return frames_path.empty() ? formats::FrameClock::FromRate(*fps, t0.value_or(0.0))
                               : formats::FrameClock::FromCsv(frames_path, bad_rows);
  }
  // Frames to process, for the progress display: the frames file's rows; 0 (unknown) with --fps.
  static std::int64_t ExpectedFrames(const formats::FrameClock& clock) { return clock.from_file() ? clock.size() : 0; }
  // The report's inputs video_<i> and frames.
  void AddReportInputs(io::Json* report) const {
    for (std::size_t i = 0; i < videos.size(); ++i) cli::AddReportInput(report, "video_" + std::to_string(i), videos[i]);
    if (!frames_path.empty()) cli::AddReportInput(report, "frames", frames_path);
  }
  // The report's "frame_times".
  io::Json FrameTimesJson() const {
    return frames_path.empty() ? io::Json{{"source", "fps"}, {"fps_hz", *fps}, {"t0_s", t0.value_or(0.0)}}
                               : io::Json{{"source", "frames"}};
  }
};

// The report's "time_s" and "time_per_frame_ms" (total and extraction).
inline void AddReportTimes(io::Json* report, std::int64_t frames, double wall_s, double extract_s) {
  const auto per_frame_ms = [&](double s) { return frames ? 1e3 * s / static_cast<double>(frames) : 0.0; };
  (*report)["time_s"] = {{"total", wall_s}, {"extraction", extract_s}};
  (*report)["time_per_frame_ms"] = {{"total", per_frame_ms(wall_s)}, {"extraction", per_frame_ms(extract_s)}};
}

}  // namespace rk::app

// rk-extract's subcommands (apps/subcommand.h) and the video input options they share.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/frame_times.h"
#include "io/cli.h"
#include "io/error.h"
#include "io/utc_time.h"
#include "subcommand.h"
#include "io/run_record.h"
#include "video/recording_times.h"
#include "video/stdin_video.h"

namespace rk::app {

Command AddBeaconCommand(CLI::App& app);      // extract_beacon_cmd.cpp
Command AddFeaturesCommand(CLI::App& app);    // extract_features_cmd.cpp
Command AddSilhouetteCommand(CLI::App& app);  // extract_silhouette_cmd.cpp
Command AddPointsCommand(CLI::App& app);      // extract_points_cmd.cpp

// --video, --frames | --fps [--t0] | the recording's own times [--epoch-utc], --bad-rows: the recording and
// its frame times (formats/frame_times.h, video/recording_times.h). Paths and optional values, so
// registered here rather than from an option table.
struct VideoInputArgs {
  std::vector<std::string> videos;
  std::string frames_path, epoch_utc;
  std::optional<double> fps, t0;
  io::BadRows bad_rows = io::BadRows::kError;  // --frames rows
  // The recording's own times, when neither --frames nor --fps is given (set by Clock()).
  mutable std::optional<video::RecordingFrameTimes> recording;

  void Add(CLI::App* app) {
    app->add_option("--video", videos,
                    "Recording: Phantom .cine, Photron .mraw (or its .cihx/.cih), a video file (ffmpeg-readable) or "
                    "an image-sequence pattern dir/%06d.png; repeat for segments, read in the order given. Not '-': "
                    "a video is not read from stdin")
        ->required();
    auto* o_frames = app->add_option("--frames", frames_path, "Frame times CSV with columns frame,t_s");
    auto* o_fps = app->add_option("--fps", fps, "Constant frame rate (Hz): t = t0 + frame / fps");
    app->add_option("--t0", t0, "Time of frame 0 (s) with --fps [default 0]")->needs(o_fps);
    auto* o_epoch = app->add_option("--epoch-utc", epoch_utc,
                                    "Without --frames/--fps the recording's own times are used (as rk-import "
                                    "frames); UTC-stamped ones (IRIG, camera clock) count from this ISO-8601 "
                                    "epoch [default: from the first frame]");
    o_frames->excludes(o_fps);
    o_epoch->excludes(o_frames)->excludes(o_fps);
    cli::AddBadRowsOption(app, &bad_rows);
  }
  void CheckFrameTimes() const {
    video::RefuseStdinVideo(videos);
    io::ParseEpochOption(epoch_utc);
  }
  // The videos, then the frames file if any.
  std::vector<cli::NamedPath> Inputs() const {
    std::vector<cli::NamedPath> inputs;
    for (const std::string& v : videos) inputs.push_back({"--video", v});
    inputs.push_back({"--frames", frames_path});
    return inputs;
  }
  // --frames, --fps, else the recording's own times: where they come from and their gaps are said on
  // stderr (and in the report's frame_times); a time that goes backwards stops the run (exit 3), as the
  // tools' rows must be in time order: correct it in rk-import frames' output and give that as --frames.
  formats::FrameClock Clock() const {
    if (!frames_path.empty()) return formats::FrameClock::FromCsv(frames_path, bad_rows);
    if (fps) return formats::FrameClock::FromRate(*fps, t0.value_or(0.0));
    video::FrameTimesOptions o;
    o.epoch_unix_s = io::ParseEpochOption(epoch_utc);
    recording = video::ReadFrameTimes(videos, o);
    if (recording->backwards > 0) {
      for (const std::string& p : recording->problems) {
        if (p.find("goes back") != std::string::npos || p.find("same time") != std::string::npos) {
          throw DataError(videos.front(), 0, 0, p + ": frame times must increase; write them with rk-import frames, "
                                                    "correct them and give --frames");
        }
      }
    }
    for (const io::Warning& w : video::FrameTimesSummary(*recording).warnings) io::EmitWarning(w.message);
    std::vector<double> t;
    t.reserve(recording->frames.size());
    for (const video::FrameTime& f : recording->frames) t.push_back(f.t_s);
    return formats::FrameClock::FromTimes(std::move(t), videos.front() + " (its own frame times)");
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
    if (!frames_path.empty()) return io::Json{{"source", "frames"}};
    if (fps) return io::Json{{"source", "fps"}, {"fps_hz", *fps}, {"t0_s", t0.value_or(0.0)}};
    io::Json j = recording ? video::FrameTimesSummary(*recording).details["frame_times"] : io::Json::object();
    j["source"] = "recording";
    return j;
  }
};

// The report's "time_s" and "time_per_frame_ms" (total and extraction).
inline void AddReportTimes(io::Json* report, std::int64_t frames, double wall_s, double extract_s) {
  const auto per_frame_ms = [&](double s) { return frames ? 1e3 * s / static_cast<double>(frames) : 0.0; };
  (*report)["time_s"] = {{"total", wall_s}, {"extraction", extract_s}};
  (*report)["time_per_frame_ms"] = {{"total", per_frame_ms(wall_s)}, {"extraction", per_frame_ms(extract_s)}};
}

}  // namespace rk::app

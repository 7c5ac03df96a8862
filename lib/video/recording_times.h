// A recording's own frame times (SPEC.md §1.1 "Recordings", §2.1 video frame times): for every frame of
// every --video segment, in decode order, the time the recording itself gives, and where it comes from
// (`time_source`), in this order of preference:
//   irig / camera  a camera file's per-frame stamps (CINE time block: IRIG-synchronised or the camera's
//                  clock, per frame);
//   host           rk-capture's frames.csv beside its segments (seg_NNN.y4m, seg_NNN/%06d.pgm);
//   container      a container's presentation times (Matroska, MP4/MOV, MPEG-TS), by ffprobe;
//   nominal        the rate the file states (MRAW's record rate and frame numbers, CINE without a time
//                  block, y4m, AVI), or --fps for an image sequence.
// Absolute times (IRIG, a camera's real-time clock) become t_s relative to the epoch when one is given,
// else relative to the first frame (said). Times that go backwards and gaps of more than 1.5 frame
// intervals are reported with their frame numbers, never renumbered or repaired.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/run_summary.h"
#include "video/camera_file.h"

namespace rk::video {

struct FrameTime {
  std::int64_t frame = 0;
  double t_s = 0.0;
  TimeSource source = TimeSource::kNominal;
  double exposure_s = std::numeric_limits<double>::quiet_NaN();
  double camera_ts_s = std::numeric_limits<double>::quiet_NaN();
};

struct FrameTimesOptions {
  std::optional<double> epoch_unix_s;  // --epoch-utc as POSIX seconds
  std::optional<double> fps_hz;        // a rate for recordings that state none (image sequences)
};

struct RecordingFrameTimes {
  std::vector<FrameTime> frames;
  bool absolute = false;            // the stamps are UTC
  bool relative_to_epoch = false;   // t_s = stamp − epoch (else relative to the first frame)
  double nominal_rate_hz = 0.0;     // of the first segment (0: none)
  std::vector<std::string> sources; // per segment: "path: where its times come from"
  std::vector<std::string> nominal; // the sources of the segments timed by a nominal rate (said on stderr)
  std::vector<io::Warning> warnings;  // the files' own (RecordingTimes::warnings); absolute times without an epoch (no_epoch)
  // Stamps that go backwards (or repeat) and gaps > 1.5 intervals: "frame N: ..." each.
  std::vector<std::string> problems;
  std::int64_t backwards = 0, gaps = 0;
  double largest_gap_s = 0.0;
};

// Reads the frame times of `segments` (without decoding images where the container says them).
// UsageError for a recording with no times and no --fps; IoError / DataError as the readers.
RecordingFrameTimes ReadFrameTimes(const std::vector<std::string>& segments, const FrameTimesOptions& options);


// The run summary of a recording's frame times: frames by time source (headline); warnings: segments timed
// only by a nominal rate (nominal_times), the file's own disagreements (times_disagree), absolute times
// without an epoch (no_epoch), backwards stamps and gaps (time_backwards, frame_gap: the first 20 with their
// frame numbers, then a count); details: frame_times (the sources, counts, the largest gap).
io::RunSummary FrameTimesSummary(const RecordingFrameTimes& times);

// The rk-capture frames.csv that times `segment` (a seg_NNN.y4m or seg_NNN/%06d.pgm beside it), or "".
std::string CaptureFramesFile(const std::string& segment);

}  // namespace rk::video

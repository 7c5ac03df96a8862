// Frame times of a recording (SPEC.md §2.1 "video frame times", written by rk-sim and rk-capture, read by every
// tool that takes --video): either a
// frames.csv with columns frame,t_s (frame = 0-based decode index counting on
// across segments, t_s non-decreasing), or a constant rate t = t0 + frame / fps.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "io/csv.h"

namespace rk::formats {

class FrameClock {
 public:
  // Reads frame,t_s by column name ("-" = stdin). Throws DataError (file:line:col)
  // for a non-numeric or non-finite cell, time going backwards, or frame numbers
  // that do not count 0, 1, 2, ...; IoError if unreadable.
  // `bad_rows`: io::BadRows::kSkip drops rows without an integer frame and a time, or whose time
  // goes backwards; the frame numbers of the rows kept must still count 0, 1, 2, ..., except that a
  // skipped row's frame number is a hole (no time): after n skipped rows the count may jump by n.
  static FrameClock FromCsv(const std::string& path, io::BadRows bad_rows = io::BadRows::kError);
  // A recording's own times (video::ReadFrameTimes: CINE stamps, container times, ...), frame k at t_s[k];
  // `source` names the recording in messages.
  static FrameClock FromTimes(std::vector<double> t_s, std::string source);
  // t = t0 + frame / fps; throws UsageError unless fps > 0 and both finite.
  static FrameClock FromRate(double fps_hz, double t0_s);

  bool from_file() const { return from_file_; }
  const std::string& path() const { return path_; }
  // Number of frame times in the file (from_file() only).
  std::int64_t size() const { return static_cast<std::int64_t>(t_s_.size()); }
  // Time of a frame; NaN for a hole (a frame whose row was skipped); throws DataError naming the file
  // if it lists fewer frames.
  double TimeOf(std::int64_t frame) const;

 private:
  bool from_file_ = false;
  std::string path_;
  std::vector<double> t_s_;        // NaN: a hole
  std::int64_t trailing_holes_ = 0;  // rows skipped after the last one kept: frames that may follow
  double fps_hz_ = 0.0;
  double t0_s_ = 0.0;
};

// One row of a frames.csv with the optional columns of SPEC.md §2.1 (rk-import frames): NaN = empty.
struct FrameTimeRow {
  std::int64_t frame = 0;
  double t_s = 0.0;
  std::string time_source;  // irig, camera, container, host, nominal
  double exposure_s = std::numeric_limits<double>::quiet_NaN();
  double camera_ts_s = std::numeric_limits<double>::quiet_NaN();
};
// Column order of that file.
inline constexpr const char* kFrameTimesColumns = "frame,t_s,time_source,exposure_s,camera_ts_s";
// Writes `rows` (t_s, exposure_s and camera_ts_s to the nanosecond) after `comments` ("# " lines), atomically
// ("-" = stdout).
void WriteFrameTimes(const std::string& path, const std::vector<FrameTimeRow>& rows,
                     const std::vector<std::string>& comments);

}  // namespace rk::formats

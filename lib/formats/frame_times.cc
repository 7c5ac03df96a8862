// Frame times from frames.csv or from a constant rate; see frame_times.h.
#include "formats/frame_times.h"

#include <cmath>
#include <limits>
#include <utility>

#include "io/csv.h"
#include "io/error.h"

namespace rk::formats {

FrameClock FrameClock::FromCsv(const std::string& path, io::BadRows bad_rows) {
  io::CsvReadOptions read;
  read.bad_rows = bad_rows;
  read.rule.integers = {"frame"};
  read.rule.non_decreasing = "t_s";
  const io::CsvTable table = io::CsvTable::Read(path, read);
  const int c_frame = table.RequireColumn("frame");
  const int c_t = table.RequireColumn("t_s");
  FrameClock clock;
  clock.from_file_ = true;
  clock.path_ = path;
  clock.t_s_.reserve(table.rows());
  // Under --bad-rows skip a skipped row may have held the next frame number: each skipped row before a
  // row lets that row's frame number jump one further (the frames between are holes: no time). Any
  // other break in 0, 1, 2, ... is an error in both modes.
  const std::vector<io::SkippedRow>& skipped = table.skipped();
  std::size_t next_skipped = 0;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    const std::int64_t frame = table.Int(i, c_frame);
    const std::int64_t expected = static_cast<std::int64_t>(clock.t_s_.size());
    std::int64_t may_skip = 0;
    while (next_skipped < skipped.size() && skipped[next_skipped].line < table.Line(i)) {
      ++may_skip;
      ++next_skipped;
    }
    if (frame != expected && !(frame > expected && frame - expected <= may_skip)) {
      throw table.CellError(i, c_frame,
                            "frame numbers must count 0, 1, 2, ... in decode order; expected " +
                                std::to_string(expected) + ", found " + std::to_string(frame));
    }
    clock.t_s_.resize(static_cast<std::size_t>(frame), std::numeric_limits<double>::quiet_NaN());
    clock.t_s_.push_back(table.Double(i, c_t));
  }
  clock.trailing_holes_ = static_cast<std::int64_t>(skipped.size() - next_skipped);
  table.RequireNonDecreasing(c_t);
  if (clock.t_s_.empty()) throw DataError(path, 0, 0, "no frame times (the file has a header but no rows)");
  return clock;
}

FrameClock FrameClock::FromTimes(std::vector<double> t_s, std::string source) {
  FrameClock clock;
  clock.from_file_ = true;
  clock.path_ = std::move(source);
  clock.t_s_ = std::move(t_s);
  return clock;
}

void WriteFrameTimes(const std::string& path, const std::vector<FrameTimeRow>& rows,
                     const std::vector<std::string>& comments) {
  io::CsvWriter out(io::SplitList(kFrameTimesColumns));
  for (const std::string& c : comments) out.Comment(c);
  constexpr int kNs = 9;
  for (const FrameTimeRow& r : rows) {
    out.Add(r.frame).Add(r.t_s, kNs).Add(r.time_source).Add(r.exposure_s, kNs).Add(r.camera_ts_s, kNs).EndRow();
  }
  out.Write(path);
}

FrameClock FrameClock::FromRate(double fps_hz, double t0_s) {
  if (!(fps_hz > 0) || !std::isfinite(fps_hz)) throw UsageError("--fps must be a positive number of frames per second");
  if (!std::isfinite(t0_s)) throw UsageError("--t0 must be a finite number of seconds");
  FrameClock clock;
  clock.fps_hz_ = fps_hz;
  clock.t0_s_ = t0_s;
  return clock;
}

double FrameClock::TimeOf(std::int64_t frame) const {
  if (!from_file_) return t0_s_ + static_cast<double>(frame) / fps_hz_;
  // A frame after the last listed one, where rows at the end of the file were skipped: a hole.
  if (frame >= size() && frame < size() + trailing_holes_) return std::numeric_limits<double>::quiet_NaN();
  if (frame < 0 || frame >= size()) {
    throw DataError(path_, 0, 0,
                    "lists times for " + std::to_string(size()) + " frames but the video has more (no time for frame " +
                        std::to_string(frame) + ")");
  }
  return t_s_[static_cast<std::size_t>(frame)];
}

}  // namespace rk::formats

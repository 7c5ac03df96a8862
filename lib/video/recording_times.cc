// A recording's own frame times; see recording_times.h.
#include "video/recording_times.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

#include "io/csv.h"
#include "io/error.h"
#include "io/number_text.h"
#include "io/run_record.h"
#include "io/utc_time.h"
#include "video/frame_source.h"
#include "video/y4m.h"

namespace rk::video {
namespace fs = std::filesystem;
namespace {

// One segment's times before they are placed on the output's time line: a camera file's own, or made here.
struct SegmentTimes : RecordingTimes {
  bool on_trial_clock = false;  // rk-capture's t_s: already seconds since the trial epoch
};

// Runs a command, returns its stdout; DataError naming `path` with ffprobe's first error line on failure.
std::string RunProbe(const std::string& cmd, const std::string& path) {
  const std::string err = MakeTempFile();
  FILE* p = ::popen((cmd + " 2>" + ShellQuote(err)).c_str(), "r");
  if (!p) throw IoError(path, "cannot run ffprobe");
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int rc = ::pclose(p);
  std::string errtext;
  if (FILE* e = std::fopen(err.c_str(), "r")) {
    char line[512] = {0};
    if (std::fgets(line, sizeof line, e)) errtext = line;
    std::fclose(e);
  }
  ::unlink(err.c_str());
  if (rc != 0) throw DataError(path, 0, 0, "ffprobe cannot read it" + (errtext.empty() ? "" : ": " + errtext));
  return out;
}

double ParseRate(const std::string& r) {  // "30000/1001"
  const auto slash = r.find('/');
  const double num = std::atof(r.substr(0, slash).c_str());
  const double den = slash == std::string::npos ? 1.0 : std::atof(r.substr(slash + 1).c_str());
  return num > 0 && den > 0 ? num / den : 0.0;
}

// Containers whose presentation times are real per-frame times (not frame index over a rate).
bool TimedContainer(const std::string& format_name) {
  for (const char* f : {"matroska", "webm", "mov", "mp4", "mpegts", "nut"}) {
    if (format_name.find(f) != std::string::npos) return true;
  }
  return false;
}

SegmentTimes NominalTimes(std::int64_t count, double nominal_rate_hz, const std::string& basis) {
  SegmentTimes s;
  s.nominal_rate_hz = nominal_rate_hz;
  s.basis = basis;
  s.frames.resize(static_cast<std::size_t>(count));
  for (std::int64_t i = 0; i < count; ++i) s.frames[static_cast<std::size_t>(i)].t_s = static_cast<double>(i) / nominal_rate_hz;
  return s;
}

// A video file through ffprobe: its packets' presentation times (sorted: the decoder's output order)
// for a timed container, else its frame count at the stated rate.
SegmentTimes ContainerTimes(const std::string& path, const FrameTimesOptions& o) {
  const std::string q = ShellQuote(path);
  std::istringstream head(RunProbe("ffprobe -v error -select_streams v:0 -show_entries format=format_name:stream=r_frame_rate "
                                   "-of default=nw=1 " + q, path));
  std::string line, format_name, rate_text;
  while (std::getline(head, line)) {
    if (line.rfind("format_name=", 0) == 0) format_name = line.substr(12);
    if (line.rfind("r_frame_rate=", 0) == 0) rate_text = line.substr(13);
  }
  double rate = ParseRate(rate_text);
  std::istringstream pk(RunProbe("ffprobe -v error -select_streams v:0 -show_entries packet=pts_time -of csv=p=0 " + q, path));
  std::vector<double> pts;
  bool all_timed = true;
  while (std::getline(pk, line)) {
    if (line.empty()) continue;
    char* end = nullptr;
    const double t = std::strtod(line.c_str(), &end);
    if (end == line.c_str() || !std::isfinite(t)) all_timed = false;
    pts.push_back(t);
  }
  if (pts.empty()) throw DataError(path, 0, 0, "video has no frames");
  if (o.fps_hz) rate = *o.fps_hz;
  if (TimedContainer(format_name) && all_timed) {
    std::sort(pts.begin(), pts.end());
    SegmentTimes s;
    s.nominal_rate_hz = rate;
    s.basis = "the container's presentation times (" + format_name + ")";
    s.frames.resize(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      s.frames[i].t_s = s.frames[i].camera_ts_s = pts[i];
      s.frames[i].source = TimeSource::kContainer;
    }
    return s;
  }
  if (!(rate > 0)) throw UsageError(path + ": the video states no frame rate; give --fps");
  return NominalTimes(static_cast<std::int64_t>(pts.size()), rate,
                      "no per-frame times in " + format_name + ": frame number over the " +
                          (o.fps_hz ? std::string("--fps") : "stated") + " rate " + io::NumberText(rate) + " Hz");
}

// Frames of an image-sequence pattern (numbered from 0 or 1, to the first missing).
std::int64_t SequenceFrames(const std::string& pattern) {
  std::int64_t start = fs::exists(SequenceFramePath(pattern, 0)) ? 0 : 1;
  std::int64_t n = 0;
  while (fs::exists(SequenceFramePath(pattern, start + n))) ++n;
  if (n == 0) throw IoError(pattern, "no image matches the pattern");
  return n;
}

std::int64_t CountFrames(const std::string& segment) {
  if (IsSequencePattern(segment)) return SequenceFrames(segment);
  if (IsMonoY4m(segment)) {
    Y4mReader r(segment);
    cv::Mat m;
    while (r.Read(&m)) {
    }
    return r.frames_read();
  }
  FrameSource s({segment});
  cv::Mat m;
  std::int64_t n = 0;
  while (s.Read(&m)) ++n;
  return n;
}

// rk-capture's frames.csv rows of this segment (column `segment` = its number).
SegmentTimes CaptureTimes(const std::string& segment, const std::string& frames_csv) {
  static const std::regex seg_re(R"(seg_(\d{3,})(\.y4m)?)");
  std::smatch m;
  const std::string name = fs::path(segment).filename() == "%06d.pgm" ? fs::path(segment).parent_path().filename().string()
                                                                      : fs::path(segment).filename().string();
  std::regex_match(name, m, seg_re);
  const std::int64_t index = std::stoll(m[1].str());
  const io::CsvTable table = io::CsvTable::Read(frames_csv, io::CsvReadOptions{});
  const int c_t = table.RequireColumn("t_s");
  const int c_seg = table.RequireColumn("segment");
  SegmentTimes s;
  s.on_trial_clock = true;
  s.basis = "rk-capture's " + frames_csv + " (host clock, seconds since the trial epoch)";
  for (std::size_t i = 0; i < table.rows(); ++i) {
    if (table.Int(i, c_seg) != index) continue;
    FrameStamp f;
    f.t_s = table.Double(i, c_t);
    f.source = TimeSource::kHost;
    s.frames.push_back(f);
  }
  const std::int64_t frames = CountFrames(segment);
  if (frames != static_cast<std::int64_t>(s.frames.size())) {
    throw DataError(frames_csv, 0, 0, "lists " + std::to_string(s.frames.size()) + " frames of segment " + std::to_string(index) +
                                          " but " + segment + " holds " + std::to_string(frames) +
                                          " (run rk-capture recover on the trial)");
  }
  if (s.frames.size() >= 2) {
    s.nominal_rate_hz = static_cast<double>(s.frames.size() - 1) / (s.frames.back().t_s - s.frames.front().t_s);
  }
  return s;
}

SegmentTimes TimesOf(const std::string& segment, const FrameTimesOptions& o) {
  if (!IsSequencePattern(segment) && IsCameraFile(segment)) {
    SegmentTimes s;
    static_cast<RecordingTimes&>(s) = CameraFileReader(segment).file().times;
    return s;
  }
  const std::string capture = CaptureFramesFile(segment);
  if (!capture.empty()) return CaptureTimes(segment, capture);
  if (IsSequencePattern(segment)) {
    if (!o.fps_hz) throw UsageError(segment + ": an image sequence has no frame times; give --fps HZ (or --frames F.csv)");
    return NominalTimes(SequenceFrames(segment), *o.fps_hz, "image sequence at --fps " + io::NumberText(*o.fps_hz) + " Hz");
  }
  if (IsMonoY4m(segment)) {
    const double rate = o.fps_hz ? *o.fps_hz : Y4mReader(segment).format().fps;
    return NominalTimes(CountFrames(segment), rate, "y4m: frame number over the header's rate " + io::NumberText(rate) + " Hz");
  }
  return ContainerTimes(segment, o);
}

// Seconds to the nanosecond ("0.003000000"): differences of stamps kept in binary fractions of a second.
std::string Nanoseconds(double s) {
  char b[48];
  std::snprintf(b, sizeof b, "%.9f", s);
  return b;
}

std::string Tenths(double x) {
  char b[48];
  std::snprintf(b, sizeof b, "%.1f", x);
  return b;
}

// Backwards stamps and gaps > 1.5 intervals, each with its frame number.
void FindProblems(double interval_s, RecordingFrameTimes* r) {
  for (std::size_t i = 1; i < r->frames.size(); ++i) {
    const double dt = r->frames[i].t_s - r->frames[i - 1].t_s;
    const std::string at = "frame " + std::to_string(r->frames[i].frame) + ": ";
    if (dt <= 0) {
      ++r->backwards;
      r->problems.push_back(at + (dt < 0 ? "time goes back by " + Nanoseconds(-dt) + " s"
                                         : std::string("same time as the frame before")));
    } else if (interval_s > 0 && dt > 1.5 * interval_s) {
      ++r->gaps;
      r->largest_gap_s = std::max(r->largest_gap_s, dt);
      r->problems.push_back(at + "gap of " + Nanoseconds(dt) + " s after the frame before (" +
                            Tenths(dt / interval_s) + " frame intervals)");
    }
  }
}

}  // namespace

std::string CaptureFramesFile(const std::string& segment) {
  static const std::regex y4m_re(R"(seg_\d{3,}\.y4m)"), pgm_re(R"(seg_\d{3,})");
  const fs::path p(segment);
  fs::path folder;
  if (std::regex_match(p.filename().string(), y4m_re)) {
    folder = p.parent_path();
  } else if (IsSequencePattern(segment) && std::regex_match(p.parent_path().filename().string(), pgm_re)) {
    folder = p.parent_path().parent_path();
  } else {
    return "";
  }
  const fs::path frames = (folder.empty() ? fs::path(".") : folder) / "frames.csv";
  std::error_code ec;
  return fs::is_regular_file(frames, ec) ? frames.string() : "";
}

RecordingFrameTimes ReadFrameTimes(const std::vector<std::string>& segments, const FrameTimesOptions& o) {
  RecordingFrameTimes r;
  std::vector<SegmentTimes> all;
  for (const std::string& seg : segments) {
    all.push_back(TimesOf(seg, o));
    r.sources.push_back(seg + ": " + all.back().basis);
    const std::vector<FrameStamp>& f = all.back().frames;
    if (!f.empty() && f.front().source == TimeSource::kNominal) r.nominal.push_back(r.sources.back());
    for (const io::Warning& w : all.back().warnings) r.warnings.push_back({w.code, seg + ": " + w.message});
  }
  r.absolute = all.front().absolute;
  for (std::size_t i = 1; i < all.size(); ++i) {
    if (all[i].absolute != r.absolute || all[i].on_trial_clock != all.front().on_trial_clock) {
      throw DataError(segments[i], 0, 0, "its frame times are on another clock than " + segments[0] +
                                             "'s (absolute UTC, the trial clock or relative): give --frames");
    }
  }
  r.nominal_rate_hz = all.front().nominal_rate_hz;
  // The time line: the epoch for absolute stamps when given, the trial epoch for rk-capture's, else the first frame.
  // zero = zero_whole + zero_frac, kept apart so that UTC stamps keep their nanoseconds.
  double zero_whole = all.front().origin_s;
  double zero_frac = all.front().frames.empty() ? 0.0 : all.front().frames.front().t_s;
  if (r.absolute && o.epoch_unix_s) {
    zero_whole = std::floor(*o.epoch_unix_s);
    zero_frac = *o.epoch_unix_s - zero_whole;
    r.relative_to_epoch = true;
  } else if (all.front().on_trial_clock) {
    zero_whole = zero_frac = 0.0;
    r.relative_to_epoch = true;
  } else if (r.absolute) {
    r.warnings.push_back({"no_epoch", "the recording's times are UTC but no --epoch-utc was given: t_s counts from its first frame"});
  }
  std::int64_t k = 0;
  for (const SegmentTimes& s : all) {
    for (const FrameStamp& f : s.frames) {
      r.frames.push_back({k++, (s.origin_s - zero_whole) + (f.t_s - zero_frac), f.source, f.exposure_s, f.camera_ts_s});
    }
  }
  FindProblems(r.nominal_rate_hz > 0 ? 1.0 / r.nominal_rate_hz : 0.0, &r);
  return r;
}

io::RunSummary FrameTimesSummary(const RecordingFrameTimes& times) {
  io::RunSummary s;
  constexpr std::size_t kSaid = 20;  // problems said one by one, then a count
  std::map<std::string, std::int64_t> by_source;
  for (const FrameTime& f : times.frames) ++by_source[TimeSourceName(f.source)];
  for (const std::string& n : times.nominal) s.Warn("nominal_times", "frame times of " + n);
  for (const io::Warning& w : times.warnings) s.Warn(w.code, w.message);
  for (std::size_t i = 0; i < times.problems.size() && i < kSaid; ++i) {
    const bool back = times.problems[i].find("goes back") != std::string::npos ||
                      times.problems[i].find("same time") != std::string::npos;
    s.Warn(back ? "time_backwards" : "frame_gap", times.problems[i]);
  }
  if (times.problems.size() > kSaid) {
    s.Warn("frame_time_problems", std::to_string(times.problems.size() - kSaid) + " more frame time problems (" +
                                      std::to_string(times.backwards) + " backwards or repeated, " +
                                      std::to_string(times.gaps) + " gaps in all)");
  }
  const double n = static_cast<double>(times.frames.size());
  s.AddFigure("frames", n, "", std::to_string(times.frames.size()) + " frames");
  for (const auto& [source, count] : by_source) {
    s.AddFigure("time_source_" + source, static_cast<double>(count) / n, "fraction",
                std::to_string(count) + " frames");
  }
  s.details["frame_times"] = {
      {"frames", times.frames.size()},
      {"sources", times.sources},
      {"time_sources", by_source},
      {"absolute", times.absolute},
      {"relative_to", times.relative_to_epoch ? "epoch" : "first frame"},
      {"nominal_rate_hz", times.nominal_rate_hz},
      {"backwards", times.backwards},
      {"gaps", times.gaps},
      {"largest_gap_s", times.largest_gap_s},
  };
  return s;
}

}  // namespace rk::video

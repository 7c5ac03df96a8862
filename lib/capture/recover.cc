#include "capture/recover.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>

#include "capture/clock.h"
#include "capture/segment_writer.h"
#include "formats/turret_log.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_positions.h"
#include "io/version.h"
#include "trial/layout.h"
#include "video/frame_source.h"

namespace rk::capture {
namespace fs = std::filesystem;

io::Json RecoverSummary::ToJson() const {
  io::Json j;
  j["dir"] = dir;
  j["state_before"] = state_before;
  j["state_after"] = state_after;
  j["repairs"] = repairs;
  j["problems"] = problems;
  j["readable"] = readable();
  j["frames"] = frames;
  j["rows"] = rows;
  return j;
}

namespace {

// A text log split into lines with their byte offsets.
struct LogText {
  std::string data;
  std::vector<std::size_t> line_start;  // offset of each line (complete lines only)
};

// A video segment of a camera folder; frames: whole frames on disk, -1 removed (no frames), -2 unreadable.
struct SegmentOnDisk {
  int index = 0;
  std::string rel;      // manifest path
  std::string path;     // file (y4m) or folder (pgm)
  bool pgm = false;
  std::int64_t frames = 0;
  // y4m
  std::int64_t header_bytes = 0, frame_bytes = 0;
  FrameFormat format;
};

class Recovery {
 public:
  Recovery(std::string dir, const RecoverOptions& o) : dir_(std::move(dir)), o_(o) { s_.dir = dir_; }
  RecoverSummary Run();

 private:
  std::string Path(const std::string& rel) const { return (fs::path(dir_) / rel).string(); }
  // Every path the manifest names (logs, camera folders, frames files) must lie inside the trial
  // folder after links are resolved: recover writes nowhere else. Throws DataError at the key.
  void CheckPathsInside(const io::Json& m, const std::string& manifest_path, const std::string& text) const;
  // The last guard before a file is cut or removed: false (and a problem) for a path outside the folder.
  bool Writable(const std::string& path);
  void Repair(const std::string& what) { s_.repairs.push_back(what); }
  void Problem(const std::string& what) { s_.problems.push_back(what); }
  bool Truncate(const std::string& path, std::int64_t bytes);
  bool Remove(const std::string& path);
  // Cuts a torn tail; returns the text (complete lines) or nullopt if unreadable.
  std::optional<LogText> ReadLog(const std::string& rel);
  // Checks a CSV log: header with `required` columns, numeric t_s non-decreasing. Returns the table.
  std::optional<io::CsvTable> CheckCsv(const std::string& rel, const LogText& text,
                                       const std::vector<std::string>& required);
  void CheckRange(const std::string& rel);
  void CheckTurret(const std::string& rel);
  std::vector<std::string> RecoverCamera(const std::string& name, const io::Json& cam, const io::Json& stream);
  // RecoverCamera's stages: the segments of the folder, whole frames in each, then frames.csv against them.
  std::vector<SegmentOnDisk> ListSegments(const std::string& name, const std::string& folder);
  void CheckY4mSegment(SegmentOnDisk* s, std::optional<FrameFormat>* first_format);
  void CheckPgmSegment(const std::string& name, SegmentOnDisk* s);
  bool ReadRowSegments(const io::CsvTable& table, std::vector<int>* row_segment,
                       std::map<int, std::int64_t>* rows_per_segment);
  bool CutRowsWithoutFrames(const std::string& frames_rel, const LogText& text, const io::CsvTable& table,
                            const std::vector<SegmentOnDisk>& segs, int last_row_segment,
                            std::vector<int>* row_segment, std::map<int, std::int64_t>* rows_per_segment);
  bool CutFramesWithoutRows(std::vector<SegmentOnDisk>* segs, std::map<int, std::int64_t>* rows_per_segment,
                            int last_row_segment, std::vector<std::string>* video, std::int64_t* frames_total);

  std::string dir_;
  RecoverOptions o_;
  RecoverSummary s_;
};

void Recovery::CheckPathsInside(const io::Json& m, const std::string& manifest_path, const std::string& text) const {
  const io::JsonPositions pos(text);
  const auto check = [&](const std::string& rel, const std::string& pointer, const std::string& key) {
    if (io::IsInsideFolder(dir_, Path(rel))) return;
    const io::TextPosition p = pos.At(pointer);
    throw DataError(manifest_path, p.line, p.column,
                    key + ": '" + rel + "' leads outside the trial folder (after links); recover writes only inside it");
  };
  for (const char* key : {"range", "turret"}) {
    if (m.contains(key) && m[key].is_string()) check(m[key].get<std::string>(), std::string("/") + key, key);
  }
  for (auto it = m["cameras"].begin(); it != m["cameras"].end(); ++it) {
    const std::string cam = "/cameras/" + io::PointerToken(it.key());
    check(it.key(), cam, "cameras." + it.key());
    if (it.value().is_object() && it.value().contains("frames") && it.value()["frames"].is_string()) {
      check(it.value()["frames"].get<std::string>(), cam + "/frames", "cameras." + it.key() + ".frames");
    }
  }
}

bool Recovery::Writable(const std::string& path) {
  std::error_code ec;
  if (io::IsInsideFolder(dir_, path) && !fs::is_symlink(path, ec)) return true;
  Problem(path + ": a link or a path outside the trial folder: not changed");
  return false;
}

bool Recovery::Truncate(const std::string& path, std::int64_t bytes) {
  if (!Writable(path)) return false;
  if (o_.check_only) return true;
  if (::truncate(path.c_str(), static_cast<off_t>(bytes)) != 0) {
    Problem(path + ": cannot truncate: " + std::strerror(errno));
    return false;
  }
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd >= 0) {
    ::fdatasync(fd);
    ::close(fd);
  }
  return true;
}

bool Recovery::Remove(const std::string& path) {
  if (!Writable(path)) return false;
  if (o_.check_only) return true;
  std::error_code ec;
  fs::remove_all(path, ec);
  if (ec) {
    Problem(path + ": cannot remove: " + ec.message());
    return false;
  }
  return true;
}

std::optional<LogText> Recovery::ReadLog(const std::string& rel) {
  const std::string path = Path(rel);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    Problem(rel + ": missing");
    return std::nullopt;
  }
  LogText t;
  t.data = io::ReadFile(path);
  std::size_t end = t.data.size();
  // A power cut can leave the file longer than its data (a block of NULs): drop trailing NULs, then
  // anything after the last line end.
  while (end > 0 && t.data[end - 1] == '\0') --end;
  const std::size_t last_nl = end == 0 ? std::string::npos : t.data.rfind('\n', end - 1);
  const std::size_t keep = last_nl == std::string::npos ? 0 : last_nl + 1;
  if (keep < t.data.size()) {
    const std::size_t torn = t.data.size() - keep;
    Repair(rel + ": torn last line (" + std::to_string(torn) + " bytes) cut off");
    if (!Truncate(path, static_cast<std::int64_t>(keep))) return std::nullopt;
    t.data.resize(keep);
  }
  const auto nul = t.data.find('\0');
  if (nul != std::string::npos) {
    const std::size_t line = static_cast<std::size_t>(std::count(t.data.begin(), t.data.begin() + nul, '\n')) + 1;
    Problem(rel + ":" + std::to_string(line) + ": NUL bytes inside the file (data lost in a power cut?)");
    return std::nullopt;
  }
  std::size_t pos = 0;
  while (pos < t.data.size()) {
    t.line_start.push_back(pos);
    const std::size_t nl = t.data.find('\n', pos);
    pos = nl == std::string::npos ? t.data.size() : nl + 1;
  }
  return t;
}

std::optional<io::CsvTable> Recovery::CheckCsv(const std::string& rel, const LogText& text,
                                               const std::vector<std::string>& required) {
  try {
    io::CsvTable t = io::CsvTable::Parse(text.data, rel);
    for (const auto& c : required) t.RequireColumn(c);
    const int ct = t.RequireColumn("t_s");
    for (std::size_t r = 0; r < t.rows(); ++r) t.Double(r, ct);
    t.RequireNonDecreasing(ct);
    s_.rows[rel] = static_cast<std::int64_t>(t.rows());
    return t;
  } catch (const Error& e) {
    Problem(e.what());
    return std::nullopt;
  }
}

void Recovery::CheckRange(const std::string& rel) {
  const auto text = ReadLog(rel);
  if (!text) return;
  const auto t = CheckCsv(rel, *text, {"t_s", "range_m"});
  if (!t) return;
  try {
    const int cr = t->RequireColumn("range_m"), cs = t->Column("status");
    for (std::size_t r = 0; r < t->rows(); ++r) {
      t->OptionalDouble(r, cr);
      if (cs >= 0 && !t->IsEmpty(r, cs)) t->Int(r, cs);
    }
  } catch (const Error& e) {
    Problem(e.what());
  }
}

void Recovery::CheckTurret(const std::string& rel) {
  const auto text = ReadLog(rel);
  if (!text) return;
  const auto t = CheckCsv(rel, *text, formats::TurretLogColumns());
  if (!t) return;
  try {
    const int ca = t->RequireColumn("az_deg"), ce = t->RequireColumn("el_deg");
    for (std::size_t r = 0; r < t->rows(); ++r) {
      t->OptionalDouble(r, ca);
      t->OptionalDouble(r, ce);
    }
  } catch (const Error& e) {
    Problem(e.what());
  }
}

std::vector<std::string> Recovery::RecoverCamera(const std::string& name, const io::Json& cam,
                                                 const io::Json& /*stream*/) {
  const std::string folder = Path(name);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    Problem(name + ": camera folder missing");
    return {};
  }
  std::vector<SegmentOnDisk> segs = ListSegments(name, folder);

  // 1. Every segment: whole frames only.
  std::optional<FrameFormat> first_format;
  for (auto& s : segs) {
    if (!s.pgm) {
      CheckY4mSegment(&s, &first_format);
    } else {
      CheckPgmSegment(name, &s);
    }
  }

  // 2. frames.csv against the frames on disk, segment by segment.
  const std::string frames_rel = cam.contains("frames") && cam["frames"].is_string()
                                     ? cam["frames"].get<std::string>()
                                     : name + "/" + trial::kFramesFile;
  const auto text = ReadLog(frames_rel);
  std::vector<std::string> video;
  if (!text) return video;
  const auto table = CheckCsv(frames_rel, *text, {"frame", "t_s", "segment"});
  if (!table) return video;
  std::map<int, std::int64_t> rows_per_segment;
  std::vector<int> row_segment;
  if (!ReadRowSegments(*table, &row_segment, &rows_per_segment)) return video;
  for (const auto& s : segs) {
    if (s.frames == -2) return video;  // reported above; nothing more can be matched
  }
  const int last_row_segment = row_segment.empty() ? -1 : row_segment.back();
  if (!CutRowsWithoutFrames(frames_rel, *text, *table, segs, last_row_segment, &row_segment, &rows_per_segment)) {
    return video;
  }
  std::int64_t frames_total = 0;
  if (!CutFramesWithoutRows(&segs, &rows_per_segment, last_row_segment, &video, &frames_total)) return video;
  s_.frames[name] = frames_total;
  s_.rows[frames_rel] = static_cast<std::int64_t>(row_segment.size());
  return video;
}

std::vector<SegmentOnDisk> Recovery::ListSegments(const std::string& name, const std::string& folder) {
  std::vector<SegmentOnDisk> segs;
  std::error_code ec;
  static const std::regex y4m_re(R"(seg_(\d{3,})\.y4m)"), pgm_re(R"(seg_(\d{3,}))");
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    const std::string fn = e.path().filename().string();
    std::smatch m;
    SegmentOnDisk s;
    if (e.is_symlink(ec)) {
      if (std::regex_match(fn, m, pgm_re) || std::regex_match(fn, m, y4m_re)) {
        Problem(name + "/" + fn + ": a link, not a segment rk-capture wrote: not read, not changed");
      }
      continue;
    }
    if (e.is_regular_file() && std::regex_match(fn, m, y4m_re)) {
      s.index = std::stoi(m[1]);
      s.rel = name + "/" + fn;
      s.path = e.path().string();
    } else if (e.is_directory() && std::regex_match(fn, m, pgm_re)) {
      s.index = std::stoi(m[1]);
      s.rel = name + "/" + fn + "/%06d.pgm";
      s.path = e.path().string();
      s.pgm = true;
    } else {
      continue;
    }
    segs.push_back(s);
  }
  std::sort(segs.begin(), segs.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
  return segs;
}

// A y4m segment: a readable header, every frame with its marker, a torn last frame cut off.
void Recovery::CheckY4mSegment(SegmentOnDisk* seg, std::optional<FrameFormat>* first_format) {
  SegmentOnDisk& s = *seg;
  std::error_code ec;
  std::ifstream in(s.path, std::ios::binary);
  std::string header;
  std::getline(in, header);
  const std::int64_t size = static_cast<std::int64_t>(fs::file_size(s.path, ec));
  if (!in || !ParseY4mHeader(header, &s.format)) {
    if (size == 0 || (size < 256 && header.rfind("YUV4MPEG2", 0) == 0 && header.size() == static_cast<std::size_t>(size))) {
      Repair(s.rel + ": segment without frames (torn header) removed");
      Remove(s.path);
      s.frames = -1;
    } else {
      Problem(s.rel + ": not a readable YUV4MPEG2 (mono) header");
      s.frames = -2;
    }
    return;
  }
  s.header_bytes = static_cast<std::int64_t>(header.size()) + 1;
  s.frame_bytes = 6 + static_cast<std::int64_t>(s.format.width) * s.format.height * (s.format.bit_depth / 8);
  const std::int64_t whole = (size - s.header_bytes) / s.frame_bytes;
  const std::int64_t torn = (size - s.header_bytes) % s.frame_bytes;
  // Every frame starts with its marker.
  const int fd = ::open(s.path.c_str(), O_RDONLY | O_CLOEXEC);
  std::int64_t good = 0;
  for (; good < whole; ++good) {
    char mark[6];
    if (::pread(fd, mark, 6, static_cast<off_t>(s.header_bytes + good * s.frame_bytes)) != 6 ||
        std::memcmp(mark, "FRAME\n", 6) != 0) {
      break;
    }
  }
  if (fd >= 0) ::close(fd);
  if (good < whole) {
    Problem(s.rel + ": frame " + std::to_string(good) + " has no FRAME marker at byte " +
            std::to_string(s.header_bytes + good * s.frame_bytes) + " (corrupt segment)");
    s.frames = -2;
    return;
  }
  if (torn > 0) {
    Repair(s.rel + ": torn last frame (" + std::to_string(torn) + " bytes) cut off");
    Truncate(s.path, s.header_bytes + whole * s.frame_bytes);
  }
  s.frames = whole;
  if (*first_format && ((*first_format)->width != s.format.width || (*first_format)->height != s.format.height ||
                        (*first_format)->bit_depth != s.format.bit_depth)) {
    Problem(s.rel + ": frame size or depth differs from the first segment");
  }
  if (!*first_format) *first_format = s.format;
}

// A PGM segment folder: unfinished frames removed, complete frames counted up to the first gap.
void Recovery::CheckPgmSegment(const std::string& name, SegmentOnDisk* seg) {
  SegmentOnDisk& s = *seg;
  std::error_code ec;
  // Hidden temporaries are frames that were being written.
  for (const auto& e : fs::directory_iterator(s.path, ec)) {
    const std::string fn = e.path().filename().string();
    if (!fn.empty() && fn[0] == '.' && fn.size() > 4 && fn.substr(fn.size() - 4) == ".tmp") {
      Repair(name + "/" + fs::path(s.path).filename().string() + "/" + fn + ": unfinished frame removed");
      Remove(e.path().string());
    }
  }
  const std::string pattern = (fs::path(s.path) / "%06d.pgm").string();
  std::int64_t n = 0;
  while (fs::exists(video::SequenceFramePath(pattern, n), ec)) {
    const std::string f = video::SequenceFramePath(pattern, n);
    std::ifstream in(f, std::ios::binary);
    std::string magic;
    int w = 0, h = 0, maxval = 0;
    in >> magic >> w >> h >> maxval;
    in.get();
    const std::int64_t want = static_cast<std::int64_t>(in.tellg()) +
                              static_cast<std::int64_t>(w) * h * (maxval > 255 ? 2 : 1);
    if (!in || magic != "P5" || w <= 0 || h <= 0 || static_cast<std::int64_t>(fs::file_size(f, ec)) != want) {
      Problem(name + "/" + fs::path(s.path).filename().string() + "/" + fs::path(f).filename().string() +
              ": not a complete PGM");
      break;
    }
    ++n;
  }
  // A file after a missing index would never be read.
  std::int64_t total = 0;
  for (const auto& e : fs::directory_iterator(s.path, ec)) {
    if (e.path().extension() == ".pgm") ++total;
  }
  if (total > n) {
    Problem(s.rel + ": " + std::to_string(total - n) + " frame file(s) after frame " + std::to_string(n) +
            " are missing or unreadable");
    s.frames = -2;
    return;
  }
  s.frames = n;
}

// frames.csv's segment of each row (frame numbers counting up, segments never going back).
bool Recovery::ReadRowSegments(const io::CsvTable& table, std::vector<int>* row_segment,
                               std::map<int, std::int64_t>* rows_per_segment) {
  try {
    const int cf = table.RequireColumn("frame"), cs = table.RequireColumn("segment");
    for (std::size_t r = 0; r < table.rows(); ++r) {
      if (table.Int(r, cf) != static_cast<std::int64_t>(r)) {
        throw table.CellError(r, cf, "frame numbers must count 0, 1, 2, ...");
      }
      const int seg = static_cast<int>(table.Int(r, cs));
      if (!row_segment->empty() && seg < row_segment->back()) throw table.CellError(r, cs, "segment goes backwards");
      row_segment->push_back(seg);
      ++(*rows_per_segment)[seg];
    }
  } catch (const Error& e) {
    Problem(e.what());
    return false;
  }
  return true;
}

// Rows naming frames that are not on disk: cut from the end of frames.csv, a problem anywhere else.
bool Recovery::CutRowsWithoutFrames(const std::string& frames_rel, const LogText& text, const io::CsvTable& table,
                                    const std::vector<SegmentOnDisk>& segs, int last_row_segment,
                                    std::vector<int>* row_segment, std::map<int, std::int64_t>* rows_per_segment) {
  std::int64_t rows_to_keep = static_cast<std::int64_t>(row_segment->size());
  std::map<int, const SegmentOnDisk*> by_index;
  for (const auto& s : segs) {
    if (s.frames >= 0) by_index[s.index] = &s;
  }
  for (const auto& [seg, nrows] : *rows_per_segment) {
    const auto it = by_index.find(seg);
    const std::int64_t on_disk = it == by_index.end() ? 0 : it->second->frames;
    if (nrows > on_disk) {
      if (seg != last_row_segment) {
        Problem(frames_rel + ": segment " + std::to_string(seg) + " has " + std::to_string(nrows) +
                " rows but only " + std::to_string(on_disk) + " frames on disk (not at the end of the recording)");
        return false;
      }
      rows_to_keep -= nrows - on_disk;
      Repair(frames_rel + ": " + std::to_string(nrows - on_disk) + " row(s) at the end name frames not on disk; removed");
    }
  }
  if (rows_to_keep < static_cast<std::int64_t>(row_segment->size())) {
    // Cut the file at the first dropped row (found by its line in the file).
    const std::size_t line = table.Line(static_cast<std::size_t>(rows_to_keep));  // 1-based
    const std::size_t offset = text.line_start[line - 1];
    Truncate(Path(frames_rel), static_cast<std::int64_t>(offset));
    row_segment->resize(static_cast<std::size_t>(rows_to_keep));
    rows_per_segment->clear();
    for (int sgi : *row_segment) ++(*rows_per_segment)[sgi];
  }
  return true;
}

// Frames without a row: removed at the end of the recording, a problem anywhere else; empty segments
// removed. The segments kept go into `video` (in order, also those before a problem).
bool Recovery::CutFramesWithoutRows(std::vector<SegmentOnDisk>* segs, std::map<int, std::int64_t>* rows_per_segment,
                                    int last_row_segment, std::vector<std::string>* video,
                                    std::int64_t* frames_total) {
  for (auto& s : *segs) {
    if (s.frames < 0) continue;
    const std::int64_t rows = rows_per_segment->count(s.index) ? (*rows_per_segment)[s.index] : 0;
    if (s.frames > rows) {
      const bool at_end = s.index >= last_row_segment;
      if (!at_end) {
        Problem(s.rel + ": " + std::to_string(s.frames) + " frames but frames.csv has " + std::to_string(rows) +
                " rows for it (not at the end of the recording)");
        return false;
      }
      Repair(s.rel + ": " + std::to_string(s.frames - rows) + " frame(s) without a time in frames.csv removed");
      if (s.pgm) {
        const std::string pattern = (fs::path(s.path) / "%06d.pgm").string();
        for (std::int64_t k = rows; k < s.frames; ++k) Remove(video::SequenceFramePath(pattern, k));
      } else {
        Truncate(s.path, s.header_bytes + rows * s.frame_bytes);
      }
      s.frames = rows;
    }
    if (s.frames == 0) {
      Repair(s.rel + ": segment without frames removed");
      Remove(s.path);
      continue;
    }
    *frames_total += s.frames;
    video->push_back(s.rel);
  }
  return true;
}

RecoverSummary Recovery::Run() {
  std::error_code ec;
  if (!fs::is_directory(dir_, ec)) throw IoError(dir_, "not a folder");
  const std::string manifest_path = Path(trial::kManifestFile);
  if (!fs::is_regular_file(manifest_path, ec)) throw IoError(manifest_path, "no manifest: not a trial directory");
  // Never touch a recording in progress.
  const int lock = ::open(Path(trial::kCaptureLockFile).c_str(), O_RDONLY | O_CLOEXEC);
  if (lock >= 0) {
    const bool busy = ::flock(lock, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
    ::close(lock);
    if (busy) throw UsageError(dir_ + ": rk-capture is still recording into it (" + trial::kCaptureLockFile + " is held); stop it first");
  }
  const std::string manifest_text = io::ReadFile(manifest_path);
  io::Json m = io::ParseJson(manifest_text, manifest_path);
  if (!m.is_object() || !m.contains("cameras") || !m["cameras"].is_object()) {
    throw DataError(manifest_path, 0, 0, "not a trial manifest (no \"cameras\" object)");
  }
  CheckPathsInside(m, manifest_path, manifest_text);
  const bool by_capture = m.contains("capture") && m["capture"].is_object();
  s_.state_before = by_capture && m["capture"].contains("state") && m["capture"]["state"].is_string()
                        ? m["capture"]["state"].get<std::string>()
                        : "unknown";
  for (auto it = m["cameras"].begin(); it != m["cameras"].end(); ++it) {
    io::Json stream;
    if (by_capture && m["capture"].contains("streams") && m["capture"]["streams"].contains("cameras") &&
        m["capture"]["streams"]["cameras"].contains(it.key())) {
      stream = m["capture"]["streams"]["cameras"][it.key()];
    }
    const std::size_t problems_before = s_.problems.size();
    const std::vector<std::string> video = RecoverCamera(it.key(), it.value(), stream);
    if (!it.value().contains("video") || it.value()["video"] != io::Json(video)) {
      if (s_.problems.size() == problems_before) {
        Repair(std::string(trial::kManifestFile) + ": cameras." + it.key() + ".video set to the " +
               std::to_string(video.size()) + " segment(s) on disk");
        it.value()["video"] = video;
      }
    }
  }
  for (const char* key : {"range", "turret"}) {
    if (m.contains(key) && m[key].is_string()) {
      const std::string rel = m[key].get<std::string>();
      if (std::string(key) == "range") {
        CheckRange(rel);
      } else {
        CheckTurret(rel);
      }
    }
  }
  if (by_capture && fs::is_regular_file(Path(trial::kEventsFile), ec)) {
    ReadLog(trial::kEventsFile);  // a torn last line is cut; the content is free text
  }
  if (by_capture) {
    io::Json& cap = m["capture"];
    if (s_.state_before == "recording") {
      cap["state"] = "recovered";
      Repair(std::string(trial::kManifestFile) + ": state 'recording' (the recording did not stop cleanly) set to 'recovered'");
    }
    s_.state_after = cap.value("state", "unknown");
    io::Json rec;
    rec["tool"] = std::string("rk-capture recover ") + kVersion;
    rec["utc"] = FormatUtc(RealNowNs(), 3);
    rec["repairs"] = s_.repairs;
    rec["problems"] = s_.problems;
    rec["readable"] = s_.problems.empty();
    rec["frames"] = s_.frames;
    rec["rows"] = s_.rows;
    cap["recover"] = rec;
  } else {
    s_.state_after = s_.state_before;
  }
  if (!o_.check_only) io::WriteJson(manifest_path, m);
  return s_;
}

}  // namespace

RecoverSummary RecoverTrial(const std::string& dir, const RecoverOptions& options) {
  Recovery r(dir, options);
  return r.Run();
}

}  // namespace rk::capture

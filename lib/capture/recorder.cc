#include "capture/recorder.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cmath>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>

#include "camera/camera_model.h"
#include "capture/append_log.h"
#include "capture/camera_source.h"
#include "capture/clock.h"
#include "capture/durable_file.h"
#include "capture/segment_writer.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/version.h"
#include "trial/layout.h"
#include "trial/manifest.h"

namespace rk::capture {
namespace fs = std::filesystem;

io::Json CameraSummary::ToJson() const {
  return {{"source_kind", source_kind},   {"format", format},           {"fps", fps},
          {"width", width},               {"height", height},           {"bit_depth", bit_depth},
          {"frames_grabbed", grabbed},    {"frames_written", written},  {"dropped_queue_full", dropped_queue},
          {"dropped_disk_low", dropped_disk}, {"write_failed", write_failed}, {"source_errors", source_errors},
          {"segments", segments},         {"source_ended", ended}};
}

io::Json CaptureSummary::ToJson() const {
  io::Json j;
  j["out"] = out_dir;
  j["stop_reason"] = stop_reason;
  j["recorded_s"] = recorded_s;
  io::Json cams = io::Json::object();
  for (const auto& c : cameras) cams[c.name] = c.ToJson();
  j["cameras"] = cams;
  if (range) {
    j["range"] = range->ToJson();
    j["range"]["rows"] = range_rows;
  }
  if (turret) {
    j["turret"] = turret->ToJson();
    j["turret"]["rows"] = turret_rows;
  }
  j["gaps"] = gaps;
  j["write_failures"] = write_failures;
  j["max_sync_pass_s"] = max_sync_pass_s;
  return j;
}

namespace {

constexpr std::size_t kMaxGapsListed = 10000;

struct GapRecord {
  std::string stream, reason;
  double start_s = 0;
  std::optional<double> end_s;
};

class Recorder;

// One camera: grabber thread → bounded buffer pool → writer thread.
struct CameraStream {
  CameraConfig cfg;
  std::unique_ptr<CameraSource> src;
  double fps = 0;
  std::int64_t frames_per_segment = 1;
  std::string folder;  // absolute

  struct Item {
    int buffer = -1;
    Stamp at;
    std::int64_t seq = 0;
  };
  std::vector<cv::Mat> pool;
  std::vector<int> free_buffers;
  std::deque<Item> queue;
  std::mutex mutex;
  std::condition_variable cv;
  bool grab_done = false;

  std::unique_ptr<AppendLog> frames_log;
  std::unique_ptr<SegmentWriter> writer;
  FrameFormat format;                    // set by the writer thread before have_format
  std::atomic<bool> have_format{false};  // read by the manifest writer
  int segment = -1;
  std::int64_t frame_index = 0;

  std::mutex gap_mutex;
  std::unique_ptr<GapState> gap;
  DeviceReporter reporter;

  std::atomic<std::int64_t> grabbed{0}, written{0}, dropped_queue{0}, dropped_disk{0}, write_failed{0},
      source_errors{0};
  std::atomic<bool> ended{false};
  std::thread grab_thread, write_thread;

  void Fault(const Stamp& at, const std::string& reason) {
    std::lock_guard<std::mutex> lock(gap_mutex);
    gap->Fault(at, reason);
  }
  void Ok(const Stamp& at) {
    std::lock_guard<std::mutex> lock(gap_mutex);
    gap->Ok(at);
  }
};

class Recorder {
 public:
  Recorder(const StationConfig& cfg, const CaptureOptions& opt) : cfg_(cfg), opt_(opt) {}
  ~Recorder() {
    Abort();
    if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
  }

  CaptureSummary Run();

 private:
  // --- set-up ---
  void PrepareFolder();
  void Connect();
  void CreateLogs();
  void Abort();  // before recording starts: stop what runs, remove what was created

  // --- streams ---
  void GrabLoop(CameraStream* cam);
  void WriteLoop(CameraStream* cam);
  void WriteFrame(CameraStream* cam, const CameraStream::Item& item);
  void OnRange(const RangeSample& s);
  void OnTurret(const TurretSample& s);

  // --- events, gaps, manifest ---
  double T(const Stamp& at) const { return epoch_.TrialSeconds(at.mono_ns); }
  void Event(EventLevel level, const std::string& source, const std::string& message);
  void GapBegin(const std::string& stream, AppendLog* log, const Stamp& at, const std::string& reason);
  void GapEnd(const std::string& stream, AppendLog* log, const Stamp& at);
  DeviceReporter MakeReporter(const std::string& stream, AppendLog** log);
  void WriteManifest(const std::string& state);
  // Raises the calling (stamping) thread to the configured real-time priority; records the outcome.
  void RealTime(const std::string& stream);
  io::Json ManifestJson(const std::string& state);
  std::string StatusLine(double t_s);
  CaptureSummary Summarise();

  const StationConfig& cfg_;
  const CaptureOptions& opt_;
  std::string dir_;
  bool created_dir_ = false;
  bool recording_ = false;
  int lock_fd_ = -1;
  TrialEpoch epoch_;
  Stamp started_;
  std::int64_t record_start_ns_ = 0, record_end_ns_ = 0;
  std::unique_ptr<Syncer> syncer_;
  std::unique_ptr<AppendLog> events_;
  std::atomic<std::int64_t> events_lost_{0}, manifest_failures_{0};
  std::atomic<bool> stop_{false};

  std::vector<std::unique_ptr<CameraStream>> cameras_;
  std::unique_ptr<DimetixDriver> range_;
  std::unique_ptr<PtuDriver> turret_;
  std::unique_ptr<AppendLog> range_log_, turret_log_;
  AppendLog* range_log_ptr_ = nullptr;
  AppendLog* turret_log_ptr_ = nullptr;
  std::thread range_thread_, turret_thread_;
  // Disk-side gaps of the device logs (rows that could not be written).
  std::mutex write_gap_mutex_;
  std::unique_ptr<GapState> range_write_gap_, turret_write_gap_;
  DeviceReporter range_write_reporter_, turret_write_reporter_;
  std::atomic<std::int64_t> range_failed_{0}, turret_failed_{0};
  std::atomic<bool> el_warned_{false};
  std::atomic<int> realtime_threads_{0}, normal_threads_{0};
  std::atomic<bool> realtime_warned_{false};

  std::mutex manifest_mutex_;  // gaps_, video lists
  std::vector<GapRecord> gaps_;
  std::int64_t gaps_total_ = 0;
  std::map<std::string, std::vector<std::string>> video_lists_;
  std::string stopped_utc_;
  std::string stop_reason_;

  // Status-line rates.
  std::atomic<double> last_az_{NAN}, last_el_{NAN};
  std::int64_t status_range_rows_ = 0, status_turret_rows_ = 0;
  double status_t_ = 0;
};

void Recorder::PrepareFolder() {
  // dir_ is set only once the folder is ours: Abort() cleans dir_, and must never touch a folder
  // the user had.
  const std::string out = opt_.out_dir;
  std::error_code ec;
  const fs::file_status st = fs::status(out, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) throw UsageError("--out " + out + " exists and is not a folder; nothing was written");
    if (!fs::is_empty(out, ec)) {
      throw UsageError("--out " + out + " exists and is not empty; rk-capture never writes into an existing trial");
    }
    if (::access(out.c_str(), W_OK) != 0) throw IoError(out, "folder is not writable");
  } else {
    fs::create_directories(out, ec);
    if (ec) throw IoError(out, "cannot create folder: " + ec.message());
    created_dir_ = true;
  }
  dir_ = out;
  const std::string lock = (fs::path(dir_) / trial::kCaptureLockFile).string();
  lock_fd_ = ::open(lock.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0 || ::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) throw IoError(lock, "cannot lock the trial folder");
}

void Recorder::Abort() {
  if (recording_) return;
  stop_ = true;
  if (range_thread_.joinable()) range_thread_.join();
  if (turret_thread_.joinable()) turret_thread_.join();
  if (syncer_) syncer_->Stop();
  // Before recording started nothing of value was written: leave the folder as it was found.
  cameras_.clear();
  range_.reset();
  turret_.reset();
  events_.reset();
  range_log_.reset();
  turret_log_.reset();
  syncer_.reset();
  if (!dir_.empty()) {
    std::error_code ec;
    if (created_dir_) {
      fs::remove_all(dir_, ec);
    } else {
      for (const auto& e : fs::directory_iterator(dir_, ec)) fs::remove_all(e.path(), ec);
    }
  }
  dir_.clear();
}

void Recorder::Event(EventLevel level, const std::string& source, const std::string& message) {
  const Stamp at = Now();
  const std::string line = FormatFixed(T(at), 6) + " " + FormatUtc(at.real_ns, 3) + " " + EventLevelName(level) +
                           " " + source + ": " + message;
  if (events_) {
    events_->Post(line);
  } else {
    ++events_lost_;
  }
  if (level != EventLevel::kInfo && opt_.warn) opt_.warn(source + ": " + message);
}

void Recorder::GapBegin(const std::string& stream, AppendLog* log, const Stamp& at, const std::string& reason) {
  const double t = T(at);
  {
    std::lock_guard<std::mutex> lock(manifest_mutex_);
    ++gaps_total_;
    if (gaps_.size() < kMaxGapsListed) gaps_.push_back({stream, reason, t, std::nullopt});
  }
  Event(EventLevel::kWarning, stream, "gap begins: " + reason);
  if (log) log->Post("# gap begins at t_s=" + FormatFixed(t, 6) + ": " + reason);
}

void Recorder::GapEnd(const std::string& stream, AppendLog* log, const Stamp& at) {
  const double t = T(at);
  double start = t;
  {
    std::lock_guard<std::mutex> lock(manifest_mutex_);
    for (auto it = gaps_.rbegin(); it != gaps_.rend(); ++it) {
      if (it->stream == stream && !it->end_s) {
        it->end_s = t;
        start = it->start_s;
        break;
      }
    }
  }
  Event(EventLevel::kInfo, stream, "gap ends after " + FormatFixed(t - start, 3) + " s");
  if (log) log->Post("# gap ends at t_s=" + FormatFixed(t, 6));
}

DeviceReporter Recorder::MakeReporter(const std::string& stream, AppendLog** log) {
  DeviceReporter r;
  r.event = [this, stream](EventLevel level, const std::string& m) { Event(level, stream, m); };
  r.gap_begin = [this, stream, log](const Stamp& at, const std::string& reason) {
    GapBegin(stream, *log, at, reason);
  };
  r.gap_end = [this, stream, log](const Stamp& at) { GapEnd(stream, *log, at); };
  return r;
}

void Recorder::Connect() {
  if (cfg_.rangefinder) {
    range_ = std::make_unique<DimetixDriver>(*cfg_.rangefinder, MakeReporter("range", &range_log_ptr_),
                                             [this](const RangeSample& s) { OnRange(s); });
    std::string why;
    if (!range_->Connect(&why)) throw IoError(cfg_.rangefinder->serial.port, "rangefinder: " + why);
  }
  if (cfg_.turret) {
    turret_ = std::make_unique<PtuDriver>(*cfg_.turret, MakeReporter("turret", &turret_log_ptr_),
                                          [this](const TurretSample& s) { OnTurret(s); });
    std::string why;
    if (!turret_->Connect(&why)) throw IoError(cfg_.turret->serial.port, "turret: " + why);
  }
  for (const CameraConfig& cc : cfg_.cameras) {
    auto cam = std::make_unique<CameraStream>();
    cam->cfg = cc;
    cam->folder = (fs::path(dir_) / cc.name).string();
    cam->src = MakeCameraSource(cc.source);
    std::string why;
    if (!cam->src->Open(&why)) throw IoError(cc.source_text, "camera '" + cc.name + "': " + why);
    cam->fps = cam->src->fps();
    if (std::abs(cam->fps - cc.source.fps) > 1e-6 * cc.source.fps) {
      Event(EventLevel::kWarning, "camera:" + cc.name,
            "runs at " + FormatFixed(cam->fps, 3) + " fps, not the configured " + FormatFixed(cc.source.fps, 3));
    }
    cam->frames_per_segment = std::max<std::int64_t>(1, std::llround(cfg_.segment_s * cam->fps));
    const int queue = cc.queue_frames > 0 ? cc.queue_frames : std::clamp(static_cast<int>(std::floor(cam->fps)), 2, 64);
    cam->pool.resize(static_cast<std::size_t>(queue));
    for (int i = 0; i < queue; ++i) cam->free_buffers.push_back(i);
    cameras_.push_back(std::move(cam));
    Event(EventLevel::kInfo, "camera:" + cc.name,
          "opened " + cameras_.back()->src->kind() + " source '" + cc.source_text + "' at " +
              FormatFixed(cameras_.back()->fps, 3) + " fps, " + std::to_string(queue) + " frame buffers");
  }
}

void Recorder::CreateLogs() {
  const std::string epoch_note = "t_s = seconds since epoch_utc " + epoch_.utc() +
                                 " on CLOCK_MONOTONIC; host_mono_s = CLOCK_MONOTONIC, host_real_s = CLOCK_REALTIME "
                                 "(Unix time) at arrival";
  const std::string version = std::string("# rk-capture ") + kVersion + ": ";
  if (range_) {
    const auto& o = *cfg_.rangefinder;
    range_log_ = std::make_unique<AppendLog>(
        (fs::path(dir_) / trial::kRangeFile).string(),
        version + "Dimetix DLS on " + o.serial.port + ", device " + std::to_string(o.device_id) + ", " +
            (o.mode == DimetixMode::kTracking ? "tracking" : "single") + " mode; " + epoch_note + "\n" + trial::kRangeColumns +
            "\n",
        syncer_.get());
    range_log_ptr_ = range_log_.get();
  }
  if (turret_) {
    const auto& o = *cfg_.turret;
    const auto st = turret_->stats();
    turret_log_ = std::make_unique<AppendLog>(
        (fs::path(dir_) / trial::kTurretFile).string(),
        version + "FLIR PTU on " + o.serial.port + "; az = wrap360(" + FormatFixed(o.map.pan_zero_deg, 6) + " + " +
            FormatFixed(o.map.pan_sign, 0) + " * pan_pos * pan_res_arcsec / 3600), el = " +
            FormatFixed(o.map.tilt_zero_deg, 6) + " + " + FormatFixed(o.map.tilt_sign, 0) +
            " * tilt_pos * tilt_res_arcsec / 3600; resolution read from the unit: pan " +
            FormatFixed(st.pan_res_arcsec, 6) + ", tilt " + FormatFixed(st.tilt_res_arcsec, 6) +
            " arcsec per position; " + epoch_note + "\n" + trial::kTurretColumns + "\n",
        syncer_.get());
    turret_log_ptr_ = turret_log_.get();
  }
  range_write_gap_ = std::make_unique<GapState>(&range_write_reporter_);
  turret_write_gap_ = std::make_unique<GapState>(&turret_write_reporter_);
  range_write_reporter_ = MakeReporter("range", &range_log_ptr_);
  turret_write_reporter_ = MakeReporter("turret", &turret_log_ptr_);
  // Rows that the disk refused: counted and marked as a gap of the stream (comment lines aside).
  auto on_result = [this](GapState* gap, std::atomic<std::int64_t>* failed, const char* file) {
    return [this, gap, failed, file](const std::string& line, bool ok, const std::string& why) {
      if (!line.empty() && line[0] == '#') return;
      std::lock_guard<std::mutex> lock(write_gap_mutex_);
      if (ok) {
        gap->Ok(Now());
      } else {
        ++*failed;
        gap->Fault(Now(), std::string(file) + " not written: " + why);
      }
    };
  };
  if (range_log_) range_log_->set_on_result(on_result(range_write_gap_.get(), &range_failed_, trial::kRangeFile));
  if (turret_log_) turret_log_->set_on_result(on_result(turret_write_gap_.get(), &turret_failed_, trial::kTurretFile));
  for (auto& cam : cameras_) {
    cam->frames_log = std::make_unique<AppendLog>(
        (fs::path(cam->folder) / trial::kFramesFile).string(),
        version + "camera " + cam->cfg.name + ", source '" + cam->cfg.source_text + "'; " + epoch_note +
            "; seq = source frame counter (a jump = frames dropped)\n" + trial::kFramesColumns + "\n",
        syncer_.get());
    AppendLog* log = cam->frames_log.get();
    CameraStream* c = cam.get();
    const std::string stream = "camera:" + cam->cfg.name;
    cam->reporter.event = [this, stream](EventLevel level, const std::string& m) { Event(level, stream, m); };
    cam->reporter.gap_begin = [this, stream, log](const Stamp& at, const std::string& r) {
      GapBegin(stream, log, at, r);
    };
    cam->reporter.gap_end = [this, stream, log](const Stamp& at) { GapEnd(stream, log, at); };
    cam->gap = std::make_unique<GapState>(&c->reporter);
    video_lists_[cam->cfg.name] = {};
  }
}

void Recorder::OnRange(const RangeSample& s) {
  const double t = T(s.stamp) - cfg_.rangefinder->latency_s;
  std::string row = FormatFixed(t, 9) + ",";
  if (s.distance_01mm) row += FormatFixed(static_cast<double>(*s.distance_01mm) / 10000.0, 4);
  row += "," + std::to_string(s.status) + "," + FormatFixed(static_cast<double>(s.stamp.mono_ns) * 1e-9, 9) + "," +
         FormatFixed(static_cast<double>(s.stamp.real_ns) * 1e-9, 6);
  range_log_->Post(std::move(row));  // never wait for the disk on the stamping thread
}

void Recorder::OnTurret(const TurretSample& s) {
  const auto& o = *cfg_.turret;
  const double t = T(s.stamp) - o.latency_s;
  const double az = o.map.AzimuthDeg(s.pan_pos, s.pan_res_arcsec);
  const double el = o.map.ElevationDeg(s.tilt_pos, s.tilt_res_arcsec);
  const bool el_ok = el >= -90.0 && el <= 90.0;
  if (!el_ok && !el_warned_.exchange(true)) {
    Event(EventLevel::kWarning, "turret",
          "elevation " + FormatFixed(el, 3) + " deg outside [-90, 90]: check tilt_zero_deg / tilt_sign; such rows "
          "have empty angles");
  }
  std::string row = FormatFixed(t, 9) + "," + (el_ok ? FormatFixed(az, 9) : "") + "," +
                    (el_ok ? FormatFixed(el, 9) : "") + "," + std::to_string(s.pan_pos) + "," +
                    std::to_string(s.tilt_pos) + "," + FormatFixed(s.pan_res_arcsec, 6) + "," +
                    FormatFixed(s.tilt_res_arcsec, 6) + "," + FormatFixed(s.pair_dt_s, 6) + "," +
                    FormatFixed(static_cast<double>(s.stamp.mono_ns) * 1e-9, 9) + "," +
                    FormatFixed(static_cast<double>(s.stamp.real_ns) * 1e-9, 6);
  if (el_ok) {
    last_az_ = az;
    last_el_ = el;
  }
  turret_log_->Post(std::move(row));
}

void Recorder::GrabLoop(CameraStream* cam) {
  std::int64_t seq = 0;
  cv::Mat discard;
  while (!stop_.load()) {
    int b = -1;
    {
      std::lock_guard<std::mutex> lock(cam->mutex);
      if (!cam->free_buffers.empty()) {
        b = cam->free_buffers.back();
        cam->free_buffers.pop_back();
      }
    }
    cv::Mat* target = b >= 0 ? &cam->pool[static_cast<std::size_t>(b)] : &discard;
    Stamp at;
    std::string why;
    GrabResult r = GrabResult::kError;
    try {
      r = cam->src->Grab(target, &at, &why, stop_);
    } catch (const std::exception& e) {
      why = e.what();
      r = GrabResult::kError;
    }
    if (r == GrabResult::kFrame) {
      ++cam->grabbed;
      if (b < 0) {
        ++cam->dropped_queue;
        cam->Fault(at, "frames dropped: " + std::to_string(cam->pool.size()) +
                           " frames already wait for the disk (seq " + std::to_string(seq) + ")");
      } else {
        std::lock_guard<std::mutex> lock(cam->mutex);
        cam->queue.push_back({b, at, seq});
        cam->cv.notify_one();
      }
      ++seq;
      continue;
    }
    if (b >= 0) {
      std::lock_guard<std::mutex> lock(cam->mutex);
      cam->free_buffers.push_back(b);
    }
    if (r == GrabResult::kStopped) break;
    if (r == GrabResult::kEnd) {
      cam->ended = true;
      Event(EventLevel::kInfo, "camera:" + cam->cfg.name, "source ended after " + std::to_string(seq) + " frames");
      break;
    }
    ++cam->source_errors;
    cam->Fault(Now(), why);
    // Reopen after a pause (a camera unplugged and plugged back in).
    cam->src->Close();
    if (!SleepUntil(MonoNowNs() + kNsPerS, stop_)) break;
    std::string owhy;
    if (cam->src->Open(&owhy)) {
      Event(EventLevel::kInfo, "camera:" + cam->cfg.name, "reopened");
    }
  }
  std::lock_guard<std::mutex> lock(cam->mutex);
  cam->grab_done = true;
  cam->cv.notify_all();
}

void Recorder::WriteFrame(CameraStream* cam, const CameraStream::Item& item) {
  const cv::Mat& frame = cam->pool[static_cast<std::size_t>(item.buffer)];
  const std::string stream = "camera:" + cam->cfg.name;
  if (!cam->have_format) {
    cam->format = {frame.cols, frame.rows, frame.depth() == CV_16U ? 16 : 8, cam->fps};
    cam->writer = MakeSegmentWriter(cam->cfg.format, dir_, cam->cfg.name, cam->format, syncer_.get());
    cam->have_format.store(true, std::memory_order_release);
    if (!cam->cfg.model_path.empty()) {
      try {
        const camera::CameraModel m = camera::LoadCameraModel(cam->cfg.model_path);
        if (m.width_px != frame.cols || m.height_px != frame.rows) {
          Event(EventLevel::kWarning, stream,
                "frames are " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                    " but the camera model says " + std::to_string(m.width_px) + "x" + std::to_string(m.height_px));
        }
      } catch (const std::exception&) {
      }
    }
    Event(EventLevel::kInfo, stream,
          "frames " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) + " " +
              std::to_string(cam->format.bit_depth) + "-bit, written as " + cam->cfg.format + " segments of " +
              std::to_string(cam->frames_per_segment) + " frames");
  }
  // Keep the last of the disk for the small streams (range, turret, events, manifest).
  const std::int64_t free = syncer_->free_bytes();
  if (free >= 0 && static_cast<double>(free) < cfg_.min_free_mb * 1e6) {
    ++cam->dropped_disk;
    cam->Fault(item.at, "disk almost full (" + FormatFixed(static_cast<double>(free) / 1e6, 0) + " MB free, min_free_mb " +
                            FormatFixed(cfg_.min_free_mb, 0) + "): frames dropped");
    return;
  }
  std::string why;
  if (!cam->writer->open() || cam->writer->frames_in_segment() >= cam->frames_per_segment) {
    if (cam->writer->open()) cam->writer->End();
    if (!cam->writer->Begin(cam->segment + 1, &why)) {
      ++cam->write_failed;
      cam->Fault(item.at, "cannot start segment " + std::to_string(cam->segment + 1) + ": " + why);
      return;
    }
    ++cam->segment;
  }
  if (!cam->writer->Write(frame, &why)) {
    ++cam->write_failed;
    cam->Fault(item.at, "frame not written: " + why);
    // A file-size limit (RLIMIT_FSIZE, a FAT file system's 4 GiB): go on in a new segment.
    if (cam->writer->file_too_large() && cam->writer->frames_in_segment() > 0) cam->writer->End();
    return;
  }
  const std::string row = std::to_string(cam->frame_index) + "," + FormatFixed(T(item.at), 9) + "," +
                          FormatFixed(static_cast<double>(item.at.mono_ns) * 1e-9, 9) + "," +
                          FormatFixed(static_cast<double>(item.at.real_ns) * 1e-9, 6) + "," +
                          std::to_string(item.seq) + "," + std::to_string(cam->segment);
  if (!cam->frames_log->Append(row, &why)) {
    // The frame stays only if its time is on disk too.
    std::string uwhy;
    cam->writer->UndoLast(&uwhy);
    ++cam->write_failed;
    cam->Fault(item.at, "frames.csv not written (" + why + "): frame removed");
    return;
  }
  syncer_->NoteWritten(static_cast<std::int64_t>(frame.total() * frame.elemSize()));
  ++cam->frame_index;
  ++cam->written;
  if (cam->writer->frames_in_segment() == 1) {
    std::lock_guard<std::mutex> lock(manifest_mutex_);
    video_lists_[cam->cfg.name].push_back(cam->writer->SegmentPath(cam->segment));
  }
  cam->Ok(item.at);
}

void Recorder::WriteLoop(CameraStream* cam) {
  while (true) {
    CameraStream::Item item;
    {
      std::unique_lock<std::mutex> lock(cam->mutex);
      cam->cv.wait(lock, [&] { return !cam->queue.empty() || cam->grab_done; });
      if (cam->queue.empty()) break;
      item = cam->queue.front();
      cam->queue.pop_front();
    }
    try {
      WriteFrame(cam, item);
    } catch (const std::exception& e) {
      ++cam->write_failed;
      cam->Fault(item.at, std::string("frame not written: ") + e.what());
    }
    std::lock_guard<std::mutex> lock(cam->mutex);
    cam->free_buffers.push_back(item.buffer);
  }
  if (cam->writer) cam->writer->End();
}

io::Json Recorder::ManifestJson(const std::string& state) {
  trial::Manifest m;
  const std::string name = !cfg_.name.empty() ? cfg_.name : fs::path(dir_).lexically_normal().filename().string();
  m.name = name.empty() || name == "." ? "trial" : name;
  m.epoch_utc = epoch_.utc();
  m.station = cfg_.station;
  std::lock_guard<std::mutex> lock(manifest_mutex_);
  for (const auto& cam : cameras_) {
    trial::CameraRole role = trial::CameraRole::kBeacon;
    trial::ParseCameraRole(cam->cfg.role, &role);  // checked by the station configuration's reader
    trial::CameraEntry c = trial::CameraInItsFolder(cam->cfg.name, role, video_lists_[cam->cfg.name]);
    if (cam->cfg.model_path.empty()) c.model.clear();  // written as null
    if (!cam->cfg.target_path.empty()) c.target = trial::CameraFile(cam->cfg.name, trial::kTargetModelFile);
    m.cameras.push_back(c);
  }
  if (turret_) m.turret = trial::kTurretFile;
  if (range_) m.range = trial::kRangeFile;
  m.steps = cfg_.steps;

  io::Json cap;
  cap["tool"] = "rk-capture";
  cap["version"] = kVersion;
  cap["command_line"] = opt_.command_line;
  cap["state"] = state;
  char host[256] = {0};
  ::gethostname(host, sizeof host - 1);
  cap["host"] = host;
  cap["started_utc"] = FormatUtc(started_.real_ns, 6);
  cap["updated_utc"] = FormatUtc(RealNowNs(), 6);
  cap["stopped_utc"] = stopped_utc_.empty() ? io::Json(nullptr) : io::Json(stopped_utc_);
  cap["stop_reason"] = stop_reason_.empty() ? io::Json(nullptr) : io::Json(stop_reason_);
  cap["recording_start_s"] = epoch_.TrialSeconds(record_start_ns_);
  cap["recording_end_s"] = record_end_ns_ > 0 ? io::Json(epoch_.TrialSeconds(record_end_ns_)) : io::Json(nullptr);
  cap["clocks"] = DescribeClocks(epoch_);
  cap["sync_s"] = cfg_.sync_s;
  cap["stamping_threads"] = {{"realtime_priority", cfg_.realtime_priority},
                             {"realtime", realtime_threads_.load()},
                             {"normal", normal_threads_.load()}};
  cap["events"] = trial::kEventsFile;
  cap["config_path"] = cfg_.path;
  cap["config"] = cfg_.json;
  io::Json streams;
  io::Json scams = io::Json::object();
  for (const auto& cam : cameras_) {
    io::Json c;
    c["source"] = cam->cfg.source_text;
    c["source_kind"] = cam->src->kind();
    c["fps"] = cam->fps;
    c["format"] = cam->cfg.format;
    c["frames_per_segment"] = cam->frames_per_segment;
    const bool known = cam->have_format.load(std::memory_order_acquire);
    c["width"] = known ? io::Json(cam->format.width) : io::Json(nullptr);
    c["height"] = known ? io::Json(cam->format.height) : io::Json(nullptr);
    c["bit_depth"] = known ? io::Json(cam->format.bit_depth) : io::Json(nullptr);
    c["frames_grabbed"] = cam->grabbed.load();
    c["frames_written"] = cam->written.load();
    c["dropped_queue_full"] = cam->dropped_queue.load();
    c["dropped_disk_low"] = cam->dropped_disk.load();
    c["write_failed"] = cam->write_failed.load();
    c["source_errors"] = cam->source_errors.load();
    c["source_ended"] = cam->ended.load();
    scams[cam->cfg.name] = c;
  }
  streams["cameras"] = scams;
  if (range_) {
    io::Json r = range_->stats().ToJson();
    r["options"] = cfg_.rangefinder->ToJson();
    r["rows"] = range_log_ ? range_log_->lines() : 0;
    r["rows_not_written"] = range_failed_.load();
    streams["range"] = r;
  }
  if (turret_) {
    io::Json t = turret_->stats().ToJson();
    t["options"] = cfg_.turret->ToJson();
    t["rows"] = turret_log_ ? turret_log_->lines() : 0;
    t["rows_not_written"] = turret_failed_.load();
    streams["turret"] = t;
  }
  cap["streams"] = streams;
  io::Json gaps = io::Json::array();
  for (const auto& g : gaps_) {
    gaps.push_back({{"stream", g.stream},
                    {"start_s", g.start_s},
                    {"end_s", g.end_s ? io::Json(*g.end_s) : io::Json(nullptr)},
                    {"reason", g.reason}});
  }
  cap["gaps"] = gaps;
  cap["gaps_total"] = gaps_total_;
  cap["events_not_written"] = events_lost_.load();
  m.extra["capture"] = cap;
  return trial::ManifestToJson(m);
}

void Recorder::RealTime(const std::string& stream) {
  if (cfg_.realtime_priority <= 0) return;
  std::string why;
  if (RaiseThreadPriority(cfg_.realtime_priority, &why)) {
    ++realtime_threads_;
  } else {
    ++normal_threads_;
    if (!realtime_warned_.exchange(true)) {
      Event(EventLevel::kInfo, stream,
            "real-time priority " + std::to_string(cfg_.realtime_priority) + " not granted (" + why +
                "): arrival stamps may be late while the CPUs are busy");
    }
  }
}

void Recorder::WriteManifest(const std::string& state) {
  try {
    io::WriteJson((fs::path(dir_) / trial::kManifestFile).string(), ManifestJson(state));
    if (syncer_) syncer_->DirectoryChanged(dir_);
  } catch (const std::exception& e) {
    if (manifest_failures_++ == 0) Event(EventLevel::kError, "manifest", std::string("not updated: ") + e.what());
  }
}

std::string Recorder::StatusLine(double t_s) {
  std::string s = "rk-capture " + FormatFixed(t_s, 1) + " s";
  for (const auto& cam : cameras_) {
    s += " | " + cam->cfg.name + " " + std::to_string(cam->written.load()) + " fr";
    const std::int64_t drops = cam->dropped_queue.load() + cam->dropped_disk.load() + cam->write_failed.load();
    s += " " + std::to_string(drops) + " drop";
    if (cam->ended.load()) s += " (ended)";
  }
  const double dt = t_s - status_t_;
  if (range_log_) {
    const std::int64_t rows = range_log_->lines();
    s += " | range " + (dt > 0 ? FormatFixed(static_cast<double>(rows - status_range_rows_) / dt, 1) : "-") + " Hz";
    status_range_rows_ = rows;
  }
  if (turret_log_) {
    const std::int64_t rows = turret_log_->lines();
    s += " | turret " + (dt > 0 ? FormatFixed(static_cast<double>(rows - status_turret_rows_) / dt, 1) : "-") +
         " Hz az " + FormatFixed(last_az_.load(), 4) + " el " + FormatFixed(last_el_.load(), 4);
    status_turret_rows_ = rows;
  }
  status_t_ = t_s;
  std::int64_t gaps = 0;
  {
    std::lock_guard<std::mutex> lock(manifest_mutex_);
    gaps = gaps_total_;
  }
  s += " | gaps " + std::to_string(gaps);
  const std::int64_t free = syncer_->free_bytes();
  if (free >= 0) s += " | " + FormatFixed(static_cast<double>(free) / 1e9, 1) + " GB free";
  return s;
}

CaptureSummary Recorder::Summarise() {
  CaptureSummary s;
  s.out_dir = dir_;
  s.stop_reason = stop_reason_;
  s.recorded_s = static_cast<double>(record_end_ns_ - record_start_ns_) * 1e-9;
  for (const auto& cam : cameras_) {
    CameraSummary c;
    c.name = cam->cfg.name;
    c.source_kind = cam->src->kind();
    c.format = cam->cfg.format;
    c.fps = cam->fps;
    c.width = cam->format.width;
    c.height = cam->format.height;
    c.bit_depth = cam->have_format ? cam->format.bit_depth : 0;
    c.grabbed = cam->grabbed;
    c.written = cam->written;
    c.dropped_queue = cam->dropped_queue;
    c.dropped_disk = cam->dropped_disk;
    c.write_failed = cam->write_failed;
    c.source_errors = cam->source_errors;
    c.segments = cam->segment + 1;
    c.ended = cam->ended;
    s.write_failures += c.dropped_disk + c.write_failed;
    s.cameras.push_back(c);
  }
  if (range_) {
    s.range = range_->stats();
    s.range_rows = range_log_->lines();
  }
  if (turret_) {
    s.turret = turret_->stats();
    s.turret_rows = turret_log_->lines();
  }
  {
    std::lock_guard<std::mutex> lock(manifest_mutex_);
    s.gaps = gaps_total_;
  }
  s.write_failures += range_failed_ + turret_failed_ + events_lost_ + manifest_failures_;
  s.max_sync_pass_s = syncer_->max_pass_s();
  return s;
}

CaptureSummary Recorder::Run() {
  std::string why;
  if (!opt_.Check(&why)) throw UsageError(why);
  PrepareFolder();
  // A write past RLIMIT_FSIZE must fail with EFBIG (and be handled), not kill the process.
  ::signal(SIGXFSZ, SIG_IGN);
  started_ = Now();
  epoch_ = TrialEpoch::FromStamp(started_);
  syncer_ = std::make_unique<Syncer>(dir_, cfg_.sync_s);
  if (opt_.free_space_probe) syncer_->set_free_space_probe(opt_.free_space_probe);
  syncer_->set_on_error([this](const std::string& w) { Event(EventLevel::kError, "disk", w); });
  events_ = std::make_unique<AppendLog>((fs::path(dir_) / trial::kEventsFile).string(), "", syncer_.get());
  events_->set_on_result([this](const std::string&, bool ok, const std::string&) {
    if (!ok) ++events_lost_;
  });
  syncer_->Start();
  Event(EventLevel::kInfo, "capture",
        std::string("rk-capture ") + kVersion + " started; epoch " + epoch_.utc() + "; config " + cfg_.path);
  for (const auto& w : cfg_.warnings) Event(EventLevel::kInfo, "config", w);

  // Models and targets beside the recording, so the trial folder stands alone.
  for (const CameraConfig& cc : cfg_.cameras) {
    const fs::path folder = fs::path(dir_) / cc.name;
    std::error_code ec;
    fs::create_directory(folder, ec);
    if (ec) throw IoError(folder.string(), "cannot create folder: " + ec.message());
    if (!cc.model_path.empty()) io::WriteFileAtomic((folder / trial::kCameraModelFile).string(), io::ReadFile(cc.model_path));
    if (!cc.target_path.empty()) io::WriteFileAtomic((folder / trial::kTargetModelFile).string(), io::ReadFile(cc.target_path));
  }
  Connect();
  CreateLogs();
  record_start_ns_ = MonoNowNs();
  WriteManifest("recording");

  // Recording: from here on nothing throws out of Run; faults become events and gaps.
  recording_ = true;
  Event(EventLevel::kInfo, "capture", "recording");
  for (auto& cam : cameras_) {
    CameraStream* c = cam.get();
    c->write_thread = std::thread([this, c] { WriteLoop(c); });
    c->grab_thread = std::thread([this, c] {
      RealTime("camera:" + c->cfg.name);
      GrabLoop(c);
    });
  }
  if (range_) {
    range_thread_ = std::thread([this] {
      RealTime("range");
      range_->Run(stop_);
    });
  }
  if (turret_) {
    turret_thread_ = std::thread([this] {
      RealTime("turret");
      turret_->Run(stop_);
    });
  }

  const std::int64_t manifest_period = static_cast<std::int64_t>(cfg_.manifest_s * 1e9);
  const std::int64_t status_period = static_cast<std::int64_t>(opt_.status_period_s * 1e9);
  const std::int64_t end_ns = opt_.duration_s > 0 ? record_start_ns_ + static_cast<std::int64_t>(opt_.duration_s * 1e9)
                                                  : INT64_MAX;
  std::int64_t next_manifest = record_start_ns_ + manifest_period, next_status = record_start_ns_ + status_period;
  status_t_ = epoch_.TrialSeconds(record_start_ns_);
  while (true) {
    const std::int64_t now = MonoNowNs();
    if (opt_.stop && opt_.stop->load()) {
      stop_reason_ = "signal";
      break;
    }
    if (now >= end_ns) {
      stop_reason_ = "duration";
      break;
    }
    if (!range_ && !turret_ && !cameras_.empty()) {
      bool all_ended = true;
      for (const auto& cam : cameras_) all_ended = all_ended && cam->ended.load();
      if (all_ended) {
        stop_reason_ = "sources ended";
        break;
      }
    }
    if (now >= next_manifest) {
      WriteManifest("recording");
      next_manifest += manifest_period;
      if (next_manifest < now) next_manifest = now + manifest_period;
    }
    if (opt_.status && now >= next_status) {
      opt_.status(StatusLine(epoch_.TrialSeconds(now)));
      next_status += status_period;
      if (next_status < now) next_status = now + status_period;
    }
    const std::int64_t wake = std::min({end_ns, next_manifest, opt_.status ? next_status : INT64_MAX, now + 50000000});
    const std::int64_t sleep_ns = std::max<std::int64_t>(0, wake - now);
    timespec ts{static_cast<time_t>(sleep_ns / kNsPerS), static_cast<long>(sleep_ns % kNsPerS)};
    ::nanosleep(&ts, nullptr);
  }
  record_end_ns_ = MonoNowNs();
  Event(EventLevel::kInfo, "capture", "stopping (" + stop_reason_ + ")");
  stop_ = true;
  for (auto& cam : cameras_) {
    if (cam->grab_thread.joinable()) cam->grab_thread.join();
    if (cam->write_thread.joinable()) cam->write_thread.join();
    cam->src->Close();
  }
  if (range_thread_.joinable()) range_thread_.join();
  if (turret_thread_.joinable()) turret_thread_.join();
  stopped_utc_ = FormatUtc(RealNowNs(), 6);
  Event(EventLevel::kInfo, "capture",
        "stopped after " + FormatFixed(static_cast<double>(record_end_ns_ - record_start_ns_) * 1e-9, 3) + " s");
  // Everything posted reaches the files before the last sync.
  if (range_log_) range_log_->Drain();
  if (turret_log_) turret_log_->Drain();
  for (auto& cam : cameras_) cam->frames_log->Drain();
  events_->Drain();
  syncer_->Stop();
  WriteManifest("complete");
  std::string dwhy;
  SyncDirectory(dir_, &dwhy);
  CaptureSummary summary = Summarise();
  return summary;
}

}  // namespace

CaptureSummary RunCapture(const StationConfig& config, const CaptureOptions& options) {
  Recorder r(config, options);
  return r.Run();
}

}  // namespace rk::capture

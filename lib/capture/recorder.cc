// rk-capture's recording (capture/recorder.h): the summaries, and the Recorder's life — folder, set-up in
// order, threads, supervision, stop. Its other parts are listed in capture/recorder_internal.h.
#include "capture/recorder.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <thread>

#include "capture/recorder_internal.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/version.h"
#include "trial/layout.h"

namespace rk::capture {
namespace fs = std::filesystem;

io::Json CameraSummary::ToJson() const {
  return {{"source_kind", source_kind},   {"format", format},           {"fps", fps},
          {"width", width},               {"height", height},           {"bit_depth", bit_depth},
          {"frames_grabbed", grabbed},    {"frames_written", written},  {"dropped_queue_full", dropped_queue},
          {"dropped_disk_low", dropped_disk}, {"write_failed", write_failed}, {"source_errors", source_errors},
          {"frames_outside_recording", outside}, {"segments", segments},         {"source_ended", ended},      {"stream", stream}};
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

namespace internal {

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

CaptureSummary Recorder::Run() {
  std::string why;
  if (!opt_.Check(&why)) throw UsageError(why);
  PrepareFolder();
  // A write past RLIMIT_FSIZE must fail with EFBIG (and be handled), not kill the process.
  ::signal(SIGXFSZ, SIG_IGN);
  StartDisk();
  CopyModels();
  Connect();
  CreateLogs();
  record_start_ns_ = MonoNowNs();
  if (opt_.duration_s > 0) record_stop_ns_ = record_start_ns_ + static_cast<std::int64_t>(opt_.duration_s * 1e9);
  WriteManifest("recording");

  // Recording: from here on nothing throws out of Run; faults become events and gaps.
  recording_ = true;
  Event(EventLevel::kInfo, "capture", "recording");
  StartThreads();
  Supervise();
  StopAndFlush();
  CaptureSummary summary = Summarise();
  return summary;
}

void Recorder::StartDisk() {
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
}

// Models and targets beside the recording, so the trial folder stands alone.
void Recorder::CopyModels() {
  for (const CameraConfig& cc : cfg_.cameras) {
    const fs::path folder = fs::path(dir_) / cc.name;
    std::error_code ec;
    fs::create_directory(folder, ec);
    if (ec) throw IoError(folder.string(), "cannot create folder: " + ec.message());
    if (!cc.model_path.empty()) io::WriteFileAtomic((folder / trial::kCameraModelFile).string(), io::ReadFile(cc.model_path));
    if (!cc.target_path.empty()) io::WriteFileAtomic((folder / trial::kTargetModelFile).string(), io::ReadFile(cc.target_path));
  }
  if (!cfg_.pointing_path.empty()) {
    io::WriteFileAtomic((fs::path(dir_) / trial::kPointingFile).string(), io::ReadFile(cfg_.pointing_path));
  }
}

void Recorder::StartThreads() {
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
}

void Recorder::Supervise() {
  const std::int64_t manifest_period = static_cast<std::int64_t>(cfg_.manifest_s * 1e9);
  const std::int64_t status_period = static_cast<std::int64_t>(opt_.status_period_s * 1e9);
  const std::int64_t end_ns = record_stop_ns_;
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
}

void Recorder::StopAndFlush() {
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
}

}  // namespace internal

CaptureSummary RunCapture(const StationConfig& config, const CaptureOptions& options) {
  internal::Recorder r(config, options);
  return r.Run();
}

}  // namespace rk::capture

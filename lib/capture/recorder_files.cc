// The recorder's trial files (SPEC.md §6, names from lib/trial): the stream logs with their header lines,
// and trial.json with its "capture" object, rewritten while recording.
#include "capture/recorder_internal.h"

#include <exception>
#include <filesystem>

#include "io/file_util.h"
#include "io/version.h"
#include "trial/layout.h"
#include "trial/manifest.h"

namespace rk::capture::internal {
namespace fs = std::filesystem;

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
            "; seq = source frame counter (a jump = frames dropped)" +
            (cam->src->has_camera_clock()
                 ? "; camera_ts_s = the camera's own time stamp of the frame, its clock as it reads it (not re-based); "
                   "t_s = that stamp mapped onto the host clock (camera clock mapping followed as the run goes) "
                   "where time_source is camera, else the arrival"
                 : "") +
            "\n" + trial::kFramesColumns + (cam->src->has_camera_clock() ? ",camera_ts_s,time_source" : "") + "\n",
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

io::Json Recorder::ManifestJson(const std::string& state) {
  trial::Manifest m;
  const std::string name = !cfg_.name.empty() ? cfg_.name : fs::path(dir_).lexically_normal().filename().string();
  m.name = name.empty() || name == "." ? "trial" : name;
  m.epoch_utc = epoch_.utc();
  m.Single().station = cfg_.station;
  std::lock_guard<std::mutex> lock(manifest_mutex_);
  for (const auto& cam : cameras_) {
    trial::CameraRole role = trial::CameraRole::kBeacon;
    trial::ParseCameraRole(cam->cfg.role, &role);  // checked by the station configuration's reader
    trial::CameraEntry c = trial::CameraInItsFolder(cam->cfg.name, role, video_lists_[cam->cfg.name]);
    if (cam->cfg.model_path.empty()) c.model.clear();  // written as null
    if (!cam->cfg.target_path.empty()) c.target = trial::CameraFile(cam->cfg.name, trial::kTargetModelFile);
    m.Single().cameras.push_back(c);
  }
  if (turret_) m.Single().turret = trial::kTurretFile;
  if (range_) m.Single().range = trial::kRangeFile;
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
  cap["streams"] = StreamsJson();
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

// The manifest's "capture.streams": each camera's source, format and counters, each device's statistics.
io::Json Recorder::StreamsJson() {
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
    c["frames_outside_recording"] = cam->outside.load();
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
  return streams;
}

void Recorder::WriteManifest(const std::string& state) {
  try {
    io::WriteJson((fs::path(dir_) / trial::kManifestFile).string(), ManifestJson(state));
    if (syncer_) syncer_->DirectoryChanged(dir_);
  } catch (const std::exception& e) {
    if (manifest_failures_++ == 0) Event(EventLevel::kError, "manifest", std::string("not updated: ") + e.what());
  }
}

}  // namespace rk::capture::internal

// The recorder's reporting: events (events.log, warnings to the caller), gaps of a stream (manifest and
// "# gap" comment lines), the live status line and the summary at the end.
#include "capture/recorder_internal.h"

namespace rk::capture::internal {

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
    c.outside = cam->outside;
    c.dropped_queue = cam->dropped_queue;
    c.dropped_disk = cam->dropped_disk;
    c.write_failed = cam->write_failed;
    c.source_errors = cam->source_errors;
    c.segments = cam->segment + 1;
    c.ended = cam->ended;
    c.stream = cam->src->StreamReport();
    if (c.stream.is_object()) {
      std::lock_guard<std::mutex> lock(cam->mutex);
      c.stream["camera_clock"] = cam->clock_fit.ToJson();
    }
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

}  // namespace rk::capture::internal

// The recorder's cameras: per camera a grabber thread (stamps frames into a bounded buffer pool, drops and
// counts a frame with no free buffer, reopens a failing source) and a writer thread (segment first, then the
// frames.csv row, so frames.csv never names a frame that is not on disk).
#include "capture/recorder_internal.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "camera/camera_model.h"

namespace rk::capture::internal {

namespace {
constexpr double kSilencePeriods = 5.0;  // a camera stamp step beyond this many frame periods ...
constexpr double kSilenceMinS = 0.2;     // ... and this long is a gap
// A camera stamp step that differs from the host's arrival step by more than this is the camera's clock
// stepping (reset, PTP set), not a silence: longer than any stall of the host (Aravis holds a second of frames).
constexpr double kClockStepMinS = 10.0;
}  // namespace

void CameraStream::ClockFit::Add(double camera_s, double host_s) {
  if (n == 0) {
    x0 = camera_s;
    y0 = host_s;
  }
  const double x = camera_s - x0, y = host_s - y0;
  ++n;
  sx += x;
  sy += y;
  sxx += x * x;
  sxy += x * y;
  syy += y * y;
}

io::Json CameraStream::ClockFit::ToJson() const {
  if (n < 2) return nullptr;
  const double m = static_cast<double>(n);
  const double vxx = sxx - sx * sx / m, vxy = sxy - sx * sy / m, vyy = syy - sy * sy / m;
  if (!(vxx > 0)) return nullptr;
  const double slope = vxy / vxx;
  const double intercept = (sy - slope * sx) / m;  // host − y0 at camera = x0
  const double rss = std::max(0.0, vyy - slope * vxy);
  // The host's arrival time lags the exposure by the transfer: the offset includes it (a constant), the
  // residual is the host's jitter about the line.
  return {{"frames", n},
          {"offset_s", y0 + intercept - x0},
          {"drift_ppm", (slope - 1.0) * 1e6},
          {"residual_rms_s", n > 2 ? std::sqrt(rss / (m - 2.0)) : 0.0},
          {"model", "host_mono_s = offset_s + camera_ts_s + drift_ppm·1e-6·(camera_ts_s − first camera_ts_s)"},
          {"first_camera_ts_s", x0}};
}

void Recorder::GrabLoop(CameraStream* cam) {
  std::int64_t seq = 0;
  cv::Mat discard;
  std::int64_t last_camera_ns = -1;  // the camera's own stamps: a silence, a clock that went back
  bool new_clock_unqueued = false;     // a clock step seen on a frame that found no free buffer
  Stamp last_at;
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
    if (r == GrabResult::kFrame && (at.mono_ns < record_start_ns_ || at.mono_ns >= record_stop_ns_)) {
      // Outside the recording (sent before it began, or after --duration): not part of it, no loss either.
      ++cam->outside;
      if (b >= 0) {
        std::lock_guard<std::mutex> lock(cam->mutex);
        cam->free_buffers.push_back(b);
      }
      continue;
    }
    if (r == GrabResult::kFrame) {
      ++cam->grabbed;
      seq += cam->src->lost_before_last();
      const std::int64_t cns = cam->src->camera_ns();
      bool new_clock = false;
      if (cns >= 0 && last_camera_ns >= 0) {
        const double step_s = static_cast<double>(cns - last_camera_ns) * 1e-9;
        const double host_step_s = static_cast<double>(at.mono_ns - last_at.mono_ns) * 1e-9;
        const double period_s = cam->fps > 0 ? 1.0 / cam->fps : 0.0;
        if (step_s <= 0.0 || std::abs(step_s - host_step_s) > kClockStepMinS) {
          // A camera that reset its clock (power cycle) or had it set (PTP): its stamps start again; so does
          // the clock mapping, from this frame.
          Event(EventLevel::kWarning, "camera:" + cam->cfg.name,
                (step_s <= 0.0 ? "camera clock went back by " + FormatFixed(-step_s, 6) + " s"
                               : "camera clock stepped by " + FormatFixed(step_s, 6) + " s while the host's advanced " +
                                     FormatFixed(host_step_s, 6) + " s") +
                    ": a new camera clock mapping starts");
          std::lock_guard<std::mutex> lock(cam->mutex);
          cam->clock_fit = {};
          new_clock = true;
        } else if (step_s > std::max(kSilenceMinS, kSilencePeriods * period_s)) {
          // The camera itself sent nothing for a while (paused, reconfigured): a gap from the last frame to this
          // one, closed when this frame is written.
          cam->Fault(last_at, "camera sent no frame for " + FormatFixed(step_s, 3) + " s (its own clock)");
        }
      }
      if (cns >= 0) {
        last_camera_ns = cns;
        last_at = at;
      }
      new_clock = new_clock || new_clock_unqueued;
      new_clock_unqueued = b < 0 && new_clock;
      if (b < 0) {
        ++cam->dropped_queue;
        cam->Fault(at, "frames dropped: " + std::to_string(cam->pool.size()) +
                           " frames already wait for the disk (seq " + std::to_string(seq) + ")");
      } else {
        std::lock_guard<std::mutex> lock(cam->mutex);
        cam->queue.push_back({b, at, seq, cns, cam->src->frame_time_shift_ns(), new_clock});
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
    // A camera with its own clock went silent after its last frame: the gap starts there.
    cam->Fault(last_camera_ns >= 0 ? last_at : Now(), why);
    // Reopen after a pause (a camera unplugged and plugged back in).
    cam->src->Close();
    if (!SleepUntil(MonoNowNs() + kNsPerS, stop_)) break;
    std::string owhy;
    if (cam->src->Open(&owhy)) {
      Event(EventLevel::kInfo, "camera:" + cam->cfg.name, "reopened");
      ReportFeatures(cam);
    }
  }
  std::lock_guard<std::mutex> lock(cam->mutex);
  cam->grab_done = true;
  cam->cv.notify_all();
}

void Recorder::WriteFrame(CameraStream* cam, const CameraStream::Item& item) {
  if (item.new_clock) cam->clock_restart_pending = true;  // even if this frame is not written
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
  // A camera with its own clock: t_s from its stamp through the mapping onto the host clock (camera_clock.h),
  // said in time_source; a frame without a stamp, or one the mapping would put at or before the last row, keeps
  // its arrival time ("host").
  double t_s = T(item.at);
  std::string camera_cols;
  if (cam->src->has_camera_clock()) {
    const char* source = "host";
    if (item.camera_ns >= 0) {
      if (cam->clock_restart_pending) cam->clock_map.Reset();
      cam->clock_restart_pending = false;
      // A hardware trigger's time: the stamp (exposure start) less the trigger's delay, on the camera's clock.
      const double mapped = cam->clock_map.Add(item.camera_ns, static_cast<double>(item.at.mono_ns) * 1e-9) -
                            static_cast<double>(item.shift_ns) * 1e-9 - static_cast<double>(epoch_.mono_ns) * 1e-9;
      if (mapped > cam->last_t_s) {
        t_s = mapped;
        source = "camera";
      }
      camera_cols = "," + FormatFixed(static_cast<double>(item.camera_ns) * 1e-9, 9) + "," + source;
    } else {
      camera_cols = ",," + std::string(source);
    }
  }
  cam->last_t_s = t_s;
  const std::string row = std::to_string(cam->frame_index) + "," + FormatFixed(t_s, 9) + "," +
                          FormatFixed(static_cast<double>(item.at.mono_ns) * 1e-9, 9) + "," +
                          FormatFixed(static_cast<double>(item.at.real_ns) * 1e-9, 6) + "," +
                          std::to_string(item.seq) + "," + std::to_string(cam->segment) + camera_cols;
  if (!cam->frames_log->Append(row, &why)) {
    // The frame stays only if its time is on disk too.
    std::string uwhy;
    cam->writer->UndoLast(&uwhy);
    ++cam->write_failed;
    cam->Fault(item.at, "frames.csv not written (" + why + "): frame removed");
    return;
  }
  if (item.camera_ns >= 0) {
    std::lock_guard<std::mutex> lock(cam->mutex);
    cam->clock_fit.Add(static_cast<double>(item.camera_ns) * 1e-9, static_cast<double>(item.at.mono_ns) * 1e-9);
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

}  // namespace rk::capture::internal

// The recorder's cameras: per camera a grabber thread (stamps frames into a bounded buffer pool, drops and
// counts a frame with no free buffer, reopens a failing source) and a writer thread (segment first, then the
// frames.csv row, so frames.csv never names a frame that is not on disk).
#include "capture/recorder_internal.h"

#include <exception>

#include "camera/camera_model.h"

namespace rk::capture::internal {

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

}  // namespace rk::capture::internal

// The recorder behind RunCapture (internal to lib/capture; the interface is capture/recorder.h). One
// Recorder records one trial; its parts, each in its own file:
//   recorder.cc          the recording's life: folder, set-up order, threads, supervision, stop
//   recorder_devices.cc  rangefinder and turret: connect, rows from their samples, thread priority
//   recorder_cameras.cc  per camera: grabber thread, writer thread (segments and frames.csv)
//   recorder_files.cc    the trial's files through lib/trial: stream logs and their headers, manifest
//   recorder_status.cc   events, gaps, the live status line and the summary
#pragma once

#include <unistd.h>

#include <atomic>
#include <cmath>

#include "capture/camera_clock.h"
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "capture/append_log.h"
#include "capture/camera_source.h"
#include "capture/clock.h"
#include "capture/device.h"
#include "capture/durable_file.h"
#include "capture/recorder.h"
#include "capture/segment_writer.h"
#include "io/json_util.h"

namespace rk::capture::internal {

inline constexpr std::size_t kMaxGapsListed = 10000;

struct GapRecord {
  std::string stream, reason;
  double start_s = 0;
  std::optional<double> end_s;
};

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
    std::int64_t camera_ns = -1;  // the camera's own time stamp (aravis), −1 without
    std::int64_t shift_ns = 0;    // subtracted from camera_ns for the frame's time (a hardware trigger's delay)
    bool new_clock = false;       // the camera's clock stepped before this frame: a new mapping starts here
  };
  bool clock_restart_pending = false;  // writer thread: a new mapping from the next frame that is written
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

  // The camera clock → host clock mapping (a camera with its own clock): host_mono = offset + (1 + drift) ·
  // camera, fitted by least squares over every written frame (sums about the first frame, under `mutex`).
  struct ClockFit {
    std::int64_t n = 0;
    double x0 = 0, y0 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    void Add(double camera_s, double host_s);
    io::Json ToJson() const;  // null before two frames
  } clock_fit;
  CameraClockMapper clock_map;               // t_s of a camera with a clock (writer thread)
  double last_t_s = -1e300;                  // the last row's t_s (writer thread)
  std::atomic<std::int64_t> grabbed{0}, written{0}, dropped_queue{0}, dropped_disk{0}, write_failed{0},
      source_errors{0}, outside{0};
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
  // --- set-up (recorder.cc, devices in recorder_devices.cc, files in recorder_files.cc) ---
  void PrepareFolder();
  void StartDisk();   // syncer and events.log
  void CopyModels();  // camera and target models beside the recording
  void Connect();
  void CreateLogs();
  void Abort();  // before recording starts: stop what runs, remove what was created

  // --- recording (recorder.cc) ---
  void StartThreads();
  void Supervise();  // manifest and status until a stop condition; sets stop_reason_
  void StopAndFlush();

  // --- streams (cameras in recorder_cameras.cc, devices in recorder_devices.cc) ---
  void GrabLoop(CameraStream* cam);
  // The features an Aravis camera was asked for and what it took (events.log: a refused or changed value is a
  // warning).
  void ReportFeatures(CameraStream* cam);
  void WriteLoop(CameraStream* cam);
  void WriteFrame(CameraStream* cam, const CameraStream::Item& item);
  void OnRange(const RangeSample& s);
  void OnTurret(const TurretSample& s);

  // --- events, gaps, status (recorder_status.cc), manifest (recorder_files.cc) ---
  double T(const Stamp& at) const { return epoch_.TrialSeconds(at.mono_ns); }
  void Event(EventLevel level, const std::string& source, const std::string& message);
  void GapBegin(const std::string& stream, AppendLog* log, const Stamp& at, const std::string& reason);
  void GapEnd(const std::string& stream, AppendLog* log, const Stamp& at);
  DeviceReporter MakeReporter(const std::string& stream, AppendLog** log);
  void WriteManifest(const std::string& state);
  // Raises the calling (stamping) thread to the configured real-time priority; records the outcome.
  void RealTime(const std::string& stream);
  io::Json ManifestJson(const std::string& state);
  io::Json StreamsJson();  // called with manifest_mutex_ held
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
  std::int64_t record_stop_ns_ = INT64_MAX;  // start + --duration: frames that arrive later are not recorded
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

}  // namespace rk::capture::internal

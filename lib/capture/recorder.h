// rk-capture: records a live station (cameras, Dimetix rangefinder, FLIR turret) into a trial
// directory (SPEC.md §6) that the rest of the suite reads unchanged; docs/rk-capture.md.
//
// Threads: per camera one grabber (stamps frames on arrival into a pool of at most one second of
// buffers; a frame with no free buffer is dropped and counted) and one writer (segments +
// frames.csv row, in that order, so frames.csv never names a frame that is not on disk); one
// thread per serial device; the Syncer (fdatasync of every file each sync_s ≤ 1 s, free space);
// the caller's thread rewrites the manifest each manifest_s and shows the status line.
// Faults (a silent or garbled device, a hang-up, a camera error, a full disk) are logged in
// events.log, marked as gaps (manifest "capture.gaps", "# gap" comment lines in the stream's CSV)
// and never stop the other streams.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "capture/dimetix.h"
#include "capture/ptu.h"
#include "capture/station_config.h"
#include "io/json_util.h"
#include "io/options.h"

namespace rk::capture {

struct CaptureOptions {
  std::string out_dir;                        // created; refused if it exists and is not an empty folder
  double duration_s = 0.0;                    // > 0: stop after this long; 0: until *stop
  const std::atomic<bool>* stop = nullptr;    // set asynchronously (SIGINT / SIGTERM) for a clean stop
  std::function<void(const std::string&)> status;  // the live status line, every status_period_s
  std::function<void(const std::string&)> warn;    // warning and error events, as they happen
  double status_period_s = 0.5;
  std::vector<std::string> command_line;      // recorded in the manifest
  std::function<std::int64_t()> free_space_probe;  // replaces statvfs (tests)

  // The command-line options of rk-capture's recording (io/options.h); capture_options.cc.
  static const io::OptionTable<CaptureOptions>& Table();
  bool Check(std::string* why) const;
};

struct CameraSummary {
  std::string name, source_kind, format;
  double fps = 0;
  int width = 0, height = 0, bit_depth = 0;
  std::int64_t grabbed = 0, written = 0, dropped_queue = 0, dropped_disk = 0, write_failed = 0, source_errors = 0;
  std::int64_t outside = 0;  // frames that arrived before the recording began or after --duration: not recorded
  int segments = 0;
  bool ended = false;  // the source ended before the recording did (a file without loop)
  io::Json stream;     // an Aravis camera's stream counters and features (AravisSource::StreamReport), else null
  io::Json ToJson() const;
};

struct CaptureSummary {
  std::string out_dir, stop_reason;  // "duration", "signal", "sources ended"
  double recorded_s = 0;
  std::vector<CameraSummary> cameras;
  std::optional<DimetixStats> range;
  std::optional<PtuStats> turret;
  std::int64_t range_rows = 0, turret_rows = 0;
  std::int64_t gaps = 0;
  // Records lost to the disk (full, I/O error): frames dropped or not written, CSV rows and
  // events not written, manifest updates that failed.
  std::int64_t write_failures = 0;
  double max_sync_pass_s = 0;
  io::Json ToJson() const;
};

// Records until the duration is over or *stop is set, then stops the devices, writes what is
// queued and leaves the manifest in state "complete". Throws rk::Error before recording starts
// (output folder refused, a device or camera not answering) and leaves nothing behind then.
// Process-wide effect: SIGXFSZ is ignored (a file-size limit must fail a write, not kill the
// recording).
CaptureSummary RunCapture(const StationConfig& config, const CaptureOptions& options);

}  // namespace rk::capture

// Dimetix DLS-series laser rangefinder (seed 001: DLS-B15) on a serial line, ASCII protocol of the
// Dimetix Technical Reference Manual ("Command set"). Commands end with CR LF; N = device ID 0..9:
//   sNg              single distance measurement   → gNg+xxxxxxxx   distance in 0.1 mm
//   sNh              tracking (continuous)         → gNh+xxxxxxxx   one reply per measurement
//   sNc              stop / clear                  → gN?
//   sNo / sNp        laser on / off                → gN?
//   sNt              temperature                   → gNt+xxxxxxxx   in 0.1 °C
//   any command, on failure                        → gN@Ezzz        error code zzz (255: signal too weak)
// After power-on the device sends gN? by itself. The manual documents the sNg/gNg and sNuh/gNuh
// reply pairs; that tracking replies carry the command letter (gNh+…) is inferred from them, and the
// parser accepts a distance reply with any command letter (docs/rk-capture.md, "Protocols").
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "capture/device.h"
#include "capture/serial_port.h"

namespace rk::capture {

enum class DimetixReplyKind { kDistance, kError, kAck, kTemperature, kInvalid };

struct DimetixReply {
  DimetixReplyKind kind = DimetixReplyKind::kInvalid;
  std::string command;     // letters after gN: "g", "h", "t", ... (empty for gN? and gN@E)
  std::int64_t value = 0;  // distance (0.1 mm), error code, or temperature (0.1 °C)
};

// Parses one reply line (terminators removed). Lines for another device ID, lines with
// non-printable bytes and anything not of the forms above are kInvalid.
DimetixReply ParseDimetixReply(std::string_view line, int device_id);
// "sN<cmd>\r\n".
std::string DimetixCommand(int device_id, std::string_view cmd);

enum class DimetixMode { kTracking, kSingle };

struct DimetixOptions {
  SerialOptions serial;
  int device_id = 0;                       // N in the commands, 0 … 9
  DimetixMode mode = DimetixMode::kTracking;
  double rate_hz = 5.0;                    // single: sNg issued at this rate; tracking: expected rate
  int tracking_ms = 0;                     // > 0: tracking started as sNh+<ms> (sampling time, DLS-C/E)
  double timeout_s = 2.0;                  // no reply for this long → gap, device re-armed
  double reconnect_s = 1.0;                // retry period after a hang-up or while silent
  bool laser_off_at_end = true;            // sNp when the recording stops
  double latency_s = 0.0;                  // subtracted from the arrival time for t_s

  bool Check(std::string* why) const;
  io::Json ToJson() const;
};

struct RangeSample {
  Stamp stamp;                                // arrival of the reply's line terminator
  std::optional<std::int64_t> distance_01mm;  // empty on an error reply
  int status = 0;                             // 0 ok, else the device's error code
};

struct DimetixStats {
  std::int64_t samples = 0, ok = 0, errors = 0, garbage_lines = 0, timeouts = 0, disconnects = 0,
               reconnects = 0, restarts = 0;
  std::map<int, std::int64_t> error_codes;
  std::optional<double> temperature_start_c, temperature_end_c;
  io::Json ToJson() const;
};

class DimetixDriver {
 public:
  DimetixDriver(DimetixOptions options, DeviceReporter reporter, std::function<void(const RangeSample&)> on_sample);

  // Start-up check before recording: opens the port, stops any running measurement (sNc must be
  // acknowledged), switches the laser on and reads the temperature. False with the reason if the
  // port cannot be opened or the device does not answer.
  bool Connect(std::string* why);
  // Measures until `stop`; faults are reported, never thrown. On the way out: sNc, temperature,
  // laser off (if configured). Runs on its own thread.
  void Run(const std::atomic<bool>& stop);
  DimetixStats stats() const;

 private:
  bool OpenPort(std::string* why);
  bool Initialize(std::string* why);
  // Sends `cmd` and waits for a reply of `want` kind (distance replies in between are passed on as
  // samples). Returns the reply, or nullopt on timeout / hang-up.
  std::optional<DimetixReply> Transact(std::string_view cmd, DimetixReplyKind want, double timeout_s, std::string* why);
  bool Send(std::string_view cmd, std::string* why);
  // Reads for up to `timeout_s` and handles every complete line: distances (and, outside a
  // transaction, error replies) become samples; other replies go to `non_samples`.
  // Returns -1 on hang-up, else the number of replies handled.
  int Pump(double timeout_s, bool in_transaction, std::string* why, std::vector<DimetixReply>* non_samples);
  void HandleGarbage(const std::string& line, const Stamp& at);
  void Disconnected(const std::string& why);
  bool StartMeasuring(std::string* why);

  DimetixOptions o_;
  DeviceReporter reporter_;
  std::function<void(const RangeSample&)> on_sample_;
  SerialPort port_;
  LineSplitter splitter_;
  GapState gap_;
  mutable std::mutex stats_mutex_;
  DimetixStats stats_;
  std::int64_t last_reply_ns_ = 0;
  bool hung_up_ = false;  // set by Send / Pump on a hang-up
  std::int64_t garbage_logged_ns_ = 0;
  std::int64_t garbage_unlogged_ = 0;
};

}  // namespace rk::capture

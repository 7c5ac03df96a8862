// FLIR pan-tilt unit (seed 001: PTU-D48E; PTU-D46 and E-series share the ASCII protocol) on a serial
// line. Commands end with a space (or CR); replies are lines:
//   "*" [result]        success; a query's result follows ("* 1234", verbose "* Current Pan position is 1234")
//   "!" message         failure; "!P" / "!T" are asynchronous pan / tilt limit hits
// Queries and commands used:
//   PP / TP             current absolute pan / tilt position, in positions (counts)
//   PR / TR             resolution, arc-seconds per position (read from the unit, never assumed)
//   PP<n> / TP<n>       go to absolute position n (optional pointing at start)
//   ED / FT             echo off, terse feedback (the parser also reads echoed and verbose replies)
//   V                   firmware version ("* Pan-Tilt Controller v…"): the resynchronisation barrier
//                       after an unanswered query (replies come in order; nothing else answers text)
//
// Positions to angles (SPEC.md §2: azimuth [0, 360) clockwise from north, elevation up positive):
//   az_deg = wrap360(pan_zero_deg + pan_sign · pan_pos · pan_res_arcsec / 3600)
//   el_deg = tilt_zero_deg + tilt_sign · tilt_pos · tilt_res_arcsec / 3600
// pan_zero_deg is the azimuth of pan position 0 (found by survey); pan_sign = +1 when positive
// positions turn the unit clockwise seen from above (FLIR: positive pan = right), −1 otherwise;
// likewise tilt_sign = +1 when positive tilt positions raise the boresight.
#pragma once

#include <atomic>
#include <deque>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "capture/device.h"
#include "capture/serial_port.h"

namespace rk::capture {

enum class PtuReplyKind { kOk, kError, kLimit, kInvalid };

struct PtuReply {
  PtuReplyKind kind = PtuReplyKind::kInvalid;
  std::optional<double> value;  // first number in a success reply
  std::string text;             // the reply after '*' or '!', trimmed
};

// Parses one reply line; an echoed command before the '*' or '!' is skipped.
PtuReply ParsePtuReply(std::string_view line);

struct PtuAngleMap {
  double pan_zero_deg = 0.0;   // azimuth of pan position 0
  double pan_sign = 1.0;       // +1 or -1
  double tilt_zero_deg = 0.0;  // elevation of tilt position 0
  double tilt_sign = 1.0;      // +1 or -1

  double AzimuthDeg(std::int64_t pan_pos, double pan_res_arcsec) const;
  double ElevationDeg(std::int64_t tilt_pos, double tilt_res_arcsec) const;
  // Nearest position for an azimuth (the pan offset from pan_zero_deg taken in (−180, 180]) and
  // for an elevation.
  std::int64_t PanPosition(double az_deg, double pan_res_arcsec) const;
  std::int64_t TiltPosition(double el_deg, double tilt_res_arcsec) const;
};

struct PtuOptions {
  SerialOptions serial;
  double rate_hz = 50.0;       // polling rate (one PP and one TP query per poll)
  double timeout_s = 0.5;      // a query unanswered this long → gap
  double reconnect_s = 1.0;    // retry period after a hang-up
  PtuAngleMap map;
  std::optional<double> point_az_deg, point_el_deg;  // pointing commands sent once at start
  double latency_s = 0.0;      // subtracted from the arrival time for t_s

  bool Check(std::string* why) const;
  io::Json ToJson() const;
};

struct TurretSample {
  Stamp stamp;                  // mean of the arrivals of the PP and TP replies
  std::int64_t pan_pos = 0, tilt_pos = 0;
  double pair_dt_s = 0.0;       // TP arrival − PP arrival
  double pan_res_arcsec = 0.0, tilt_res_arcsec = 0.0;
};

struct PtuStats {
  std::int64_t samples = 0, error_replies = 0, garbage_lines = 0, timeouts = 0, disconnects = 0, reconnects = 0,
               late_polls = 0, limit_hits = 0;
  double pan_res_arcsec = 0.0, tilt_res_arcsec = 0.0;
  io::Json ToJson() const;
};

class PtuDriver {
 public:
  PtuDriver(PtuOptions options, DeviceReporter reporter, std::function<void(const TurretSample&)> on_sample);

  // Start-up check: opens the port, echo off and terse feedback, reads both resolutions (must be
  // > 0), sends the pointing commands if configured. False with the reason on failure.
  bool Connect(std::string* why);
  // Polls until `stop`; faults are reported, never thrown. Runs on its own thread.
  void Run(const std::atomic<bool>& stop);
  PtuStats stats() const;

 private:
  bool Setup(std::string* why);
  // Sends `cmd` + ' ' and returns the first '*' or '!' reply with its arrival, or nullopt on timeout
  // (`hung_up` set on a hang-up).
  std::optional<PtuReply> Query(std::string_view cmd, double timeout_s, Stamp* at, bool* hung_up, std::string* why);
  // Sends V and discards every line up to its answer (false on timeout or hang-up).
  bool Resync(const std::atomic<bool>& stop, bool* hung_up, std::string* why);
  void Disconnected(const std::string& why);
  void Note(std::int64_t* counter, const std::string& what, const Stamp& at);

  PtuOptions o_;
  DeviceReporter reporter_;
  std::function<void(const TurretSample&)> on_sample_;
  SerialPort port_;
  LineSplitter splitter_;
  std::deque<std::string> pending_lines_;
  Stamp pending_at_;
  GapState gap_;
  mutable std::mutex stats_mutex_;
  PtuStats stats_;
  std::int64_t noted_ns_ = 0;
  std::int64_t unnoted_ = 0;
};

}  // namespace rk::capture

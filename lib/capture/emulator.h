// Device emulators on a pseudo-terminal (rk-sim device dimetix|ptu, and the capture tests).
//
// An emulator creates a pty with posix_openpt / grantpt / unlockpt, speaks the device's protocol on
// the master side and lets clients open the slave (/dev/pts/N) like a serial port. With a "link"
// path it keeps a symbolic link to the current slave, replaced atomically when the pty is
// re-created — the way udev's /dev/serial/by-id links follow a USB adapter that is unplugged and
// plugged back in — so a configuration can name one stable port across emulated disconnects.
//
// Faults are scheduled in seconds since the emulator started, "KIND:START:DURATION[:ARG]":
//   error:S:D[:CODE]   measurements answered with an error (Dimetix gN@E<CODE>, default 255;
//                      PTU "!" replies to position queries)
//   silence:S:D        the device answers nothing and ignores commands (hung firmware, cut line)
//   garbage:S:D        every reply replaced by random bytes (line noise, wrong baud rate)
//   slow:S:D[:DELAY]   replies delayed by DELAY s (default 0.5)
//   disconnect:S:D     the pty is closed for D s (clients see a hang-up), then re-created
// Every byte sent and every command received is written to an optional truth log
//   host_mono_s,event,data
// (host_mono_s = CLOCK_MONOTONIC, the clock rk-capture stamps with; event = sent, dropped, garbage,
// lost (queued when the line was cut), received, ignored, disconnect, reconnect; data = the reply or command line without its terminator)
// so that tests can check every record rk-capture wrote against what the device said.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "io/options.h"

namespace rk::capture {

enum class FaultKind { kError, kSilence, kGarbage, kSlow, kDisconnect };

struct Fault {
  FaultKind kind = FaultKind::kError;
  double start_s = 0.0;
  double duration_s = 0.0;
  int code = 255;          // error: device error code
  double delay_s = 0.5;    // slow: extra reply delay
  bool ActiveAt(double t_s) const { return t_s >= start_s && t_s < start_s + duration_s; }
};

// Parses "error:5:2", "error:5:2:256", "silence:3:1.5", "slow:1:2:0.8", ...; false with the reason.
bool ParseFault(const std::string& text, Fault* fault, std::string* why);
std::string FaultToString(const Fault& fault);

struct EmulatorOptions {
  std::string link;            // symlink kept pointing at the pty slave ("" = none)
  std::string truth_path;      // truth log ("" = none)
  double baud = 0.0;           // > 0: replies paced at this rate (10 bits per byte)
  std::vector<Fault> faults;
  double error_rate = 0.0;     // probability that a measurement is answered with an error
  std::uint64_t seed = 1;
  // --error-rate, --baud, --seed (the paths and the faults are registered by rk-sim device).
  static const io::OptionTable<EmulatorOptions>& Table();
  bool Check(std::string* why) const { return Table().Check(*this, why); }
};

class PtyEndpoint {
 public:
  ~PtyEndpoint() { Close(); }
  // Creates a pty in raw mode (and the link). False with the reason on failure.
  bool Open(const std::string& link, std::string* why);
  void Close();
  bool is_open() const { return master_ >= 0; }
  const std::string& slave_path() const { return slave_path_; }
  bool Write(std::string_view bytes);
  // >0 bytes read, 0 on timeout, -1 on error.
  long Read(char* buf, std::size_t n, double timeout_s);

 private:
  int master_ = -1;
  int held_slave_ = -1;  // keeps the line up while no client has it open
  std::string slave_path_;
};

struct EmulatorStats {
  std::int64_t sent = 0, dropped = 0, garbage = 0, received = 0, ignored = 0, disconnects = 0;
};

class DeviceEmulator {
 public:
  explicit DeviceEmulator(EmulatorOptions options);
  virtual ~DeviceEmulator();
  DeviceEmulator(const DeviceEmulator&) = delete;
  DeviceEmulator& operator=(const DeviceEmulator&) = delete;

  // Creates the pty (and link); false with the reason on failure.
  bool Start(std::string* why);
  // The path clients should open: the link if one was asked for, else the pty slave.
  std::string port() const;
  // Serves until `stop` or, if duration_s > 0, for that long. Removes the link at the end.
  void Run(const std::atomic<bool>& stop, double duration_s);
  EmulatorStats stats() const { return stats_; }

 protected:
  // Seconds since Start().
  double Elapsed() const;
  // A command line (or token) received, terminators removed; `t` = Elapsed().
  virtual void OnCommand(const std::string& command, double t) = 0;
  // Scheduled output (tracking measurements); called every loop turn.
  virtual void OnTick(double t) = 0;
  // Next time OnTick has something to do (monotonic ns), or INT64_MAX.
  virtual std::int64_t NextWakeNs() const { return INT64_MAX; }
  // The pty was (re-)created.
  virtual void OnConnect(double t) { (void)t; }
  // Characters that end a command (default CR and LF).
  virtual bool IsTerminator(char c) const { return c == '\r' || c == '\n'; }
  // Bytes that go back immediately and unconditionally (local echo).
  virtual std::string Echo(const char* data, std::size_t n) const { (void)data, (void)n; return std::string(); }

  // Queues `line` + CR LF to be sent after `delay_s` (plus any slow fault); replies leave in order.
  void Reply(const std::string& line, double delay_s);
  // True if a fault of `kind` is active at `t`; its parameters in *fault.
  bool Active(FaultKind kind, double t, Fault* fault = nullptr) const;
  bool RandomError();
  std::mt19937_64& rng() { return rng_; }
  // Logs an event; `mono_ns` = when it happened (0 = now).
  void Truth(const char* event, std::string_view data, std::int64_t mono_ns = 0);

  EmulatorOptions o_;

 private:
  struct Pending {
    std::int64_t due_ns = 0;
    std::string line;
  };
  void SendDue(std::int64_t now_ns);
  void Pace(std::size_t bytes);

  PtyEndpoint pty_;
  std::int64_t t0_ns_ = 0;
  std::deque<Pending> pending_;
  std::string partial_;
  std::mt19937_64 rng_;
  std::FILE* truth_ = nullptr;
  EmulatorStats stats_;
};

}  // namespace rk::capture

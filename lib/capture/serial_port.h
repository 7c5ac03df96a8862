// A serial line through POSIX termios: raw mode, baud / parity / data bits / stop bits as configured,
// no flow control, non-blocking reads with poll() timeouts. Works on real ports (/dev/ttyUSB0,
// /dev/ttyS0, /dev/serial/by-id/...) and on pseudo-terminals (the device emulators).
//
// Nothing here throws for a device problem: a port that cannot be opened, a read error or a hang-up
// (a USB adapter pulled out, an emulator closing its pty) is returned to the caller, whose job is to
// log it, mark a gap and reconnect.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "io/json_util.h"

namespace rk::capture {

struct SerialOptions {
  std::string port;                // device path (a symlink is followed at every open)
  int baud = 9600;                 // one of the standard rates 1200 … 4000000
  std::string parity = "none";     // none, even, odd
  int data_bits = 8;               // 5 … 8
  int stop_bits = 1;               // 1 or 2

  bool Check(std::string* why) const;
  // Bits on the wire per character (start + data + parity + stop), for line-time estimates.
  int BitsPerChar() const { return 1 + data_bits + (parity == "none" ? 0 : 1) + stop_bits; }
  io::Json ToJson() const;
};

// Reads the common serial keys of a device block ("port", "baud", "parity", "data_bits", "stop_bits");
// `where` names the block in messages ("station.json: rangefinder").
SerialOptions SerialOptionsFromJson(const io::Json& j, const std::string& where);

class SerialPort {
 public:
  SerialPort() = default;
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  // Opens and configures the port; discards anything already received. False (with the reason)
  // if it cannot be opened or configured.
  bool Open(const SerialOptions& options, std::string* why);
  void Close();
  bool is_open() const { return fd_ >= 0; }

  // Writes all of `data` within `timeout_s`. False on error, hang-up or timeout.
  bool Write(std::string_view data, double timeout_s, std::string* why);
  // Waits up to `timeout_s` for input and reads what is there (at most `n` bytes).
  // Returns the byte count, 0 on timeout, -1 on hang-up or error (`why` says which).
  long Read(char* buf, std::size_t n, double timeout_s, std::string* why);

 private:
  int fd_ = -1;
};

// Splits a byte stream into lines at CR and/or LF (a device may end replies with either or both).
// A run of more than `max_line` bytes without a terminator is discarded as garbage and counted.
class LineSplitter {
 public:
  explicit LineSplitter(std::size_t max_line = 256) : max_line_(max_line) {}
  // Appends complete, non-empty lines (without terminators) to `lines`.
  void Feed(const char* data, std::size_t n, std::vector<std::string>* lines);
  // Also treats `extra` (e.g. a space) as a terminator.
  void set_extra_terminator(char extra) { extra_ = extra; }
  void Clear() { partial_.clear(); }
  std::size_t overlong() const { return overlong_; }
  bool has_partial() const { return !partial_.empty(); }

 private:
  std::size_t max_line_;
  char extra_ = '\n';
  std::string partial_;
  bool discarding_ = false;
  std::size_t overlong_ = 0;
};

// True if every byte of `line` is printable ASCII (0x20..0x7e).
bool IsPrintableAscii(std::string_view line);
// A short, printable rendering of arbitrary bytes for logs: "g0g+0001\x07…" (at most `max` chars).
std::string EscapeForLog(std::string_view bytes, std::size_t max = 40);

}  // namespace rk::capture

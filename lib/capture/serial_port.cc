#include "capture/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "capture/clock.h"
#include "io/error.h"

namespace rk::capture {
namespace {

speed_t BaudConstant(int baud) {
  switch (baud) {
    case 1200: return B1200;
    case 2400: return B2400;
    case 4800: return B4800;
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 500000: return B500000;
    case 576000: return B576000;
    case 921600: return B921600;
    case 1000000: return B1000000;
    case 1152000: return B1152000;
    case 1500000: return B1500000;
    case 2000000: return B2000000;
    case 2500000: return B2500000;
    case 3000000: return B3000000;
    case 3500000: return B3500000;
    case 4000000: return B4000000;
    default: return B0;
  }
}

int RemainingMs(std::int64_t deadline_ns) {
  const std::int64_t left = deadline_ns - MonoNowNs();
  if (left <= 0) return 0;
  return static_cast<int>((left + 999999) / 1000000);
}

}  // namespace

bool SerialOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (port.empty()) return fail("'port' is empty");
  if (BaudConstant(baud) == B0) return fail("'baud' " + std::to_string(baud) + " is not a standard rate (1200 ... 4000000)");
  if (parity != "none" && parity != "even" && parity != "odd")
    return fail("'parity' must be none, even or odd, not '" + parity + "'");
  if (data_bits < 5 || data_bits > 8) return fail("'data_bits' must be 5 ... 8");
  if (stop_bits != 1 && stop_bits != 2) return fail("'stop_bits' must be 1 or 2");
  return true;
}

io::Json SerialOptions::ToJson() const {
  return {{"port", port}, {"baud", baud}, {"parity", parity}, {"data_bits", data_bits}, {"stop_bits", stop_bits}};
}

SerialOptions SerialOptionsFromJson(const io::Json& j, const std::string& where) {
  SerialOptions o;
  o.port = io::RequireString(j, "port", where);
  auto integer = [&](const char* key, int fallback) {
    const double v = io::NumberOr(j, key, fallback, where);
    if (v != std::floor(v) || std::abs(v) > 1e9) throw DataError(where, 0, 0, std::string("'") + key + "' must be an integer");
    return static_cast<int>(v);
  };
  o.baud = integer("baud", o.baud);
  o.data_bits = integer("data_bits", o.data_bits);
  o.stop_bits = integer("stop_bits", o.stop_bits);
  if (j.contains("parity")) o.parity = io::RequireString(j, "parity", where);
  std::string why;
  if (!o.Check(&why)) throw DataError(where, 0, 0, why);
  return o;
}

SerialPort::~SerialPort() { Close(); }

void SerialPort::Close() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

bool SerialPort::Open(const SerialOptions& o, std::string* why) {
  Close();
  const int fd = ::open(o.port.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (why) *why = "cannot open " + o.port + ": " + std::strerror(errno);
    return false;
  }
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    if (why) *why = o.port + " is not a serial port: " + std::strerror(errno);
    ::close(fd);
    return false;
  }
  ::cfmakeraw(&tio);
  tio.c_cflag &= ~(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
  switch (o.data_bits) {
    case 5: tio.c_cflag |= CS5; break;
    case 6: tio.c_cflag |= CS6; break;
    case 7: tio.c_cflag |= CS7; break;
    default: tio.c_cflag |= CS8; break;
  }
  if (o.parity != "none") {
    tio.c_cflag |= PARENB;
    if (o.parity == "odd") tio.c_cflag |= PARODD;
    tio.c_iflag |= INPCK;  // drop characters with parity errors instead of passing them on
  }
  if (o.stop_bits == 2) tio.c_cflag |= CSTOPB;
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_iflag &= ~(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  const speed_t speed = BaudConstant(o.baud);
  ::cfsetispeed(&tio, speed);
  ::cfsetospeed(&tio, speed);
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) {
    if (why) *why = "cannot configure " + o.port + ": " + std::strerror(errno);
    ::close(fd);
    return false;
  }
  ::tcflush(fd, TCIOFLUSH);
  fd_ = fd;
  return true;
}

bool SerialPort::Write(std::string_view data, double timeout_s, std::string* why) {
  if (fd_ < 0) {
    if (why) *why = "port not open";
    return false;
  }
  const std::int64_t deadline = MonoNowNs() + static_cast<std::int64_t>(timeout_s * 1e9);
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd_, data.data() + done, data.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) {
      if (why) *why = std::string("write failed: ") + std::strerror(errno);
      return false;
    }
    pollfd p{fd_, POLLOUT, 0};
    const int ms = RemainingMs(deadline);
    if (ms == 0) {
      if (why) *why = "write timed out (output not draining)";
      return false;
    }
    const int r = ::poll(&p, 1, ms);
    if (r > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL))) {
      if (why) *why = "line hung up";
      return false;
    }
  }
  return true;
}

long SerialPort::Read(char* buf, std::size_t n, double timeout_s, std::string* why) {
  if (fd_ < 0) {
    if (why) *why = "port not open";
    return -1;
  }
  const std::int64_t deadline = MonoNowNs() + static_cast<std::int64_t>(std::max(0.0, timeout_s) * 1e9);
  while (true) {
    const ssize_t r = ::read(fd_, buf, n);
    if (r > 0) return static_cast<long>(r);
    // r == 0: a raw tty with VMIN = VTIME = 0 returns 0 when empty (not EAGAIN); poll tells a
    // hang-up apart.
    if (r < 0 && errno != EAGAIN && errno != EINTR) {
      if (why) *why = std::string("read failed: ") + std::strerror(errno);
      return -1;
    }
    const int ms = RemainingMs(deadline);
    if (ms == 0) return 0;
    pollfd p{fd_, POLLIN, 0};
    const int pr = ::poll(&p, 1, ms);
    if (pr < 0 && errno != EINTR) {
      if (why) *why = std::string("poll failed: ") + std::strerror(errno);
      return -1;
    }
    if (pr > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL))) {
      if (why) *why = "line hung up (device disconnected)";
      return -1;
    }
  }
}

void LineSplitter::Feed(const char* data, std::size_t n, std::vector<std::string>* lines) {
  for (std::size_t i = 0; i < n; ++i) {
    const char c = data[i];
    if (c == '\r' || c == '\n' || c == extra_) {
      if (discarding_) {
        discarding_ = false;
      } else if (!partial_.empty()) {
        lines->push_back(partial_);
      }
      partial_.clear();
      continue;
    }
    if (discarding_) continue;
    if (partial_.size() >= max_line_) {
      ++overlong_;
      partial_.clear();
      discarding_ = true;
      continue;
    }
    partial_.push_back(c);
  }
}

bool IsPrintableAscii(std::string_view line) {
  for (unsigned char c : line) {
    if (c < 0x20 || c > 0x7e) return false;
  }
  return true;
}

std::string EscapeForLog(std::string_view bytes, std::size_t max) {
  std::string out;
  for (unsigned char c : bytes) {
    if (out.size() >= max) {
      out += "...";
      break;
    }
    if (c >= 0x20 && c <= 0x7e && c != '\\') {
      out.push_back(static_cast<char>(c));
    } else {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      out += b;
    }
  }
  return out;
}

}  // namespace rk::capture

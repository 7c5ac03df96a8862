#include "capture/emulator.h"

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <sstream>

#include "capture/clock.h"
#include "capture/device.h"

namespace rk::capture {

bool ParseFault(const std::string& text, Fault* fault, std::string* why) {
  auto fail = [&](const std::string& w) {
    if (why) *why = "fault '" + text + "': " + w;
    return false;
  };
  std::vector<std::string> parts;
  std::stringstream ss(text);
  std::string p;
  while (std::getline(ss, p, ':')) parts.push_back(p);
  if (parts.size() < 3) return fail("expected KIND:START:DURATION[:ARG]");
  Fault f;
  const std::string& k = parts[0];
  if (k == "error") {
    f.kind = FaultKind::kError;
  } else if (k == "silence") {
    f.kind = FaultKind::kSilence;
  } else if (k == "garbage") {
    f.kind = FaultKind::kGarbage;
  } else if (k == "slow") {
    f.kind = FaultKind::kSlow;
  } else if (k == "disconnect") {
    f.kind = FaultKind::kDisconnect;
  } else {
    return fail("kind must be error, silence, garbage, slow or disconnect");
  }
  try {
    std::size_t used = 0;
    f.start_s = std::stod(parts[1], &used);
    if (used != parts[1].size()) return fail("START is not a number");
    f.duration_s = std::stod(parts[2], &used);
    if (used != parts[2].size()) return fail("DURATION is not a number");
    if (parts.size() > 4) return fail("too many fields");
    if (parts.size() == 4) {
      if (f.kind == FaultKind::kError) {
        f.code = std::stoi(parts[3], &used);
        if (used != parts[3].size() || f.code < 0 || f.code > 999) return fail("CODE must be 0 ... 999");
      } else if (f.kind == FaultKind::kSlow) {
        f.delay_s = std::stod(parts[3], &used);
        if (used != parts[3].size() || !(f.delay_s >= 0 && f.delay_s <= 60)) return fail("DELAY must be 0 ... 60 s");
      } else {
        return fail("only error and slow take a fourth field");
      }
    }
  } catch (const std::exception&) {
    return fail("START, DURATION and ARG must be numbers");
  }
  if (!(f.start_s >= 0 && std::isfinite(f.start_s))) return fail("START must be >= 0");
  if (!(f.duration_s > 0 && std::isfinite(f.duration_s))) return fail("DURATION must be > 0");
  *fault = f;
  return true;
}

std::string FaultToString(const Fault& f) {
  static const char* names[] = {"error", "silence", "garbage", "slow", "disconnect"};
  std::string s = std::string(names[static_cast<int>(f.kind)]) + ":" + std::to_string(f.start_s) + ":" +
                  std::to_string(f.duration_s);
  if (f.kind == FaultKind::kError) s += ":" + std::to_string(f.code);
  if (f.kind == FaultKind::kSlow) s += ":" + std::to_string(f.delay_s);
  return s;
}

const io::OptionTable<EmulatorOptions>& EmulatorOptions::Table() {
  static const io::OptionTable<EmulatorOptions> table =
      io::OptionTable<EmulatorOptions>()
          .Real("--error-rate", &EmulatorOptions::error_rate, "", io::Bounds::Closed(0, 1),
                "Probability that a measurement is answered with an error")
          .Real("--baud", &EmulatorOptions::baud, "", io::Bounds::Closed(0, 4e6),
                "Pace replies at this line rate, 10 bits per byte (0 = no pacing)")
          .Count("--seed", &EmulatorOptions::seed, "", io::Bounds::Any(), "Random seed (noise, errors, garbage)");
  return table;
}

bool PtyEndpoint::Open(const std::string& link, std::string* why) {
  Close();
  const int m = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (m < 0) {
    if (why) *why = std::string("posix_openpt: ") + std::strerror(errno);
    return false;
  }
  if (::grantpt(m) != 0 || ::unlockpt(m) != 0) {
    if (why) *why = std::string("grantpt/unlockpt: ") + std::strerror(errno);
    ::close(m);
    return false;
  }
  char name[256];
  if (::ptsname_r(m, name, sizeof name) != 0) {
    if (why) *why = std::string("ptsname: ") + std::strerror(errno);
    ::close(m);
    return false;
  }
  const int s = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (s < 0) {
    if (why) *why = std::string("cannot open ") + name + ": " + std::strerror(errno);
    ::close(m);
    return false;
  }
  termios tio{};
  if (::tcgetattr(s, &tio) == 0) {
    ::cfmakeraw(&tio);
    ::tcsetattr(s, TCSANOW, &tio);
  }
  ::fcntl(m, F_SETFL, ::fcntl(m, F_GETFL) | O_NONBLOCK);
  master_ = m;
  held_slave_ = s;
  slave_path_ = name;
  if (!link.empty()) {
    const std::string tmp = link + ".tmp";
    ::unlink(tmp.c_str());
    if (::symlink(name, tmp.c_str()) != 0 || ::rename(tmp.c_str(), link.c_str()) != 0) {
      if (why) *why = "cannot make link " + link + ": " + std::strerror(errno);
      Close();
      return false;
    }
  }
  return true;
}

void PtyEndpoint::Close() {
  if (held_slave_ >= 0) ::close(held_slave_);
  if (master_ >= 0) ::close(master_);
  held_slave_ = master_ = -1;
}

bool PtyEndpoint::Write(std::string_view bytes) {
  std::size_t done = 0;
  int spins = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(master_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) return false;
    // The client is not reading and the pty buffer is full: drop what does not fit after a while.
    if (++spins > 100) return false;
    ::usleep(1000);
  }
  return true;
}

long PtyEndpoint::Read(char* buf, std::size_t n, double timeout_s) {
  pollfd p{master_, POLLIN, 0};
  const int ms = std::max(0, static_cast<int>(std::ceil(timeout_s * 1000.0)));
  const int r = ::poll(&p, 1, ms);
  if (r <= 0) return 0;
  const ssize_t got = ::read(master_, buf, n);
  if (got < 0) return (errno == EAGAIN || errno == EINTR) ? 0 : -1;
  return static_cast<long>(got);
}

DeviceEmulator::DeviceEmulator(EmulatorOptions options) : o_(std::move(options)), rng_(o_.seed) {}

DeviceEmulator::~DeviceEmulator() {
  if (truth_) std::fclose(truth_);
}

std::string DeviceEmulator::port() const { return o_.link.empty() ? pty_.slave_path() : o_.link; }

double DeviceEmulator::Elapsed() const { return static_cast<double>(MonoNowNs() - t0_ns_) * 1e-9; }

void DeviceEmulator::Truth(const char* event, std::string_view data, std::int64_t mono_ns) {
  if (!truth_) return;
  std::fprintf(truth_, "%.9f,%s,%.*s\n", static_cast<double>(mono_ns > 0 ? mono_ns : MonoNowNs()) * 1e-9, event,
               static_cast<int>(data.size()), data.data());
}

bool DeviceEmulator::Start(std::string* why) {
  std::string w;
  if (!o_.Check(&w)) {
    if (why) *why = w;
    return false;
  }
  if (!o_.truth_path.empty()) {
    truth_ = std::fopen(o_.truth_path.c_str(), "w");
    if (!truth_) {
      if (why) *why = "cannot write " + o_.truth_path + ": " + std::strerror(errno);
      return false;
    }
    std::setvbuf(truth_, nullptr, _IOLBF, 1 << 16);
    std::fprintf(truth_, "host_mono_s,event,data\n");
  }
  t0_ns_ = MonoNowNs();
  if (!pty_.Open(o_.link, why)) return false;
  OnConnect(0.0);
  return true;
}

bool DeviceEmulator::Active(FaultKind kind, double t, Fault* fault) const {
  for (const Fault& f : o_.faults) {
    if (f.kind == kind && f.ActiveAt(t)) {
      if (fault) *fault = f;
      return true;
    }
  }
  return false;
}

bool DeviceEmulator::RandomError() {
  if (o_.error_rate <= 0) return false;
  return std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < o_.error_rate;
}

void DeviceEmulator::Reply(const std::string& line, double delay_s) {
  const double t = Elapsed();
  Fault slow;
  if (Active(FaultKind::kSlow, t, &slow)) delay_s += slow.delay_s;
  std::int64_t due = MonoNowNs() + static_cast<std::int64_t>(delay_s * 1e9);
  if (!pending_.empty() && due < pending_.back().due_ns) due = pending_.back().due_ns;  // in order
  pending_.push_back({due, line});
}

void DeviceEmulator::Pace(std::size_t bytes) {
  if (o_.baud <= 0) return;
  // The line time of `bytes` characters (10 bits each) passes before they have all arrived.
  const std::int64_t ns = static_cast<std::int64_t>(static_cast<double>(bytes) * 10.0 / o_.baud * 1e9);
  timespec ts{static_cast<time_t>(ns / kNsPerS), static_cast<long>(ns % kNsPerS)};
  ::nanosleep(&ts, nullptr);
}

void DeviceEmulator::SendDue(std::int64_t now_ns) {
  while (!pending_.empty() && pending_.front().due_ns <= now_ns) {
    const Pending p = pending_.front();
    pending_.pop_front();
    const double t = Elapsed();
    if (Active(FaultKind::kSilence, t)) {
      ++stats_.dropped;
      Truth("dropped", p.line);
      continue;
    }
    if (Active(FaultKind::kGarbage, t)) {
      std::uniform_int_distribution<int> len(3, 40), byte(0, 255);
      std::string junk;
      const int n = len(rng_);
      for (int i = 0; i < n; ++i) {
        char c = static_cast<char>(byte(rng_));
        if (c == '\r' || c == '\n') c = '#';
        junk.push_back(c);
      }
      junk += "\r\n";
      ++stats_.garbage;
      Pace(junk.size());
      const std::int64_t at = MonoNowNs();
      pty_.Write(junk);
      Truth("garbage", p.line, at);
      continue;
    }
    ++stats_.sent;
    // The time is taken just before the bytes go out; the log (a file write) comes after them.
    Pace(p.line.size() + 2);
    const std::int64_t at = MonoNowNs();
    pty_.Write(p.line + "\r\n");
    Truth("sent", p.line, at);
  }
}

void DeviceEmulator::Run(const std::atomic<bool>& stop, double duration_s) {
  const std::int64_t end_ns =
      duration_s > 0 ? t0_ns_ + static_cast<std::int64_t>(duration_s * 1e9) : INT64_MAX;
  char buf[512];
  while (!stop.load() && MonoNowNs() < end_ns) {
    const double t = Elapsed();
    const bool cut = Active(FaultKind::kDisconnect, t);
    if (cut && pty_.is_open()) {
      pty_.Close();
      for (const Pending& p : pending_) Truth("lost", p.line);  // queued replies die with the line
      pending_.clear();
      partial_.clear();
      ++stats_.disconnects;
      Truth("disconnect", "");
      continue;
    }
    if (!cut && !pty_.is_open()) {
      std::string why;
      if (pty_.Open(o_.link, &why)) {
        Truth("reconnect", pty_.slave_path());
        OnConnect(t);
      } else {
        SleepUntil(MonoNowNs() + 100000000, stop);
      }
      continue;
    }
    if (!pty_.is_open()) {
      SleepUntil(MonoNowNs() + 10000000, stop);
      continue;
    }
    SendDue(MonoNowNs());
    OnTick(Elapsed());
    SendDue(MonoNowNs());
    std::int64_t wake = std::min<std::int64_t>(NextWakeNs(), MonoNowNs() + 20000000);
    if (!pending_.empty()) wake = std::min(wake, pending_.front().due_ns);
    const double wait_s = std::max(0.0, static_cast<double>(wake - MonoNowNs()) * 1e-9);
    const long n = pty_.Read(buf, sizeof buf, wait_s);
    if (n <= 0) continue;
    const double tr = Elapsed();
    const bool silent = Active(FaultKind::kSilence, tr);
    if (!silent) {
      const std::string echo = Echo(buf, static_cast<std::size_t>(n));
      if (!echo.empty()) pty_.Write(echo);
    }
    for (long i = 0; i < n; ++i) {
      const char c = buf[i];
      if (IsTerminator(c)) {
        if (!partial_.empty()) {
          ++stats_.received;
          if (silent) {
            ++stats_.ignored;
            Truth("ignored", partial_);
          } else {
            Truth("received", partial_);
            OnCommand(partial_, tr);
          }
        }
        partial_.clear();
      } else if (partial_.size() < 256) {
        partial_.push_back(c);
      }
    }
  }
  pty_.Close();
  if (!o_.link.empty()) ::unlink(o_.link.c_str());
  if (truth_) std::fflush(truth_);
}

}  // namespace rk::capture

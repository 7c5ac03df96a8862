#include "capture/clock.h"

#include <sys/timex.h>
#include <time.h>

#include <cstdio>
#include <fstream>

namespace rk::capture {
namespace {

std::int64_t Read(clockid_t id) {
  timespec ts{};
  ::clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

std::int64_t Resolution(clockid_t id) {
  timespec ts{};
  ::clock_getres(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

}  // namespace

std::int64_t MonoNowNs() { return Read(CLOCK_MONOTONIC); }
std::int64_t RealNowNs() { return Read(CLOCK_REALTIME); }

Stamp Now() {
  // Bracket the monotonic reading by two real-time readings and keep the tightest of a few tries, so
  // the pair refers to one instant to well under a microsecond (a pre-emption between the reads
  // would otherwise pair readings milliseconds apart).
  Stamp best;
  std::int64_t best_gap = INT64_MAX;
  for (int i = 0; i < 3; ++i) {
    const std::int64_t r1 = Read(CLOCK_REALTIME);
    const std::int64_t m = Read(CLOCK_MONOTONIC);
    const std::int64_t r2 = Read(CLOCK_REALTIME);
    if (r2 - r1 < best_gap) {
      best_gap = r2 - r1;
      best.mono_ns = m;
      best.real_ns = r1 + (r2 - r1) / 2;
    }
    if (best_gap < 2000) break;
  }
  return best;
}

std::string FormatUtc(std::int64_t real_ns, int decimals) {
  std::int64_t sec = real_ns / kNsPerS;
  std::int64_t frac = real_ns % kNsPerS;
  if (frac < 0) {
    frac += kNsPerS;
    --sec;
  }
  const time_t t = static_cast<time_t>(sec);
  tm utc{};
  ::gmtime_r(&t, &utc);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d", utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday,
                utc.tm_hour, utc.tm_min, utc.tm_sec);
  std::string out(buf);
  if (decimals > 0) {
    if (decimals > 9) decimals = 9;
    char f[16];
    std::snprintf(f, sizeof f, "%09lld", static_cast<long long>(frac));
    out += "." + std::string(f, static_cast<std::size_t>(decimals));
  }
  return out + "Z";
}

TrialEpoch TrialEpoch::FromStamp(const Stamp& now) {
  TrialEpoch e;
  const std::int64_t into_second = ((now.real_ns % kNsPerS) + kNsPerS) % kNsPerS;
  e.real_ns = now.real_ns - into_second;
  e.mono_ns = now.mono_ns - into_second;
  return e;
}

io::Json DescribeClocks(const TrialEpoch& epoch) {
  io::Json c;
  c["t_s"] = "CLOCK_MONOTONIC at arrival - epoch_mono_s (- the device's latency_s, if configured)";
  c["host_mono_s"] = "CLOCK_MONOTONIC at arrival, seconds since boot";
  c["host_real_s"] = "CLOCK_REALTIME at arrival, Unix time (seconds since 1970-01-01T00:00:00Z)";
  c["epoch_mono_s"] = static_cast<double>(epoch.mono_ns) * 1e-9;
  c["epoch_real_s"] = epoch.real_ns / kNsPerS;
  c["monotonic_resolution_ns"] = Resolution(CLOCK_MONOTONIC);
  c["realtime_resolution_ns"] = Resolution(CLOCK_REALTIME);
  std::ifstream src("/sys/devices/system/clocksource/clocksource0/current_clocksource");
  std::string name;
  if (src && std::getline(src, name) && !name.empty()) {
    c["kernel_clocksource"] = name;
  } else {
    c["kernel_clocksource"] = nullptr;
  }
  timex tx{};
  const int state = ::adjtimex(&tx);
  if (state >= 0) {
    const bool unsync = (tx.status & STA_UNSYNC) != 0 || state == TIME_ERROR;
    c["ntp_synchronized"] = !unsync;
    c["ntp_estimated_error_us"] = tx.esterror;
  } else {
    c["ntp_synchronized"] = nullptr;
  }
  return c;
}

}  // namespace rk::capture

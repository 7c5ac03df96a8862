// Host clocks of a recording (rk-capture, docs/rk-capture.md "Time").
//
// Every sample is stamped when it arrives with two host clocks:
//   host_mono = CLOCK_MONOTONIC  (never steps; NTP may slew its rate; seconds since boot)
//   host_real = CLOCK_REALTIME   (Unix time; may step when the clock is set)
// The trial epoch is the whole UTC second at or just before the start of recording:
//   epoch_real = floor(CLOCK_REALTIME at start)          → "epoch_utc" in the manifest
//   epoch_mono = CLOCK_MONOTONIC at the instant epoch_real (read as a bracketed pair)
// and every t_s in the trial is   t_s = host_mono − epoch_mono   (− the device latency, if configured).
// t_s therefore never jumps, whatever NTP does; host_real − (epoch_real + t_s) shows how far the
// real-time clock moved against the monotonic one during the trial.
#pragma once

#include <cstdint>
#include <string>

#include "io/json_util.h"

namespace rk::capture {

constexpr std::int64_t kNsPerS = 1000000000;

// One arrival stamp, both clocks in nanoseconds.
struct Stamp {
  std::int64_t mono_ns = 0;  // CLOCK_MONOTONIC
  std::int64_t real_ns = 0;  // CLOCK_REALTIME (Unix time)
};

std::int64_t MonoNowNs();
std::int64_t RealNowNs();
// Both clocks, the real-time reading taken as the mean of two readings bracketing the monotonic one.
Stamp Now();

// "2026-11-21T08:00:00Z" (whole seconds) or with `decimals` fractional digits (1..9).
std::string FormatUtc(std::int64_t real_ns, int decimals = 0);

struct TrialEpoch {
  std::int64_t mono_ns = 0;  // CLOCK_MONOTONIC at the epoch
  std::int64_t real_ns = 0;  // CLOCK_REALTIME at the epoch (a whole second)

  // Epoch = the whole UTC second at or before `now`.
  static TrialEpoch FromStamp(const Stamp& now);
  std::string utc() const { return FormatUtc(real_ns); }
  // Seconds since the epoch of a monotonic reading.
  double TrialSeconds(std::int64_t mono_ns_at) const {
    return static_cast<double>(mono_ns_at - mono_ns) * 1e-9;
  }
};

// The manifest's "clocks" block: what t_s and the host clock columns are, the epoch on both clocks,
// the kernel clock source (/sys/.../current_clocksource), clock resolutions and the NTP state
// (adjtimex: synchronised or not, estimated error).
io::Json DescribeClocks(const TrialEpoch& epoch);

}  // namespace rk::capture

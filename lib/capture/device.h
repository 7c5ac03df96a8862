// What a device driver reports to the recorder besides its samples: events for events.log and the
// start and end of gaps (a stretch of time in which the stream has no samples because of a fault:
// a device that stopped answering, a hang-up, a disconnected line). Error replies of a device are
// samples (the range log keeps their code), not gaps.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "capture/clock.h"

namespace rk::capture {

enum class EventLevel { kInfo, kWarning, kError };
const char* EventLevelName(EventLevel level);

struct DeviceReporter {
  std::function<void(EventLevel, const std::string&)> event;
  std::function<void(const Stamp&, const std::string& reason)> gap_begin;
  std::function<void(const Stamp&)> gap_end;
};

// Tracks whether a stream is in a gap, so that a fault opens one gap and the next good sample closes it.
class GapState {
 public:
  explicit GapState(const DeviceReporter* reporter) : reporter_(reporter) {}
  // A fault: opens a gap unless one is open. Returns true if this call opened it.
  bool Fault(const Stamp& at, const std::string& reason);
  // A good sample: closes the open gap, if any.
  void Ok(const Stamp& at);
  bool in_gap() const { return in_gap_; }
  std::int64_t gaps() const { return gaps_; }

 private:
  const DeviceReporter* reporter_;
  bool in_gap_ = false;
  std::int64_t gaps_ = 0;
};

// Gives the calling thread real-time priority (SCHED_FIFO, `priority` 1..99) so that arrival stamps
// are taken within microseconds even when the CPUs are busy (the kernel still caps real-time
// threads at 95 % of a CPU). Needs CAP_SYS_NICE or an RLIMIT_RTPRIO; false with the reason if not
// granted, and the thread keeps its normal priority.
bool RaiseThreadPriority(int priority, std::string* why);

// Sleeps until CLOCK_MONOTONIC reaches `deadline_ns` or `stop` becomes true (checked every 20 ms).
// Returns false if stopped.
bool SleepUntil(std::int64_t deadline_ns, const std::atomic<bool>& stop);

}  // namespace rk::capture

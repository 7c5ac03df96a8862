#include "capture/device.h"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <cstring>

#include <algorithm>

namespace rk::capture {

const char* EventLevelName(EventLevel level) {
  switch (level) {
    case EventLevel::kInfo: return "info";
    case EventLevel::kWarning: return "warning";
    case EventLevel::kError: return "error";
  }
  return "info";
}

bool GapState::Fault(const Stamp& at, const std::string& reason) {
  if (in_gap_) return false;
  in_gap_ = true;
  ++gaps_;
  if (reporter_ && reporter_->gap_begin) reporter_->gap_begin(at, reason);
  return true;
}

void GapState::Ok(const Stamp& at) {
  if (!in_gap_) return;
  in_gap_ = false;
  if (reporter_ && reporter_->gap_end) reporter_->gap_end(at);
}

bool RaiseThreadPriority(int priority, std::string* why) {
  sched_param p{};
  p.sched_priority = priority;
  const int rc = ::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &p);
  if (rc != 0) {
    if (why) *why = std::strerror(rc);
    return false;
  }
  return true;
}

bool SleepUntil(std::int64_t deadline_ns, const std::atomic<bool>& stop) {
  while (!stop.load(std::memory_order_relaxed)) {
    const std::int64_t now = MonoNowNs();
    if (now >= deadline_ns) return true;
    const std::int64_t step = std::min<std::int64_t>(deadline_ns - now, 20000000);
    timespec ts{static_cast<time_t>(step / kNsPerS), static_cast<long>(step % kNsPerS)};
    ::nanosleep(&ts, nullptr);
  }
  return false;
}

}  // namespace rk::capture

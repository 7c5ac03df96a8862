#include "capture/dimetix.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "io/error.h"

namespace rk::capture {
namespace {

bool AllDigits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

std::string Fixed(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

}  // namespace

DimetixReply ParseDimetixReply(std::string_view line, int device_id) {
  DimetixReply r;
  if (line.size() < 3 || !IsPrintableAscii(line)) return r;
  if (line[0] != 'g' || line[1] != static_cast<char>('0' + device_id)) return r;
  std::string_view rest = line.substr(2);
  if (rest == "?") {
    r.kind = DimetixReplyKind::kAck;
    return r;
  }
  if (rest.size() >= 2 && rest[0] == '@' && rest[1] == 'E') {
    // gN@Ezzz, possibly followed by "+c" (buffered read-out) which is ignored.
    std::string_view code = rest.substr(2);
    const auto plus = code.find('+');
    if (plus != std::string_view::npos) code = code.substr(0, plus);
    if (!AllDigits(code) || code.size() > 4) return r;
    r.kind = DimetixReplyKind::kError;
    r.value = std::stoll(std::string(code));
    return r;
  }
  // gN<letters>{+|-}<digits>
  std::size_t i = 0;
  while (i < rest.size() && rest[i] >= 'a' && rest[i] <= 'z') ++i;
  if (i == 0 || i >= rest.size() || (rest[i] != '+' && rest[i] != '-')) return r;
  const std::string letters(rest.substr(0, i));
  const bool negative = rest[i] == '-';
  std::string_view digits = rest.substr(i + 1);
  // Buffered read-outs append "+c"; keep the distance part.
  const auto plus = digits.find_first_of("+-");
  if (plus != std::string_view::npos) digits = digits.substr(0, plus);
  if (!AllDigits(digits) || digits.size() > 10) return r;
  const std::int64_t v = std::stoll(std::string(digits));
  r.command = letters;
  r.value = negative ? -v : v;
  if (letters == "t") {
    r.kind = DimetixReplyKind::kTemperature;
  } else if (letters == "g" || letters == "h" || letters == "q" || letters == "ug" || letters == "uh" ||
             letters == "uq") {
    r.kind = DimetixReplyKind::kDistance;
  } else {
    r.kind = DimetixReplyKind::kInvalid;  // a reply to a command we never send
  }
  return r;
}

std::string DimetixCommand(int device_id, std::string_view cmd) {
  return "s" + std::to_string(device_id) + std::string(cmd) + "\r\n";
}

bool DimetixOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!serial.Check(why)) return false;
  if (device_id < 0 || device_id > 9) return fail("'device_id' must be 0 ... 9");
  if (!(rate_hz > 0 && rate_hz <= 1000)) return fail("'rate_hz' must be in (0, 1000]");
  if (tracking_ms < 0) return fail("'tracking_ms' must be >= 0");
  if (!(timeout_s > 0 && timeout_s <= 600)) return fail("'timeout_s' must be in (0, 600]");
  if (!(reconnect_s > 0 && reconnect_s <= 600)) return fail("'reconnect_s' must be in (0, 600]");
  if (!(std::abs(latency_s) <= 10)) return fail("'latency_s' must be within +-10 s");
  return true;
}

io::Json DimetixOptions::ToJson() const {
  io::Json j = serial.ToJson();
  j["device"] = "dimetix";
  j["device_id"] = device_id;
  j["mode"] = mode == DimetixMode::kTracking ? "tracking" : "single";
  j["rate_hz"] = rate_hz;
  j["tracking_ms"] = tracking_ms;
  j["timeout_s"] = timeout_s;
  j["reconnect_s"] = reconnect_s;
  j["laser_off_at_end"] = laser_off_at_end;
  j["latency_s"] = latency_s;
  return j;
}

io::Json DimetixStats::ToJson() const {
  io::Json j;
  j["samples"] = samples;
  j["ok"] = ok;
  j["error_replies"] = errors;
  io::Json codes = io::Json::object();
  for (const auto& [code, n] : error_codes) codes[std::to_string(code)] = n;
  j["error_codes"] = codes;
  j["garbage_lines"] = garbage_lines;
  j["timeouts"] = timeouts;
  j["disconnects"] = disconnects;
  j["reconnects"] = reconnects;
  j["device_restarts"] = restarts;
  j["temperature_start_c"] = temperature_start_c ? io::Json(*temperature_start_c) : io::Json(nullptr);
  j["temperature_end_c"] = temperature_end_c ? io::Json(*temperature_end_c) : io::Json(nullptr);
  return j;
}

DimetixDriver::DimetixDriver(DimetixOptions options, DeviceReporter reporter,
                             std::function<void(const RangeSample&)> on_sample)
    : o_(std::move(options)), reporter_(std::move(reporter)), on_sample_(std::move(on_sample)), gap_(&reporter_) {}

DimetixStats DimetixDriver::stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

bool DimetixDriver::OpenPort(std::string* why) {
  splitter_.Clear();
  return port_.Open(o_.serial, why);
}

bool DimetixDriver::Send(std::string_view cmd, std::string* why) {
  if (port_.Write(DimetixCommand(o_.device_id, cmd), 1.0, why)) return true;
  hung_up_ = true;
  return false;
}

void DimetixDriver::HandleGarbage(const std::string& line, const Stamp& at) {
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.garbage_lines;
  }
  // At most one event per second, with the count of the ones not logged.
  ++garbage_unlogged_;
  if (at.mono_ns - garbage_logged_ns_ >= kNsPerS) {
    if (reporter_.event) {
      reporter_.event(EventLevel::kWarning, "unreadable reply '" + EscapeForLog(line) + "'" +
                                                (garbage_unlogged_ > 1
                                                     ? " (" + std::to_string(garbage_unlogged_) + " since the last report)"
                                                     : std::string()));
    }
    garbage_logged_ns_ = at.mono_ns;
    garbage_unlogged_ = 0;
  }
}

int DimetixDriver::Pump(double timeout_s, bool in_transaction, std::string* why,
                        std::vector<DimetixReply>* non_samples) {
  char buf[512];
  const long n = port_.Read(buf, sizeof buf, timeout_s, why);
  if (n < 0) {
    hung_up_ = true;
    return -1;
  }
  if (n == 0) return 0;
  const Stamp at = Now();
  std::vector<std::string> lines;
  const std::size_t overlong_before = splitter_.overlong();
  splitter_.Feed(buf, static_cast<std::size_t>(n), &lines);
  if (splitter_.overlong() > overlong_before) HandleGarbage("<long run of bytes without a line end>", at);
  int handled = 0;
  for (const std::string& line : lines) {
    const DimetixReply r = ParseDimetixReply(line, o_.device_id);
    if (r.kind == DimetixReplyKind::kInvalid) {
      HandleGarbage(line, at);
      continue;
    }
    last_reply_ns_ = at.mono_ns;
    ++handled;
    if (r.kind == DimetixReplyKind::kDistance || (r.kind == DimetixReplyKind::kError && !in_transaction)) {
      RangeSample s;
      s.stamp = at;
      {
        std::lock_guard<std::mutex> lock(stats_mutex_);
        ++stats_.samples;
        if (r.kind == DimetixReplyKind::kDistance) {
          s.distance_01mm = r.value;
          ++stats_.ok;
        } else {
          s.status = static_cast<int>(r.value);
          ++stats_.errors;
          ++stats_.error_codes[s.status];
        }
      }
      gap_.Ok(at);
      if (on_sample_) on_sample_(s);
    } else {
      non_samples->push_back(r);
    }
  }
  return handled;
}

std::optional<DimetixReply> DimetixDriver::Transact(std::string_view cmd, DimetixReplyKind want, double timeout_s,
                                                    std::string* why) {
  if (!Send(cmd, why)) return std::nullopt;
  const std::int64_t deadline = MonoNowNs() + static_cast<std::int64_t>(timeout_s * 1e9);
  while (true) {
    const std::int64_t left = deadline - MonoNowNs();
    if (left <= 0) {
      if (why) *why = "no answer to s" + std::to_string(o_.device_id) + std::string(cmd) + " within " + Fixed(timeout_s, 1) + " s";
      return std::nullopt;
    }
    std::vector<DimetixReply> replies;
    if (Pump(static_cast<double>(left) * 1e-9, true, why, &replies) < 0) return std::nullopt;
    for (const DimetixReply& r : replies) {
      if (r.kind == want) return r;
      if (r.kind == DimetixReplyKind::kError) {
        if (reporter_.event) {
          reporter_.event(EventLevel::kWarning, "s" + std::to_string(o_.device_id) + std::string(cmd) +
                                                    " answered with error " + std::to_string(r.value));
        }
        return r;  // the device answers: good enough for a start-up check
      }
    }
  }
}

bool DimetixDriver::Initialize(std::string* why) {
  const double t = std::min(o_.timeout_s, 2.0);
  // Stop anything running (a tracking measurement left over from an earlier session).
  if (!Transact("c", DimetixReplyKind::kAck, t, why)) return false;
  if (!Transact("o", DimetixReplyKind::kAck, t, why)) return false;
  std::string twhy;
  const auto temp = Transact("t", DimetixReplyKind::kTemperature, t, &twhy);
  if (temp && temp->kind == DimetixReplyKind::kTemperature) {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    if (!stats_.temperature_start_c) stats_.temperature_start_c = static_cast<double>(temp->value) / 10.0;
  } else if (reporter_.event) {
    reporter_.event(EventLevel::kWarning, "temperature not read: " + (temp ? "error reply" : twhy));
  }
  return true;
}

bool DimetixDriver::Connect(std::string* why) {
  if (!OpenPort(why)) return false;
  if (!Initialize(why)) {
    port_.Close();
    return false;
  }
  if (reporter_.event) {
    const auto st = stats();
    reporter_.event(EventLevel::kInfo,
                    "connected on " + o_.serial.port + (st.temperature_start_c
                                                            ? ", temperature " + Fixed(*st.temperature_start_c, 1) + " C"
                                                            : std::string()));
  }
  return true;
}

bool DimetixDriver::StartMeasuring(std::string* why) {
  if (o_.mode == DimetixMode::kSingle) return true;
  const std::string cmd = o_.tracking_ms > 0 ? "h+" + std::to_string(o_.tracking_ms) : "h";
  return Send(cmd, why);
}

void DimetixDriver::Disconnected(const std::string& why) {
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.disconnects;
  }
  port_.Close();
  splitter_.Clear();
  gap_.Fault(Now(), "line lost: " + why);
}

void DimetixDriver::Run(const std::atomic<bool>& stop) {
  const std::int64_t period = static_cast<std::int64_t>(1e9 / o_.rate_hz);
  const std::int64_t timeout = static_cast<std::int64_t>(o_.timeout_s * 1e9);
  const std::int64_t reconnect = static_cast<std::int64_t>(o_.reconnect_s * 1e9);
  bool measuring = false;
  bool outstanding = false;  // single mode: an sNg waiting for its reply
  std::int64_t next_due = 0, sent_at = 0, next_attempt = 0, last_rearm = 0;
  while (!stop.load()) {
    std::string why;
    if (!port_.is_open()) {
      if (MonoNowNs() < next_attempt) {
        SleepUntil(next_attempt, stop);
        continue;
      }
      next_attempt = MonoNowNs() + reconnect;
      if (!OpenPort(&why) || !Initialize(&why)) {
        port_.Close();
        gap_.Fault(Now(), "rangefinder unavailable: " + why);
        continue;
      }
      {
        std::lock_guard<std::mutex> lock(stats_mutex_);
        ++stats_.reconnects;
      }
      if (reporter_.event) reporter_.event(EventLevel::kInfo, "reconnected on " + o_.serial.port);
      measuring = false;
    }
    if (!measuring) {
      if (!StartMeasuring(&why)) {
        Disconnected(why);
        continue;
      }
      measuring = true;
      outstanding = false;
      next_due = MonoNowNs();
      last_reply_ns_ = MonoNowNs();
    }
    if (o_.mode == DimetixMode::kSingle && !outstanding && MonoNowNs() >= next_due) {
      if (!Send("g", &why)) {
        Disconnected(why);
        measuring = false;
        continue;
      }
      outstanding = true;
      sent_at = MonoNowNs();
      next_due += period;
      if (next_due < sent_at) next_due = sent_at;  // the device is slower than rate_hz: as fast as it answers
    }
    double wait_s = 0.05;
    if (o_.mode == DimetixMode::kSingle && !outstanding) {
      wait_s = std::clamp(static_cast<double>(next_due - MonoNowNs()) * 1e-9, 0.0, 0.05);
    }
    std::vector<DimetixReply> others;
    const std::int64_t samples_before = stats().samples;
    if (Pump(wait_s, false, &why, &others) < 0) {
      Disconnected(why);
      measuring = false;
      continue;
    }
    if (stats().samples > samples_before) outstanding = false;
    for (const DimetixReply& r : others) {
      if (r.kind == DimetixReplyKind::kAck) {
        // Unasked gN?: the device's power-on sequence. It stopped measuring; start again.
        {
          std::lock_guard<std::mutex> lock(stats_mutex_);
          ++stats_.restarts;
        }
        if (reporter_.event)
          reporter_.event(EventLevel::kWarning, "device sent its start-up sequence (restarted); measurement re-armed");
        measuring = false;
      }
    }
    const std::int64_t now = MonoNowNs();
    const bool silent = o_.mode == DimetixMode::kSingle ? (outstanding && now - sent_at > timeout)
                                                        : (now - last_reply_ns_ > timeout);
    if (silent) {
      if (gap_.Fault(Now(), "no reply for " + Fixed(o_.timeout_s, 1) + " s")) {
        std::lock_guard<std::mutex> lock(stats_mutex_);
        ++stats_.timeouts;
      }
      outstanding = false;
      if (now - last_rearm >= reconnect) {
        // Re-arm: stop/clear must be acknowledged before measuring again.
        last_rearm = now;
        std::string rwhy;
        hung_up_ = false;
        if (Transact("c", DimetixReplyKind::kAck, std::min(0.5, o_.timeout_s), &rwhy)) {
          if (reporter_.event) reporter_.event(EventLevel::kInfo, "device answers again; measurement re-armed");
          measuring = false;
        } else if (hung_up_) {
          Disconnected(rwhy);
          measuring = false;
        }
      }
    }
  }
  // Clean stop: stop measuring, last temperature, laser off.
  if (port_.is_open()) {
    std::string why;
    Transact("c", DimetixReplyKind::kAck, 0.5, &why);
    const auto temp = Transact("t", DimetixReplyKind::kTemperature, 1.0, &why);
    if (temp && temp->kind == DimetixReplyKind::kTemperature) {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      stats_.temperature_end_c = static_cast<double>(temp->value) / 10.0;
    }
    if (o_.laser_off_at_end) Transact("p", DimetixReplyKind::kAck, 0.5, &why);
    port_.Close();
  }
}

}  // namespace rk::capture

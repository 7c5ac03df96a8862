#include "capture/ptu.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::capture {
namespace {

// The set-up queries (ED, FT, PR, TR) wait at least this long; see PtuDriver::Setup.
constexpr double kSetupTimeoutS = 2.0;

std::string Trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && s[a] == ' ') ++a;
  while (b > a && s[b - 1] == ' ') --b;
  return std::string(s.substr(a, b - a));
}

bool ParseNumber(const std::string& token, double* v) {
  if (token.empty()) return false;
  char* end = nullptr;
  const double x = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size() || !std::isfinite(x)) return false;
  *v = x;
  return true;
}

std::string Fixed(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

}  // namespace

PtuReply ParsePtuReply(std::string_view line) {
  PtuReply r;
  if (line.empty() || !IsPrintableAscii(line)) return r;
  const auto at = line.find_first_of("*!");
  if (at == std::string_view::npos) return r;
  // Whatever precedes the marker must look like an echoed command ("PP ", "pr ", "PP1000 ").
  for (char c : line.substr(0, at)) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == ' ' ||
                    c == '-' || c == '+' || c == '.';
    if (!ok) return r;
  }
  r.text = Trim(line.substr(at + 1));
  if (line[at] == '!') {
    r.kind = (r.text == "P" || r.text == "T") ? PtuReplyKind::kLimit : PtuReplyKind::kError;
    return r;
  }
  r.kind = PtuReplyKind::kOk;
  std::size_t i = 0;
  while (i < r.text.size()) {
    while (i < r.text.size() && r.text[i] == ' ') ++i;
    std::size_t j = i;
    while (j < r.text.size() && r.text[j] != ' ') ++j;
    double v = 0;
    if (j > i && ParseNumber(r.text.substr(i, j - i), &v)) {
      r.value = v;
      break;
    }
    i = j;
  }
  return r;
}

double PtuAngleMap::AzimuthDeg(std::int64_t pan_pos, double pan_res_arcsec) const {
  return geo::WrapDeg360(pan_zero_deg + pan_sign * static_cast<double>(pan_pos) * pan_res_arcsec / 3600.0);
}

double PtuAngleMap::ElevationDeg(std::int64_t tilt_pos, double tilt_res_arcsec) const {
  return tilt_zero_deg + tilt_sign * static_cast<double>(tilt_pos) * tilt_res_arcsec / 3600.0;
}

std::int64_t PtuAngleMap::PanPosition(double az_deg, double pan_res_arcsec) const {
  const double offset_deg = geo::WrapDeg180(az_deg - pan_zero_deg);
  return std::llround(pan_sign * offset_deg * 3600.0 / pan_res_arcsec);
}

std::int64_t PtuAngleMap::TiltPosition(double el_deg, double tilt_res_arcsec) const {
  return std::llround(tilt_sign * (el_deg - tilt_zero_deg) * 3600.0 / tilt_res_arcsec);
}

bool PtuOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!serial.Check(why)) return false;
  if (!(rate_hz > 0 && rate_hz <= 1000)) return fail("'rate_hz' must be in (0, 1000]");
  if (!(timeout_s > 0 && timeout_s <= 600)) return fail("'timeout_s' must be in (0, 600]");
  if (!(reconnect_s > 0 && reconnect_s <= 600)) return fail("'reconnect_s' must be in (0, 600]");
  if (map.pan_sign != 1.0 && map.pan_sign != -1.0) return fail("'pan_sign' must be 1 or -1");
  if (map.tilt_sign != 1.0 && map.tilt_sign != -1.0) return fail("'tilt_sign' must be 1 or -1");
  if (!std::isfinite(map.pan_zero_deg)) return fail("'pan_zero_deg' must be a number");
  if (!(std::abs(map.tilt_zero_deg) <= 90)) return fail("'tilt_zero_deg' must be in [-90, 90]");
  if (point_az_deg.has_value() != point_el_deg.has_value())
    return fail("'point' needs both 'az_deg' and 'el_deg'");
  if (point_el_deg && !(std::abs(*point_el_deg) <= 90)) return fail("'point.el_deg' must be in [-90, 90]");
  if (point_az_deg && !std::isfinite(*point_az_deg)) return fail("'point.az_deg' must be a number");
  if (!(std::abs(latency_s) <= 10)) return fail("'latency_s' must be within +-10 s");
  return true;
}

io::Json PtuOptions::ToJson() const {
  io::Json j = serial.ToJson();
  j["device"] = "flir-ptu";
  j["rate_hz"] = rate_hz;
  j["timeout_s"] = timeout_s;
  j["reconnect_s"] = reconnect_s;
  j["pan_zero_deg"] = map.pan_zero_deg;
  j["pan_sign"] = map.pan_sign;
  j["tilt_zero_deg"] = map.tilt_zero_deg;
  j["tilt_sign"] = map.tilt_sign;
  if (point_az_deg) j["point"] = {{"az_deg", *point_az_deg}, {"el_deg", *point_el_deg}};
  j["latency_s"] = latency_s;
  return j;
}

io::Json PtuStats::ToJson() const {
  return {{"samples", samples},         {"error_replies", error_replies}, {"garbage_lines", garbage_lines},
          {"timeouts", timeouts},       {"disconnects", disconnects},     {"reconnects", reconnects},
          {"late_polls", late_polls},   {"limit_hits", limit_hits},       {"pan_res_arcsec", pan_res_arcsec},
          {"tilt_res_arcsec", tilt_res_arcsec}};
}

PtuDriver::PtuDriver(PtuOptions options, DeviceReporter reporter, std::function<void(const TurretSample&)> on_sample)
    : o_(std::move(options)), reporter_(std::move(reporter)), on_sample_(std::move(on_sample)), gap_(&reporter_) {}

PtuStats PtuDriver::stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

void PtuDriver::Note(std::int64_t* counter, const std::string& what, const Stamp& at) {
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++*counter;
  }
  ++unnoted_;
  if (at.mono_ns - noted_ns_ >= kNsPerS) {
    if (reporter_.event) {
      reporter_.event(EventLevel::kWarning,
                      what + (unnoted_ > 1 ? " (" + std::to_string(unnoted_) + " faults since the last report)"
                                           : std::string()));
    }
    noted_ns_ = at.mono_ns;
    unnoted_ = 0;
  }
}

std::optional<PtuReply> PtuDriver::Query(std::string_view cmd, double timeout_s, Stamp* at, bool* hung_up,
                                         std::string* why) {
  *hung_up = false;
  if (!port_.Write(std::string(cmd) + " ", 1.0, why)) {
    *hung_up = true;
    return std::nullopt;
  }
  const std::int64_t deadline = MonoNowNs() + static_cast<std::int64_t>(timeout_s * 1e9);
  while (true) {
    while (!pending_lines_.empty()) {
      const std::string line = pending_lines_.front();
      pending_lines_.pop_front();
      const PtuReply r = ParsePtuReply(line);
      if (r.kind == PtuReplyKind::kInvalid) {
        Note(&stats_.garbage_lines, "unreadable reply '" + EscapeForLog(line) + "'", pending_at_);
        continue;
      }
      if (r.kind == PtuReplyKind::kOk && !r.value && !r.text.empty()) {
        continue;  // the answer to an earlier V (resynchronisation barrier): late, not ours
      }
      if (r.kind == PtuReplyKind::kLimit) {
        Note(&stats_.limit_hits, std::string(r.text == "P" ? "pan" : "tilt") + " limit hit (!" + r.text + ")",
             pending_at_);
        continue;
      }
      *at = pending_at_;
      return r;
    }
    const std::int64_t left = deadline - MonoNowNs();
    if (left <= 0) {
      if (why) *why = "no answer to " + std::string(cmd) + " within " + Fixed(timeout_s, 2) + " s";
      return std::nullopt;
    }
    char buf[256];
    const long n = port_.Read(buf, sizeof buf, static_cast<double>(left) * 1e-9, why);
    if (n < 0) {
      *hung_up = true;
      return std::nullopt;
    }
    if (n == 0) continue;
    pending_at_ = Now();
    const std::size_t overlong_before = splitter_.overlong();
    std::vector<std::string> lines;
    splitter_.Feed(buf, static_cast<std::size_t>(n), &lines);
    if (splitter_.overlong() > overlong_before)
      Note(&stats_.garbage_lines, "long run of bytes without a line end", pending_at_);
    for (auto& l : lines) pending_lines_.push_back(std::move(l));
  }
}

bool PtuDriver::Setup(std::string* why) {
  splitter_.Clear();
  pending_lines_.clear();
  // Discard whatever the unit had queued (an echo, a banner).
  char buf[256];
  std::string ignore;
  while (port_.Read(buf, sizeof buf, 0.05, &ignore) > 0) {
  }
  Stamp at;
  bool hup = false;
  // The set-up queries are answered once per connection, not per poll: they wait at least
  // kSetupTimeoutS, so a unit (or a loaded host) slow to answer its first commands after the port
  // opens costs a second, not a failed connection and a reconnect period.
  const double setup_timeout_s = std::max(o_.timeout_s, kSetupTimeoutS);
  for (const char* cmd : {"ED", "FT"}) {
    const auto r = Query(cmd, setup_timeout_s, &at, &hup, why);
    if (!r) return false;
    if (r->kind != PtuReplyKind::kOk && reporter_.event)
      reporter_.event(EventLevel::kWarning, std::string(cmd) + " answered '!" + r->text + "'");
  }
  double res[2] = {0, 0};
  const char* names[2] = {"PR", "TR"};
  for (int k = 0; k < 2; ++k) {
    const auto r = Query(names[k], setup_timeout_s, &at, &hup, why);
    if (!r) return false;
    if (r->kind != PtuReplyKind::kOk || !r->value || !(*r->value > 0)) {
      if (why) *why = std::string(names[k]) + " did not return a resolution (reply '" + r->text + "')";
      return false;
    }
    res[k] = *r->value;
  }
  std::lock_guard<std::mutex> lock(stats_mutex_);
  if (stats_.pan_res_arcsec > 0 && (res[0] != stats_.pan_res_arcsec || res[1] != stats_.tilt_res_arcsec) &&
      reporter_.event) {
    reporter_.event(EventLevel::kWarning, "resolution changed to pan " + Fixed(res[0], 6) + ", tilt " +
                                              Fixed(res[1], 6) + " arcsec per position");
  }
  stats_.pan_res_arcsec = res[0];
  stats_.tilt_res_arcsec = res[1];
  return true;
}

bool PtuDriver::Connect(std::string* why) {
  splitter_.Clear();
  if (!port_.Open(o_.serial, why)) return false;
  if (!Setup(why)) {
    port_.Close();
    return false;
  }
  const PtuStats st = stats();
  if (reporter_.event) {
    reporter_.event(EventLevel::kInfo, "connected on " + o_.serial.port + ", resolution pan " +
                                           Fixed(st.pan_res_arcsec, 6) + ", tilt " + Fixed(st.tilt_res_arcsec, 6) +
                                           " arcsec per position");
  }
  if (o_.point_az_deg) {
    const std::int64_t pan = o_.map.PanPosition(*o_.point_az_deg, st.pan_res_arcsec);
    const std::int64_t tilt = o_.map.TiltPosition(*o_.point_el_deg, st.tilt_res_arcsec);
    Stamp at;
    bool hup = false;
    for (const std::string& cmd : {"PP" + std::to_string(pan), "TP" + std::to_string(tilt)}) {
      const auto r = Query(cmd, o_.timeout_s, &at, &hup, why);
      if (!r) {
        port_.Close();
        return false;
      }
      if (reporter_.event) {
        reporter_.event(r->kind == PtuReplyKind::kOk ? EventLevel::kInfo : EventLevel::kWarning,
                        "pointing: " + cmd + (r->kind == PtuReplyKind::kOk ? " accepted" : " refused: !" + r->text));
      }
    }
  }
  return true;
}

void PtuDriver::Disconnected(const std::string& why) {
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.disconnects;
  }
  port_.Close();
  splitter_.Clear();
  pending_lines_.clear();
  gap_.Fault(Now(), "line lost: " + why);
}

bool PtuDriver::Resync(const std::atomic<bool>& stop, bool* hung_up, std::string* why) {
  *hung_up = false;
  pending_lines_.clear();
  splitter_.Clear();
  if (!port_.Write("V ", 1.0, why)) {
    *hung_up = true;
    return false;
  }
  const double wait_s = std::max(0.2, 4.0 * o_.timeout_s);
  const std::int64_t deadline = MonoNowNs() + static_cast<std::int64_t>(wait_s * 1e9);
  std::int64_t discarded = 0;
  while (!stop.load()) {
    while (!pending_lines_.empty()) {
      const std::string line = pending_lines_.front();
      pending_lines_.pop_front();
      const PtuReply r = ParsePtuReply(line);
      if (r.kind == PtuReplyKind::kOk && !r.value && !r.text.empty()) {
        pending_lines_.clear();
        if (discarded > 0 && reporter_.event) {
          reporter_.event(EventLevel::kInfo, "resynchronised; " + std::to_string(discarded) + " late line(s) discarded");
        }
        return true;
      }
      ++discarded;
    }
    const std::int64_t left = deadline - MonoNowNs();
    if (left <= 0) break;
    char buf[256];
    const long n = port_.Read(buf, sizeof buf, std::min(0.1, static_cast<double>(left) * 1e-9), why);
    if (n < 0) {
      *hung_up = true;
      return false;
    }
    if (n == 0) continue;
    pending_at_ = Now();
    std::vector<std::string> lines;
    splitter_.Feed(buf, static_cast<std::size_t>(n), &lines);
    for (auto& l : lines) pending_lines_.push_back(std::move(l));
  }
  if (why) *why = "no answer to V (version) within " + Fixed(wait_s, 1) + " s";
  return false;
}

void PtuDriver::Run(const std::atomic<bool>& stop) {
  const std::int64_t period = static_cast<std::int64_t>(1e9 / o_.rate_hz);
  const std::int64_t reconnect = static_cast<std::int64_t>(o_.reconnect_s * 1e9);
  std::int64_t next_tick = MonoNowNs(), next_attempt = 0;
  bool synced = true;
  while (!stop.load()) {
    std::string why;
    if (!port_.is_open()) {
      if (MonoNowNs() < next_attempt) {
        SleepUntil(next_attempt, stop);
        continue;
      }
      next_attempt = MonoNowNs() + reconnect;
      if (!port_.Open(o_.serial, &why) || !Setup(&why)) {
        port_.Close();
        gap_.Fault(Now(), "turret unavailable: " + why);
        continue;
      }
      {
        std::lock_guard<std::mutex> lock(stats_mutex_);
        ++stats_.reconnects;
      }
      if (reporter_.event) reporter_.event(EventLevel::kInfo, "reconnected on " + o_.serial.port);
      next_tick = MonoNowNs();
      synced = true;
    }
    if (!SleepUntil(next_tick, stop)) break;
    if (!synced) {
      // After an unanswered query a late reply may still come and would be taken for the answer to
      // the next one. The unit answers in order, so: send V (version) and discard every line up to
      // its answer, which nothing else resembles (text, no number).
      bool hup = false;
      if (!Resync(stop, &hup, &why)) {
        if (hup) {
          Disconnected(why);
        } else {
          gap_.Fault(Now(), why);
        }
        next_tick = MonoNowNs();
        continue;
      }
      synced = true;
      next_tick = MonoNowNs();
    }
    Stamp pan_at, tilt_at;
    bool hup = false;
    std::optional<PtuReply> tilt;
    const auto pan = Query("PP", o_.timeout_s, &pan_at, &hup, &why);
    if (!hup && pan && pan->kind == PtuReplyKind::kOk) tilt = Query("TP", o_.timeout_s, &tilt_at, &hup, &why);
    if (hup) {
      Disconnected(why);
      continue;
    }
    auto integral = [](const std::optional<PtuReply>& r) {
      return r && r->kind == PtuReplyKind::kOk && r->value && std::abs(*r->value) < 1e12 &&
             *r->value == std::floor(*r->value);
    };
    if (integral(pan) && integral(tilt)) {
      TurretSample s;
      s.pan_pos = static_cast<std::int64_t>(*pan->value);
      s.tilt_pos = static_cast<std::int64_t>(*tilt->value);
      s.stamp.mono_ns = pan_at.mono_ns + (tilt_at.mono_ns - pan_at.mono_ns) / 2;
      s.stamp.real_ns = pan_at.real_ns + (tilt_at.real_ns - pan_at.real_ns) / 2;
      s.pair_dt_s = static_cast<double>(tilt_at.mono_ns - pan_at.mono_ns) * 1e-9;
      {
        std::lock_guard<std::mutex> lock(stats_mutex_);
        ++stats_.samples;
        s.pan_res_arcsec = stats_.pan_res_arcsec;
        s.tilt_res_arcsec = stats_.tilt_res_arcsec;
      }
      gap_.Ok(s.stamp);
      if (on_sample_) on_sample_(s);
    } else if (!pan || (pan->kind == PtuReplyKind::kOk && !tilt)) {
      if (gap_.Fault(Now(), why)) {
        std::lock_guard<std::mutex> lock(stats_mutex_);
        ++stats_.timeouts;
      }
      synced = false;
    } else {
      const PtuReply& bad = (pan->kind != PtuReplyKind::kOk || !integral(pan)) ? *pan : *tilt;
      Note(&stats_.error_replies,
           "position query answered '" + std::string(bad.kind == PtuReplyKind::kError ? "!" : "*") + bad.text + "'",
           Now());
      gap_.Fault(Now(), "position queries answered with errors");
      if (bad.kind != PtuReplyKind::kError) synced = false;  // not the answer a position query gets
    }
    next_tick += period;
    const std::int64_t now = MonoNowNs();
    if (next_tick < now) {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      ++stats_.late_polls;
      next_tick = now;
    }
  }
  port_.Close();
}

}  // namespace rk::capture

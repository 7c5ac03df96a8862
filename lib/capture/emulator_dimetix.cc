#include "capture/emulator_dimetix.h"

#include <cmath>
#include <cstdio>
#include <random>

#include "capture/clock.h"

namespace rk::capture {

const io::OptionTable<DimetixEmulatorOptions>& DimetixEmulatorOptions::Table() {
  using O = DimetixEmulatorOptions;
  using io::Bounds;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Sub(&O::common, EmulatorOptions::Table())
          .Integer("--device-id", &O::device_id, "", Bounds::Closed(0, 9), "Device ID N in sNg / gNg (0-9)")
          .Real("--rate-hz", &O::rate_hz, "Hz", Bounds::LeftOpen(0, 1000), "Tracking rate of sNh (Hz)")
          .Real("--measure-s", &O::measure_s, "s", Bounds::Closed(0, 10), "Time of one sNg measurement (s)")
          .Real("--range-m", &O::range_m, "m", Bounds::Any(), "Mean distance (m)")
          .Real("--amplitude-m", &O::amplitude_m, "m", Bounds::Any(), "Amplitude of the distance sine (m)")
          .Real("--period-s", &O::period_s, "s", Bounds::Positive(), "Period of the distance sine (s)")
          .Real("--noise-mm", &O::noise_mm, "mm", Bounds::Closed(0, 1000), "Distance noise std (mm)")
          .Real("--temperature-c", &O::temperature_c, "deg C", Bounds::Open(-200, 200),
                "Temperature answered to sNt (deg C)");
  return table;
}

bool DimetixEmulatorOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (!(range_m - std::abs(amplitude_m) > 0.05 && range_m + std::abs(amplitude_m) < 10000)) {
    if (why) *why = "--range-m +- --amplitude-m must stay within 0.05 ... 10000 m";
    return false;
  }
  return true;
}

DimetixEmulator::DimetixEmulator(DimetixEmulatorOptions options)
    : DeviceEmulator(options.common), d_(std::move(options)) {}

void DimetixEmulator::OnConnect(double) {
  // Power-on: not measuring, start-up sequence sent.
  tracking_ = false;
  Reply("g" + std::to_string(d_.device_id) + "?", 0.0);
}

std::string DimetixEmulator::Measurement(double t, const char* letter) {
  const std::string g = "g" + std::to_string(d_.device_id);
  Fault f;
  if (Active(FaultKind::kError, t, &f)) {
    char b[32];
    std::snprintf(b, sizeof b, "@E%03d", f.code);
    return g + b;
  }
  if (RandomError()) return g + "@E255";
  const double r = d_.range_m + d_.amplitude_m * std::sin(2.0 * M_PI * t / d_.period_s) +
                   std::normal_distribution<double>(0.0, d_.noise_mm * 1e-3)(rng());
  const long long units = std::llround(r * 1e4);
  char b[48];
  std::snprintf(b, sizeof b, "%s+%08lld", letter, units);
  return g + b;
}

void DimetixEmulator::OnCommand(const std::string& cmd, double t) {
  const std::string s = "s" + std::to_string(d_.device_id);
  const std::string g = "g" + std::to_string(d_.device_id);
  if (cmd.size() < 3 || cmd.compare(0, 2, s) != 0) return;  // another device on the bus, or noise
  const std::string rest = cmd.substr(2);
  if (rest == "g") {
    tracking_ = false;
    Reply(Measurement(t + d_.measure_s, "g"), d_.measure_s);
  } else if (rest == "h" || rest.rfind("h+", 0) == 0) {
    double period = 1.0 / d_.rate_hz;
    if (rest.size() > 2) {
      try {
        const long ms = std::stol(rest.substr(2));
        if (ms > 0) period = static_cast<double>(ms) * 1e-3;
      } catch (const std::exception&) {
        Reply(g + "@E203", 0.001);
        return;
      }
    }
    tracking_ = true;
    period_ns_ = static_cast<std::int64_t>(period * 1e9);
    next_sample_ns_ = MonoNowNs() + period_ns_;
  } else if (rest == "c") {
    tracking_ = false;
    Reply(g + "?", 0.001);
  } else if (rest == "o") {
    laser_on_ = true;
    Reply(g + "?", 0.001);
  } else if (rest == "p") {
    laser_on_ = false;
    Reply(g + "?", 0.001);
  } else if (rest == "t") {
    char b[32];
    std::snprintf(b, sizeof b, "t+%08lld", std::llround(d_.temperature_c * 10.0));
    Reply(g + b, 0.01);
  } else {
    Reply(g + "@E203", 0.001);
  }
}

void DimetixEmulator::OnTick(double) {
  if (!tracking_) return;
  const std::int64_t now = MonoNowNs();
  while (tracking_ && now >= next_sample_ns_) {
    Reply(Measurement(static_cast<double>(next_sample_ns_ - now) * 1e-9 + Elapsed(), "h"), 0.0);
    next_sample_ns_ += period_ns_;
    if (next_sample_ns_ < now) next_sample_ns_ = now + period_ns_;  // a stall: no burst of old samples
  }
}

}  // namespace rk::capture

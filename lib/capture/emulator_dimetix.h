// Emulated Dimetix DLS rangefinder (protocol in capture/dimetix.h). It answers sNg (one measurement
// after measure_s), sNh / sNh+<ms> (tracking at rate_hz, or every <ms>), sNc, sNo, sNp (gN?), sNt
// (gNt+<0.1 °C>); anything else gN@E203 (the manual's "wrong syntax" code — the emulator's choice).
// It sends its start-up sequence gN? whenever its pty is (re-)created, like a device powered on.
// Measured distance: range_m + amplitude_m · sin(2π t / period_s) + N(0, noise_mm), in 0.1 mm.
#pragma once

#include <cstdint>

#include "capture/emulator.h"

namespace rk::capture {

struct DimetixEmulatorOptions {
  EmulatorOptions common;
  int device_id = 0;
  double rate_hz = 5.0;        // tracking rate of sNh without a sampling time
  double measure_s = 0.05;     // time of one sNg measurement
  double range_m = 50.0;
  double amplitude_m = 5.0;
  double period_s = 20.0;
  double noise_mm = 0.35;
  double temperature_c = 24.5;
  static const io::OptionTable<DimetixEmulatorOptions>& Table();  // with EmulatorOptions::Table()
  // Table().Check, then the distance range.
  bool Check(std::string* why) const;
};

class DimetixEmulator : public DeviceEmulator {
 public:
  explicit DimetixEmulator(DimetixEmulatorOptions options);

 protected:
  void OnCommand(const std::string& command, double t) override;
  void OnTick(double t) override;
  std::int64_t NextWakeNs() const override { return tracking_ ? next_sample_ns_ : INT64_MAX; }
  void OnConnect(double t) override;

 private:
  std::string Measurement(double t, const char* letter);
  DimetixEmulatorOptions d_;
  bool tracking_ = false;
  bool laser_on_ = false;
  std::int64_t period_ns_ = 200000000;
  std::int64_t next_sample_ns_ = 0;
};

}  // namespace rk::capture

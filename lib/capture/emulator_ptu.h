// Emulated FLIR PTU (protocol in capture/ptu.h). Factory state: echo on, verbose feedback. It
// answers PP / TP (position), PR / TR (resolution), PP<n> / TP<n> (move, slewing at slew_deg_s,
// "!" beyond ±limit_deg), ED / EE, FT / FV, V (version), A (await: answered at once); anything else
// "! Illegal command" (the error texts are the emulator's own wording). Until an axis is commanded
// it follows a sine: center + amplitude · sin(2π t / period).
#pragma once

#include <cstdint>

#include "capture/emulator.h"

namespace rk::capture {

struct PtuEmulatorOptions {
  EmulatorOptions common;
  double pan_res_arcsec = 10.8;    // PTU-D48E: 0.003° per position
  double tilt_res_arcsec = 10.8;
  double pan_center_deg = 0.0, pan_amplitude_deg = 30.0, pan_period_s = 40.0;
  double tilt_center_deg = 15.0, tilt_amplitude_deg = 10.0, tilt_period_s = 25.0;
  double slew_deg_s = 50.0;
  double pan_limit_deg = 159.0, tilt_limit_deg = 47.0;  // hypothetical ± travel (D48E: pan ±159°, tilt −47°/+31°)
  double reply_s = 0.001;          // command processing time
  static const io::OptionTable<PtuEmulatorOptions>& Table();  // with EmulatorOptions::Table(); not the limits
  // Table().Check, then the motion within the limits.
  bool Check(std::string* why) const;
};

class PtuEmulator : public DeviceEmulator {
 public:
  explicit PtuEmulator(PtuEmulatorOptions options);

 protected:
  void OnCommand(const std::string& command, double t) override;
  void OnTick(double) override {}
  void OnConnect(double t) override;
  bool IsTerminator(char c) const override { return c == ' ' || c == '\r' || c == '\n'; }
  std::string Echo(const char* data, std::size_t n) const override {
    return echo_ ? std::string(data, n) : std::string();
  }

 private:
  struct Axis {
    double center = 0, amplitude = 0, period = 1, res_arcsec = 1, limit_deg = 180;
    bool commanded = false;
    double from_deg = 0, to_deg = 0, t_cmd = 0;
    double DegAt(double t, double slew) const;
  };
  std::int64_t Position(const Axis& a, double t) const;
  PtuEmulatorOptions p_;
  Axis pan_, tilt_;
  bool echo_ = true, verbose_ = true;
};

}  // namespace rk::capture

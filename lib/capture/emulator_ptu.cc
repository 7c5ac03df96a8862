#include "capture/emulator_ptu.h"

#include <cctype>
#include <cmath>
#include <cstdio>

namespace rk::capture {

const io::OptionTable<PtuEmulatorOptions>& PtuEmulatorOptions::Table() {
  using O = PtuEmulatorOptions;
  using io::Bounds;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Sub(&O::common, EmulatorOptions::Table())
          .Real("--pan-res-arcsec", &O::pan_res_arcsec, "arcsec", Bounds::Open(0, 36000),
                "Pan resolution answered to PR (arcsec per position)")
          .Real("--tilt-res-arcsec", &O::tilt_res_arcsec, "arcsec", Bounds::Open(0, 36000),
                "Tilt resolution answered to TR (arcsec per position)")
          .Real("--pan-center-deg", &O::pan_center_deg, "deg", Bounds::Any(), "Centre of the pan sine (deg)")
          .Real("--pan-amplitude-deg", &O::pan_amplitude_deg, "deg", Bounds::Any(), "Amplitude of the pan sine (deg)")
          .Real("--pan-period-s", &O::pan_period_s, "s", Bounds::Positive(), "Period of the pan sine (s)")
          .Real("--tilt-center-deg", &O::tilt_center_deg, "deg", Bounds::Any(), "Centre of the tilt sine (deg)")
          .Real("--tilt-amplitude-deg", &O::tilt_amplitude_deg, "deg", Bounds::Any(),
                "Amplitude of the tilt sine (deg)")
          .Real("--tilt-period-s", &O::tilt_period_s, "s", Bounds::Positive(), "Period of the tilt sine (s)")
          .Real("--slew-deg-s", &O::slew_deg_s, "deg/s", Bounds::Positive(), "Speed of commanded moves (deg/s)")
          .Real("--reply-s", &O::reply_s, "s", Bounds::Closed(0, 10), "Command processing time (s)");
  return table;
}

bool PtuEmulatorOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!Table().Check(*this, why)) return false;
  if (!(std::abs(pan_center_deg) + std::abs(pan_amplitude_deg) <= pan_limit_deg))
    return fail("the pan motion must stay within +-pan limit");
  if (!(std::abs(tilt_center_deg) + std::abs(tilt_amplitude_deg) <= tilt_limit_deg))
    return fail("the tilt motion must stay within +-tilt limit");
  return true;
}

PtuEmulator::PtuEmulator(PtuEmulatorOptions options) : DeviceEmulator(options.common), p_(std::move(options)) {
  pan_ = {p_.pan_center_deg, p_.pan_amplitude_deg, p_.pan_period_s, p_.pan_res_arcsec, p_.pan_limit_deg};
  tilt_ = {p_.tilt_center_deg, p_.tilt_amplitude_deg, p_.tilt_period_s, p_.tilt_res_arcsec, p_.tilt_limit_deg};
}

void PtuEmulator::OnConnect(double) {
  // Power-on defaults.
  echo_ = true;
  verbose_ = true;
}

double PtuEmulator::Axis::DegAt(double t, double slew) const {
  if (!commanded) return center + amplitude * std::sin(2.0 * M_PI * t / period);
  const double travel = slew * (t - t_cmd);
  const double d = to_deg - from_deg;
  return std::abs(d) <= travel ? to_deg : from_deg + std::copysign(travel, d);
}

std::int64_t PtuEmulator::Position(const Axis& a, double t) const {
  return std::llround(a.DegAt(t, p_.slew_deg_s) * 3600.0 / a.res_arcsec);
}

void PtuEmulator::OnCommand(const std::string& raw, double t) {
  std::string cmd;
  for (char c : raw) cmd.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  auto ok = [&](const std::string& value, const std::string& verbose_text) {
    if (value.empty()) {
      Reply("*", p_.reply_s);
    } else {
      Reply("* " + (verbose_ ? verbose_text : value), p_.reply_s);
    }
  };
  auto error = [&](const std::string& text) { Reply("! " + text, p_.reply_s); };
  char b[96];
  if (cmd == "PP" || cmd == "TP") {
    const bool pan = cmd[0] == 'P';
    if (Active(FaultKind::kError, t) || RandomError()) {
      error("Device error (emulated)");
      return;
    }
    const std::int64_t pos = Position(pan ? pan_ : tilt_, t + p_.reply_s);
    std::snprintf(b, sizeof b, "%lld", static_cast<long long>(pos));
    ok(b, std::string("Current ") + (pan ? "Pan" : "Tilt") + " position is " + b);
  } else if (cmd == "PR" || cmd == "TR") {
    std::snprintf(b, sizeof b, "%.6g", cmd[0] == 'P' ? p_.pan_res_arcsec : p_.tilt_res_arcsec);
    ok(b, std::string(b) + " seconds arc per position");
  } else if ((cmd.rfind("PP", 0) == 0 || cmd.rfind("TP", 0) == 0) && cmd.size() > 2) {
    Axis& a = cmd[0] == 'P' ? pan_ : tilt_;
    long long target = 0;
    try {
      std::size_t used = 0;
      target = std::stoll(cmd.substr(2), &used);
      if (used != cmd.size() - 2) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      error("Illegal argument");
      return;
    }
    const double deg = static_cast<double>(target) * a.res_arcsec / 3600.0;
    if (std::abs(deg) > a.limit_deg) {
      error(std::string(cmd[0] == 'P' ? "Pan" : "Tilt") + " position out of limits");
      return;
    }
    a.from_deg = a.DegAt(t, p_.slew_deg_s);
    a.to_deg = deg;
    a.t_cmd = t;
    a.commanded = true;
    ok("", "");
  } else if (cmd == "ED" || cmd == "EE") {
    echo_ = cmd == "EE";
    ok("", "");
  } else if (cmd == "FT" || cmd == "FV") {
    verbose_ = cmd == "FV";
    ok("", "");
  } else if (cmd == "V") {
    Reply("* Pan-Tilt Controller v2.12.1 (rangekit emulator)", p_.reply_s);
  } else if (cmd == "A") {
    ok("", "");
  } else {
    error("Illegal command");
  }
}

}  // namespace rk::capture

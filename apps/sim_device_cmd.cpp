// rk-sim device dimetix|ptu: a Dimetix DLS rangefinder or a FLIR PTU emulated on a pseudo-terminal,
// with injectable faults, for rk-capture tests and dry runs. Prints the port to open on stdout.
// Thin edge: CLI11 options → rk::capture::{Dimetix,Ptu}EmulatorOptions → the emulator; docs/rk-sim.md.
#include <signal.h>

#include <atomic>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "capture/emulator_dimetix.h"
#include "capture/emulator_ptu.h"
#include "io/cli.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "sim_commands.h"

namespace rk::app {
namespace {

std::atomic<bool> g_device_stop{false};
void OnDeviceSignal(int) { g_device_stop.store(true); }

struct DeviceCli {
  rk::capture::DimetixEmulatorOptions dimetix;
  rk::capture::PtuEmulatorOptions ptu;
  std::vector<std::string> faults;
  std::string link, truth, port_file;
  double baud = 0, error_rate = 0, duration_s = 0;
  std::uint64_t seed = 1;
};

void AddCommon(CLI::App* s, DeviceCli* c) {
  s->add_option("--link", c->link,
                "Keep a symbolic link at this path to the pty (stable across emulated disconnects)");
  s->add_option("--port-file", c->port_file, "Also write the port path (link or pty) to this file");
  s->add_option("--truth", c->truth, "Write every reply sent and command received (host_mono_s,event,data)");
  s->add_option("--duration", c->duration_s, "Stop after S seconds (default: until SIGINT or SIGTERM)");
  s->add_option("--fault", c->faults,
                "KIND:START:DURATION[:ARG], KIND = error (ARG code), silence, garbage, slow (ARG delay s), "
                "disconnect; START in s since the emulator started; repeatable");
  s->add_option("--error-rate", c->error_rate, "Probability that a measurement is answered with an error")
      ->capture_default_str();
  s->add_option("--baud", c->baud, "Pace replies at this line rate, 10 bits per byte (0 = no pacing)")
      ->capture_default_str();
  s->add_option("--seed", c->seed, "Random seed (noise, errors, garbage)")->capture_default_str();
}

rk::capture::EmulatorOptions Common(const DeviceCli& c) {
  rk::capture::EmulatorOptions e;
  e.link = c.link;
  e.truth_path = c.truth;
  e.baud = c.baud;
  e.error_rate = c.error_rate;
  e.seed = c.seed;
  for (const auto& f : c.faults) {
    rk::capture::Fault fault;
    std::string why;
    if (!rk::capture::ParseFault(f, &fault, &why)) throw rk::UsageError(why);
    e.faults.push_back(fault);
  }
  return e;
}

int Serve(rk::capture::DeviceEmulator* emu, const DeviceCli& c, const Context& ctx, const char* kind) {
  if (!(c.duration_s >= 0)) throw rk::UsageError("--duration must be >= 0");
  std::string why;
  if (!emu->Start(&why)) throw rk::IoError(c.link.empty() ? "pty" : c.link, why);
  struct sigaction sa {};
  sa.sa_handler = OnDeviceSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  if (!c.port_file.empty()) rk::io::WriteFileAtomic(c.port_file, emu->port() + "\n");
  std::cout << emu->port() << std::endl;
  emu->Run(g_device_stop, c.duration_s);
  if (!ctx.common.report_path.empty()) {
    rk::io::Json r = rk::cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = std::string("device ") + kind;
    r["port"] = emu->port();
    const rk::capture::EmulatorStats st = emu->stats();
    r["summary"] = {{"sent", st.sent},         {"dropped", st.dropped},   {"garbage", st.garbage},
                    {"received", st.received}, {"ignored", st.ignored},   {"disconnects", st.disconnects}};
    rk::cli::WriteReport(ctx.common.report_path, r);
  }
  return 0;
}

}  // namespace

Command AddDeviceCommand(CLI::App& parent) {
  CLI::App* device = parent.add_subcommand(
      "device", "Emulate a serial device on a pseudo-terminal (dimetix: DLS rangefinder, ptu: FLIR pan-tilt unit)");
  device->require_subcommand(1);
  auto c = std::make_shared<DeviceCli>();
  auto& d = c->dimetix;
  auto& p = c->ptu;

  CLI::App* dim = device->add_subcommand("dimetix", "Dimetix DLS laser rangefinder (sNg, sNh, sNc, sNo, sNp, sNt)");
  AddCommon(dim, c.get());
  dim->add_option("--device-id", d.device_id, "Device ID N in sNg / gNg (0-9)")->capture_default_str();
  dim->add_option("--rate-hz", d.rate_hz, "Tracking rate of sNh (Hz)")->capture_default_str();
  dim->add_option("--measure-s", d.measure_s, "Time of one sNg measurement (s)")->capture_default_str();
  dim->add_option("--range-m", d.range_m, "Mean distance (m)")->capture_default_str();
  dim->add_option("--amplitude-m", d.amplitude_m, "Amplitude of the distance sine (m)")->capture_default_str();
  dim->add_option("--period-s", d.period_s, "Period of the distance sine (s)")->capture_default_str();
  dim->add_option("--noise-mm", d.noise_mm, "Distance noise std (mm)")->capture_default_str();
  dim->add_option("--temperature-c", d.temperature_c, "Temperature answered to sNt (deg C)")->capture_default_str();

  CLI::App* ptu = device->add_subcommand("ptu", "FLIR PTU-D46/D48 pan-tilt unit (PP, TP, PR, TR, PP<n>, TP<n>, ED, FT, V)");
  AddCommon(ptu, c.get());
  ptu->add_option("--pan-res-arcsec", p.pan_res_arcsec, "Pan resolution answered to PR (arcsec per position)")
      ->capture_default_str();
  ptu->add_option("--tilt-res-arcsec", p.tilt_res_arcsec, "Tilt resolution answered to TR (arcsec per position)")
      ->capture_default_str();
  ptu->add_option("--pan-center-deg", p.pan_center_deg, "Centre of the pan sine (deg)")->capture_default_str();
  ptu->add_option("--pan-amplitude-deg", p.pan_amplitude_deg, "Amplitude of the pan sine (deg)")->capture_default_str();
  ptu->add_option("--pan-period-s", p.pan_period_s, "Period of the pan sine (s)")->capture_default_str();
  ptu->add_option("--tilt-center-deg", p.tilt_center_deg, "Centre of the tilt sine (deg)")->capture_default_str();
  ptu->add_option("--tilt-amplitude-deg", p.tilt_amplitude_deg, "Amplitude of the tilt sine (deg)")
      ->capture_default_str();
  ptu->add_option("--tilt-period-s", p.tilt_period_s, "Period of the tilt sine (s)")->capture_default_str();
  ptu->add_option("--slew-deg-s", p.slew_deg_s, "Speed of commanded moves (deg/s)")->capture_default_str();
  ptu->add_option("--reply-s", p.reply_s, "Command processing time (s)")->capture_default_str();

  return {device, [c, dim](const Context& ctx) -> int {
            std::string why;
            if (dim->parsed()) {
              c->dimetix.common = Common(*c);
              if (!c->dimetix.Check(&why)) throw rk::UsageError(why);
              rk::capture::DimetixEmulator emu(c->dimetix);
              return Serve(&emu, *c, ctx, "dimetix");
            }
            c->ptu.common = Common(*c);
            if (!c->ptu.Check(&why)) throw rk::UsageError(why);
            rk::capture::PtuEmulator emu(c->ptu);
            return Serve(&emu, *c, ctx, "ptu");
          }};
}

}  // namespace rk::app

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
  double duration_s = 0;
};

// The options both devices take and that are not in a table (EmulatorOptions::Table() follows them).
void AddCommon(CLI::App* s, DeviceCli* c) {
  s->add_option("--link", c->link,
                "Keep a symbolic link at this path to the pty (stable across emulated disconnects)");
  s->add_option("--port-file", c->port_file, "Also write the port path (link or pty) to this file");
  s->add_option("--truth", c->truth, "Write every reply sent and command received (host_mono_s,event,data)");
  s->add_option("--duration", c->duration_s, "Stop after S seconds (default: until SIGINT or SIGTERM)");
  s->add_option("--fault", c->faults,
                "KIND:START:DURATION[:ARG], KIND = error (ARG code), silence, garbage, slow (ARG delay s), "
                "disconnect; START in s since the emulator started; repeatable");
}

// The table's options (in `e`) with the paths and faults.
rk::capture::EmulatorOptions Common(const DeviceCli& c, rk::capture::EmulatorOptions e) {
  e.link = c.link;
  e.truth_path = c.truth;
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

  CLI::App* dim = device->add_subcommand("dimetix", "Dimetix DLS laser rangefinder (sNg, sNh, sNc, sNo, sNp, sNt)");
  AddCommon(dim, c.get());
  rk::cli::AddOptions(dim, &c->dimetix, rk::capture::DimetixEmulatorOptions::Table());

  CLI::App* ptu = device->add_subcommand("ptu", "FLIR PTU-D46/D48 pan-tilt unit (PP, TP, PR, TR, PP<n>, TP<n>, ED, FT, V)");
  AddCommon(ptu, c.get());
  rk::cli::AddOptions(ptu, &c->ptu, rk::capture::PtuEmulatorOptions::Table());

  return {device, [c, dim](const Context& ctx) -> int {
            std::string why;
            if (dim->parsed()) {
              c->dimetix.common = Common(*c, c->dimetix.common);
              if (!c->dimetix.Check(&why)) throw rk::UsageError(why);
              rk::capture::DimetixEmulator emu(c->dimetix);
              return Serve(&emu, *c, ctx, "dimetix");
            }
            c->ptu.common = Common(*c, c->ptu.common);
            if (!c->ptu.Check(&why)) throw rk::UsageError(why);
            rk::capture::PtuEmulator emu(c->ptu);
            return Serve(&emu, *c, ctx, "ptu");
          }};
}

}  // namespace rk::app

// rk-capture: record a live station (cameras, Dimetix rangefinder, FLIR turret) into a trial
// directory (SPEC.md §1, §6); `rk-capture recover DIR` checks and repairs one after a crash.
// Thin edge: CLI11 options → rk::capture::{RunCapture, RecoverTrial}; docs/rk-capture.md.
// The main mode takes its options directly (SPEC.md §1.1), so this main uses rk::cli::Run itself.
#include <signal.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <string>

#include "capture/aravis_source.h"
#include "capture/recorder.h"
#include "capture/recover.h"
#include "capture/station_config.h"
#include "io/cli.h"
#include "io/error.h"
#include "io/json_util.h"

namespace {

constexpr const char* kTool = "rk-capture";
std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

void OnSignal(int) { g_stop.store(true); }

void InstallStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = OnSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: sleeping calls return early
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

std::string Fixed(double v, int d) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", d, v);
  return b;
}

int RunRecover(const std::string& dir, bool check_only, const rk::cli::CommonOptions& common, int argc,
               char** argv) {
  rk::capture::RecoverOptions o;
  o.check_only = check_only;
  const rk::capture::RecoverSummary s = rk::capture::RecoverTrial(dir, o);
  if (!common.report_path.empty()) {
    rk::io::Json r = rk::cli::MakeReport(kTool, argc, argv);
    r["subcommand"] = "recover";
    r["summary"] = s.ToJson();
    rk::cli::WriteReport(common.report_path, r);
  }
  if (!s.readable()) {
    throw rk::DataError(dir, 0, 0,
                        "unreadable data: " + s.problems.front() +
                            (s.problems.size() > 1 ? " (and " + std::to_string(s.problems.size() - 1) + " more)" : "") +
                            (check_only ? "" : "; see trial.json capture.recover"));
  }
  if (!common.quiet) {
    std::int64_t frames = 0;
    for (const auto& [cam, n] : s.frames) frames += n;
    std::cerr << kTool << ": " << dir << ": readable, " << frames << " frames, state " << s.state_after << "; "
              << s.repairs.size() << (check_only ? " repair(s) needed" : " repair(s)")
              << (s.repairs.empty() ? "" : ": " + s.repairs.front() + (s.repairs.size() > 1 ? ", ..." : "")) << "\n";
  }
  return 0;
}

int RunRecord(const std::string& config_path, rk::capture::CaptureOptions o, const rk::cli::CommonOptions& common,
              int argc, char** argv) {
  const std::string& out = o.out_dir;
  if (config_path.empty()) throw rk::UsageError("--config is required (or the subcommand recover)");
  if (out.empty()) throw rk::UsageError("--out is required");
  std::string why;
  if (!rk::capture::CaptureOptions::Table().Check(o, &why)) throw rk::UsageError(why);
  const rk::capture::StationConfig cfg = rk::capture::LoadStationConfig(config_path);
  std::mutex err_mutex;
  const bool progress = rk::cli::ShowProgress(common);
  bool status_shown = false;
  for (const auto& w : cfg.warnings) rk::cli::Warn(kTool, common, w);

  o.stop = &g_stop;
  o.command_line.assign(argv, argv + argc);
  if (progress) {
    o.status = [&](const std::string& line) {
      std::lock_guard<std::mutex> lock(err_mutex);
      std::cerr << "\r" << line << "\x1b[K" << std::flush;
      status_shown = true;
    };
  }
  o.warn = [&](const std::string& what) {
    if (common.quiet) return;
    std::lock_guard<std::mutex> lock(err_mutex);
    if (status_shown) std::cerr << "\r\x1b[K";
    std::cerr << kTool << ": warning: " << what << "\n" << std::flush;
  };
  if (!o.Check(&why)) throw rk::UsageError(why);
  InstallStopHandlers();
  const rk::capture::CaptureSummary s = rk::capture::RunCapture(cfg, o);
  {
    std::lock_guard<std::mutex> lock(err_mutex);
    if (status_shown) std::cerr << "\n";
  }
  if (!common.report_path.empty()) {
    rk::io::Json r = rk::cli::MakeReport(kTool, argc, argv);
    rk::cli::AddReportInput(&r, "config", config_path);
    r["out"] = out;
    r["options"] = rk::capture::CaptureOptions::Table().ToJson(o);
    r["summary"] = s.ToJson();
    rk::cli::WriteReport(common.report_path, r);
  }
  if (s.write_failures > 0) {
    throw rk::IoError(out, std::to_string(s.write_failures) +
                               " record(s) could not be written (disk full or I/O error); what was written is readable, "
                               "see events.log and the gaps in trial.json");
  }
  if (!common.quiet) {
    std::string line = std::string(kTool) + ": recorded " + Fixed(s.recorded_s, 1) + " s into " + out + " (" +
                       s.stop_reason + ")";
    for (const auto& c : s.cameras) {
      line += "; " + c.name + " " + std::to_string(c.written) + " frames, " +
              std::to_string(c.dropped_queue + c.dropped_disk + c.write_failed) + " dropped";
    }
    if (s.range) line += "; range " + std::to_string(s.range_rows) + " rows";
    if (s.turret) line += "; turret " + std::to_string(s.turret_rows) + " rows";
    line += "; " + std::to_string(s.gaps) + " gap(s)";
    std::cerr << line << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "rk-capture: record a live station (cameras, Dimetix DLS rangefinder, FLIR PTU turret) into a trial "
      "directory, crash-safe (docs/rk-capture.md)",
      kTool};
  rk::cli::CommonOptions common;
  rk::cli::AddCommonOptions(app, kTool, &common);
  std::string config;
  rk::capture::CaptureOptions record;
  app.add_option("--config,-c", config, "Station configuration JSON (SPEC.md section 6; paths in it relative to it)");
  app.add_option("--out,-o", record.out_dir, "Trial folder to create (refused if it exists and is not empty)");
  rk::cli::AddOptions(&app, &record, rk::capture::CaptureOptions::Table());
  CLI::App* recover = app.add_subcommand(
      "recover",
      "Check a trial directory and repair what a crash leaves (torn last lines and frames, the manifest); "
      "exit 3 if any data is unreadable");
  std::string dir;
  bool check_only = false;
  recover->add_option("dir", dir, "Trial directory written by rk-capture")->required();
  recover->add_flag("--check", check_only, "Only report what would be repaired; change nothing");
  bool list_cameras = false;
  app.add_flag("--list-cameras", list_cameras,
               "List the GigE Vision / USB3 Vision cameras Aravis discovers (id for an aravis: source, model, serial, "
               "address) and exit");
  app.require_subcommand(0, 1);
  return rk::cli::Run(app, kTool, argc, argv, [&]() -> int {
    if (list_cameras) {
      // id,model,serial,address: one camera a line (CSV, for scripts), nothing when none answers.
      std::cout << "id,model,serial,address\n";
      for (const rk::capture::AravisCameraInfo& c : rk::capture::ListAravisCameras()) {
        std::cout << c.id << "," << c.model << "," << c.serial << "," << c.address << "\n";
      }
      return 0;
    }
    if (recover->parsed()) {
      if (!config.empty() || !record.out_dir.empty() || app.count("--duration") > 0) {
        throw rk::UsageError("recover takes a trial directory only (no --config, --out or --duration)");
      }
      return RunRecover(dir, check_only, common, argc, argv);
    }
    return RunRecord(config, record, common, argc, argv);
  });
}

// A small beacon trial with stand-in tools (shell scripts that answer --version) for driving rk-run's
// engine without the real tools: used by test_run's report tests and by the fuzz harness of the report
// reader (tests/fuzz/fuzz_run_report.cc).
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "run/manifest.h"
#include "run/runner.h"

namespace rk::run::testing {

// Writes DIR/bin/<tool> for every tool of StepKinds() and the trial DIR/t0001 (trial.json, its input
// files, an out/ with one product and one step log). Returns options that plan it (--dry-run) with
// DIR/tools.json as the tool cache, so that after one run no tool is started again.
inline RunOptions MakeStandInTrial(const std::string& dir) {
  namespace fs = std::filesystem;
  const auto write = [&](const std::string& rel, const std::string& text) {
    std::ofstream(dir + "/" + rel, std::ios::binary | std::ios::trunc) << text;
    return dir + "/" + rel;
  };
  fs::create_directories(dir + "/bin");
  fs::create_directories(dir + "/t0001/az");
  fs::create_directories(dir + "/t0001/out/steps");
  for (const auto& k : StepKinds()) {
    const std::string tool = write(std::string("bin/") + k.tool, std::string("#!/bin/sh\necho '") + k.tool + " 0.1.0'\n");
    fs::permissions(tool, fs::perms::owner_all);
  }
  write("t0001/trial.json", R"({"name": "t0001", "epoch_utc": "2026-11-21T08:00:00Z",
 "cameras": {"az": {"video": ["az/seg_000.mkv"], "frames": "az/frames.csv", "model": "az/camera.json",
                    "role": "beacon"}},
 "turret": "turret.csv", "range": "range.csv", "steps": {}})");
  for (const char* f : {"az/seg_000.mkv", "az/frames.csv", "az/camera.json", "turret.csv", "range.csv",
                        "out/az.track.csv", "out/steps/az.extract-beacon.log"}) {
    write(std::string("t0001/") + f, f);
  }
  RunOptions o;
  o.trial = dir + "/t0001";
  o.dry_run = true;
  o.tool_dirs = {dir + "/bin"};
  o.tool_cache = dir + "/tools.json";
  return o;
}

}  // namespace rk::run::testing

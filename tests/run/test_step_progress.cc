// rk-run's display of its running steps' progress (run/step_progress.h): the files the tools write,
// the line made from them, no environment entry when the display is off.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "run/step_progress.h"
#include "rk_test/temp_dir.h"

namespace rk::run::internal {
namespace {

namespace fs = std::filesystem;

// One folder for the whole test program, removed when it ends.
fs::path TempDir() {
  static const rk::test::TempDir dir("step_progress");
  return dir.path();
}

TEST(StepProgress, OffWhenNobodyShowsIt) {
  StepProgressFiles p;
  EXPECT_FALSE(p.active());
  EXPECT_EQ(p.Add("extract-az", "/nonexistent/x.progress"), "");  // the tool is not asked for progress
  EXPECT_EQ(p.Line(), "");
}

TEST(StepProgress, LineFromTheRunningStepsFilesAndFilesRemoved) {
  const fs::path d = TempDir();
  StepProgressFiles p;
  std::vector<std::string> shown;
  p.Start([&](const std::string& l) { shown.push_back(l); });
  EXPECT_EQ(p.Add("extract-az", (d / "a.progress").string()), "RK_PROGRESS_FILE=" + (d / "a.progress").string());
  p.Add("extract-att", (d / "b.progress").string());
  EXPECT_EQ(p.Line(), "");  // nothing written yet: nothing shown
  std::ofstream(d / "a.progress") << "120 600 frames\n";
  const std::string line = p.Line();
  EXPECT_EQ(line.rfind("extract-az: 120/600 frames (20%)", 0), 0u) << line;
  EXPECT_EQ(line.find("extract-att"), std::string::npos);
  std::ofstream(d / "b.progress") << "7 0 frames\n";  // total unknown
  // One entry per running step, in step-id order, separated by " | ".
  EXPECT_EQ(p.Line().rfind("extract-att: 7 frames", 0), 0u) << p.Line();
  EXPECT_NE(p.Line().find(" | extract-az: 120/600 frames"), std::string::npos) << p.Line();
  p.Remove("extract-az");
  EXPECT_FALSE(fs::exists(d / "a.progress"));
  EXPECT_EQ(p.Line().rfind("extract-att: 7 frames", 0), 0u);
  p.Stop();
  EXPECT_FALSE(fs::exists(d / "b.progress"));  // Stop removes what is left (steps stopped by a signal)
  fs::remove_all(d);
}

}  // namespace
}  // namespace rk::run::internal

// Inputs found by the fuzz harness of rk-run's report reader (tests/fuzz/fuzz_run_report.cc); each is
// also in the committed corpus tests/fuzz/corpus/fuzz_run_report/crash-*.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "run/runner.h"
#include "stand_in_trial.h"
#include "rk_test/temp_dir.h"

namespace rk::run {
namespace report_regression {
namespace fs = std::filesystem;

class StandInTrial : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tmp_.path();
    options_ = testing::MakeStandInTrial(dir_);
    options_.progress = [this](const std::string& line) { said_.push_back(line); };
    const RunSummary first = RunTrial(options_);  // identifies the stand-in tools into the cache
    ASSERT_EQ(first.result, TrialResult::kPlanned) << first.error;
  }
  const rk::test::TempDir tmp_{"report_regression"};

  // Plans the trial with `report` as out/report.json.
  RunSummary PlanWith(const std::string& report) {
    std::ofstream(dir_ + "/t0001/out/report.json") << report;
    said_.clear();
    return RunTrial(options_);
  }
  bool Said(const std::string& needle) const {
    for (const auto& l : said_) {
      if (l.find(needle) != std::string::npos) return true;
    }
    return false;
  }

  std::string dir_;
  RunOptions options_;
  std::vector<std::string> said_;
};

// A previous report with a field of an unexpected type made nlohmann::json throw type_error out of
// rk-run's planning ("internal: [json.exception.type_error.302] ...", exit 1 for every later run until
// out/ was deleted by hand), and a huge number where an integer was read was undefined behaviour
// (double → integer conversion out of range). Such a report is now not trusted: every step runs again.
TEST_F(StandInTrial, DamagedPreviousReportIsNotTrusted) {
  for (const std::string report : {
           R"({"tool": "rk-run", "inputs": {"trial.json": {"bytes": 1e300}}})",
           R"({"tool": "rk-run", "inputs": {"trial.json": {"bytes": "331"}}})",
           R"({"tool": "rk-run", "steps": [{"id": "az/extract-beacon", "key": 5}]})",
           R"({"tool": "rk-run", "steps": [{"id": "az/extract-beacon", "key": "k", "key_parts": {"inputs": [1]}}]})",
           R"({"tool": "rk-run", "steps": [{"id": "az/locate", "outputs": [{"path": "az.track.csv", "mtime_ns": "x"}]}]})",
           R"({"tool": "rk-run", "trial": [1]})",
           R"({"tool": "rk-run", "tools": {"rk-extract": {"path": 3}}})",
       }) {
    const RunSummary s = PlanWith(report);
    EXPECT_EQ(s.result, TrialResult::kPlanned) << report << ": " << s.error;
    EXPECT_EQ(s.error, "") << report;
    EXPECT_TRUE(Said("out/report.json is damaged")) << report;
    for (const StepLine& l : s.steps) {
      if (l.status == "would run") {
        EXPECT_EQ(l.reason.find("up to date"), std::string::npos) << l.id;
      }
    }
  }
  // Not a report of rk-run at all: ignored as before, without a warning.
  EXPECT_EQ(PlanWith(R"({"tool": 5})").error, "");
  EXPECT_FALSE(Said("damaged"));
  EXPECT_EQ(PlanWith("[1, 2]").error, "");
}

// The same for a damaged record in the --tool-cache file that every trial of a nightly run shares.
TEST_F(StandInTrial, DamagedToolCacheRecordIsNotTrusted) {
  const std::string tool = dir_ + "/bin/rk-extract";
  std::ofstream(options_.tool_cache) << R"({")" << tool << R"(": {"path": ")" << tool
                                     << R"(", "bytes": 1e300, "id": 1, "version": []}})";
  const RunSummary s = PlanWith("{}");
  EXPECT_EQ(s.result, TrialResult::kPlanned) << s.error;
  EXPECT_EQ(s.error, "");
}

}  // namespace report_regression
}  // namespace rk::run

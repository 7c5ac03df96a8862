// Unit tests of run/run_report.cc: the quality figures of a step take the tool report's "summary" object
// whatever the step kind is.
#include <gtest/gtest.h>

#include "io/json_util.h"
#include "run/trial_run.h"

namespace rk::run::internal {
namespace {
using io::Json;

// A summary rk-run has never seen (a future tool's) is copied member by member: numbers and objects of
// numbers, as the tool wrote them.
TEST(RunReport, CopiesAnArbitrarySummaryWithoutKnowingTheKind) {
  const Json report = Json::parse(R"({"tool": "rk-future", "mean_ncc": 0.5,
      "summary": {"widgets": 12, "fit_rms_px": 0.25, "per_axis": {"x": 1.5, "y": null}}})");
  Json quality = {{"rows", 40}};
  AddToolSummary(report, &quality);
  EXPECT_EQ(quality, Json::parse(R"({"rows": 40, "widgets": 12, "fit_rms_px": 0.25,
                                      "per_axis": {"x": 1.5, "y": null}})"));
}

// rk-run's own table figures stay; a report without a summary (or not an object) adds nothing.
TEST(RunReport, TableFiguresWinAndMissingSummaryAddsNothing) {
  Json quality = {{"rows", 40}, {"ok_fraction", 0.9}};
  AddToolSummary(Json::parse(R"({"summary": {"rows": 7, "frames": 41}})"), &quality);
  EXPECT_EQ(quality["rows"], 40);
  EXPECT_EQ(quality["frames"], 41);
  const Json before = quality;
  for (const char* rep : {R"({"frames": 3})", R"({"summary": [1, 2]})", "null", R"("text")"}) {
    AddToolSummary(Json::parse(rep), &quality);
    EXPECT_EQ(quality, before) << rep;
  }
}

}  // namespace
}  // namespace rk::run::internal

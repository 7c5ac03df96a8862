// io::RunSummary, its one serialisation (cli::WriteReport) and the one stream check (cli::CheckStreams).
#include "io/run_summary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/cli.h"
#include "io/error.h"
#include "io/json_util.h"
#include "rk_test/temp_dir.h"

namespace rk::io {
namespace {

TEST(RunSummary, BriefReportNamesRowsTerminationFiguresAndWarnings) {
  RunSummary s;
  s.CountRows(RowStatus::kOk, 480);
  s.CountRows(RowStatus::kLost, 20);
  s.termination = "converged";
  s.AddFigure("tracked frames", 0.96, "fraction");
  s.AddFigure("bias", 1.5, "m");
  s.Warn("rows_lost", "20 of 500 rows lost");
  EXPECT_EQ(s.TotalRows(), 500u);
  EXPECT_EQ(s.BriefReport(), "500 rows: 480 ok, 20 lost; converged; tracked frames 96.0 %; bias 1.5 m; 1 warning");
}

TEST(RunSummary, WithoutRowsTheBriefReportStartsWithTheTermination) {
  RunSummary s;
  s.AddFigure("undefined", std::nan(""), "m");
  s.Flag("outliers_rejected", "3 outliers rejected");
  s.Warn("a", "b");
  EXPECT_FALSE(s.rows_by_status.has_value());
  EXPECT_EQ(s.BriefReport(), "completed; undefined -; 2 warnings");
  EXPECT_FALSE(s.warnings[0].on_stderr);
  EXPECT_TRUE(s.warnings[1].on_stderr);
}

TEST(WriteReport, SerialisesTheSummaryUnderTheUniformKeys) {
  test::TempDir dir;
  const std::string csv = dir / "in.csv";
  test::WriteFile(csv, "t_s\n1\n");
  Json report = {{"tool", "rk-x"}, {"inputs", {{"track", {{"path", csv}, {"rows_skipped", 2u}}}}},
                 {"warnings", "replaced"}};
  RunSummary s;
  s.CountRows(RowStatus::kOk, 3);
  s.Warn("no_range", "no frame got a range");
  s.Flag("covariance_repaired", "1 covariance repair(s)");
  s.termination = "time limit";
  s.AddFigure("range coverage", 0.5, "fraction", "rows with a range");
  s.AddFigure("sigma", std::nan(""), "m");
  s.details = {{"counts", {{"status", {{"ok", 3}}}}}, {"summary", {{"rows_with_los", 3}}}};
  cli::WriteReport(dir / "r.json", report, s);
  const Json r = LoadJson(dir / "r.json");
  EXPECT_EQ(r["status"], "ok");
  EXPECT_EQ(r["counts"]["status"]["ok"], 3);  // the tool's own keys stay
  EXPECT_EQ(r["summary"]["rows_with_los"], 3);
  EXPECT_EQ(r["rows_by_status"], Json({{"ok", 3}, {"reacquired", 0}, {"predicted", 0}, {"lost", 0}, {"invalid", 0}}));
  ASSERT_EQ(r["warnings"].size(), 3u);
  EXPECT_EQ(r["warnings"][0], Json({{"code", "no_range"}, {"message", "no frame got a range"}}));
  EXPECT_EQ(r["warnings"][1]["code"], "covariance_repaired");
  EXPECT_EQ(r["warnings"][2], Json({{"code", "rows_skipped"},
                                    {"message", "2 bad row(s) of " + csv + " skipped (--bad-rows skip)"}}));
  EXPECT_EQ(r["termination"], "time limit");
  EXPECT_EQ(r["headline"]["range coverage"],
            Json({{"value", 0.5}, {"unit", "fraction"}, {"note", "rows with a range"}}));
  EXPECT_TRUE(r["headline"]["sigma"]["value"].is_null());
}

TEST(WriteReport, ATableLessToolHasNullRowsByStatus) {
  test::TempDir dir;
  cli::WriteReport(dir / "r.json", Json::object(), RunSummary{});
  const Json r = LoadJson(dir / "r.json");
  EXPECT_TRUE(r["rows_by_status"].is_null());
  EXPECT_EQ(r["warnings"], Json::array());
  EXPECT_EQ(r["termination"], "completed");
  EXPECT_EQ(r["headline"], Json::object());
}

std::string StreamError(const cli::CommonOptions& common, const std::vector<cli::NamedPath>& in,
                        const std::vector<cli::NamedPath>& out) {
  try {
    cli::CheckStreams(common, in, out);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CheckStreams, TheMessagesOfEveryTool) {
  cli::CommonOptions none, to_stdout, to_file;
  to_stdout.report_path = "-";
  to_file.report_path = "out.csv";
  EXPECT_EQ(StreamError(none, {{"--a", "-"}, {"--b", "-"}}, {{"-o", "x"}}),
            "only one input can be read from stdin ('-')");
  EXPECT_EQ(StreamError(none, {{"--a", "-"}, {"--b", ""}}, {{"-o", "-"}}), "");
  EXPECT_EQ(StreamError(to_stdout, {{"-i", "in.csv"}}, {{"-o", "-"}}), "--report and -o cannot both be stdout");
  EXPECT_EQ(StreamError(to_file, {{"-i", "in.csv"}}, {{"-o", "out.csv"}}),
            "--report and -o name the same file out.csv");
  EXPECT_EQ(StreamError(none, {{"-i", "in.csv"}}, {{"--errors", "-"}, {"-o", "-"}}),
            "--errors and -o cannot both be stdout");
  // rk-analyze's -o is the report itself: --report may name it.
  EXPECT_EQ(StreamError(to_file, {{"-i", "in.csv"}}, {{"-o", "out.csv", true}}), "");
}

}  // namespace
}  // namespace rk::io

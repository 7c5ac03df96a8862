// --bad-rows: CsvTable under BadRows::kSkip drops the rows a reader cannot use, says where and
// why, and counts them in the run record; under kError nothing changes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/csv.h"
#include "io/error.h"
#include "io/run_record.h"
#include "rk_test/temp_dir.h"

namespace rk::io {
namespace {

// A turret-like rule: t_s required and non-decreasing, angles optional numbers.
CsvReadOptions SkipTurret() {
  CsvReadOptions o;
  o.bad_rows = BadRows::kSkip;
  o.rule.non_decreasing = "t_s";
  o.rule.optional_numbers = {"az_deg", "el_deg"};
  return o;
}

// Collects warnings instead of printing them.
class WarningCapture {
 public:
  WarningCapture() {
    SetWarningSink([this](const std::string& w) { lines.push_back(w); });
  }
  ~WarningCapture() { SetWarningSink(nullptr); }
  std::vector<std::string> lines;
};

TEST(CsvBadRows, SkipDropsEachKindOfBadRowAndNamesIt) {
  WarningCapture warnings;
  const std::string text =
      "t_s,az_deg,el_deg,note\n"
      "0.0,10,5,a\n"
      "0.1,10.1\n"            // line 3: too few fields
      "0.2,abc,5,b\n"         // line 4: not a number
      "0.3,nan,5,c\n"         // line 5: NaN
      ",10.2,5,d\n"           // line 6: empty time
      "0.4,10.3,,e\n"         // line 7: empty optional value: kept
      "0.35,10.4,5,f\n"       // line 8: time goes backwards
      "0.5,10.5,inf,g\n"      // line 9: infinite
      "0.6,10.6,5,h,extra\n"  // line 10: too many fields
      "0.7,10.7,5,\n";        // line 11: an empty cell of a column the rule does not name: kept
  const CsvTable t = CsvTable::Parse(text, "turret.csv", SkipTurret());
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.Line(0), 2u);
  EXPECT_EQ(t.Line(1), 7u);
  EXPECT_EQ(t.Line(2), 11u);
  ASSERT_EQ(t.skipped().size(), 7u);
  const std::vector<std::size_t> lines = {3, 4, 5, 6, 8, 9, 10};
  for (std::size_t i = 0; i < lines.size(); ++i) EXPECT_EQ(t.skipped()[i].line, lines[i]);
  EXPECT_NE(t.skipped()[0].reason.find("row has 2 fields, header has 4"), std::string::npos);
  EXPECT_NE(t.skipped()[1].reason.find("'abc' is not a number"), std::string::npos);
  EXPECT_EQ(t.skipped()[1].column, 5u);
  EXPECT_NE(t.skipped()[2].reason.find("not a finite number"), std::string::npos);
  EXPECT_NE(t.skipped()[3].reason.find("column 't_s': empty value"), std::string::npos);
  EXPECT_NE(t.skipped()[4].reason.find("goes backwards (0.35 after 0.4 on line 7)"), std::string::npos);
  EXPECT_NE(t.skipped()[5].reason.find("'inf' is not a finite number"), std::string::npos);
  ASSERT_EQ(warnings.lines.size(), 7u);
  EXPECT_EQ(warnings.lines[1].rfind("turret.csv:4:5: skipped bad row: column 'az_deg': 'abc' is not a number", 0), 0u)
      << warnings.lines[1];
}

TEST(CsvBadRows, ErrorModeIsUnchanged) {
  try {
    (void)CsvTable::Parse("t_s,az_deg\n0.0,1\n0.1\n", "turret.csv");
    FAIL() << "a short row must be an error by default";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("turret.csv:3:"), std::string::npos) << e.what();
  }
  // Under kError the rule is not applied: the reader's own checks decide.
  CsvReadOptions o = SkipTurret();
  o.bad_rows = BadRows::kError;
  const CsvTable t = CsvTable::Parse("t_s,az_deg,el_deg\n0.0,x,1\n", "turret.csv", o);
  EXPECT_EQ(t.rows(), 1u);
  EXPECT_TRUE(t.skipped().empty());
}

TEST(CsvBadRows, RowsKeptEqualTheCleanFile) {
  WarningCapture warnings;
  const std::string clean = "t_s,az_deg,el_deg\n0.0,1,2\n0.1,1.1,2.1\n0.2,,2.2\n0.3,1.3,2.3\n";
  const std::string dirty =
      "t_s,az_deg,el_deg\n0.0,1,2\n@@garbage@@\n0.1,1.1,2.1\n0.05,9,9\n0.2,,2.2\n0.25,1.25,+-\n0.3,1.3,2.3\n";
  const CsvTable a = CsvTable::Parse(clean, "a.csv", SkipTurret());
  const CsvTable b = CsvTable::Parse(dirty, "b.csv", SkipTurret());
  ASSERT_EQ(a.rows(), b.rows());
  for (std::size_t r = 0; r < a.rows(); ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(a.Cell(r, c), b.Cell(r, c)) << "row " << r << " col " << c;
  }
  EXPECT_EQ(b.skipped().size(), 3u);
}

TEST(CsvBadRows, IncreasingRuleSkipsRepeatedTimes) {
  WarningCapture warnings;
  CsvReadOptions o = SkipTurret();
  o.rule.increasing = true;
  const CsvTable t = CsvTable::Parse("t_s,az_deg\n0.0,1\n0.0,2\n0.1,3\n", "s.csv", o);
  ASSERT_EQ(t.rows(), 2u);
  ASSERT_EQ(t.skipped().size(), 1u);
  EXPECT_NE(t.skipped()[0].reason.find("repeats"), std::string::npos);
}

// A points track: times shared between ids, strictly increasing within each id. A repeated (id, time) is a
// duplicated record and goes (the later row, with the id and the line of the first); the same time for two
// ids stays; a file without the id column is held to strictly increasing times over the whole file.
TEST(CsvBadRows, IncreasingPerIdSkipsDuplicatedRecordsOnly) {
  WarningCapture warnings;
  CsvReadOptions o = SkipTurret();
  o.rule.increasing_per = "id";
  const CsvTable t = CsvTable::Parse(
      "t_s,id,az_deg\n0.0,a,1\n0.0,b,2\n0.1,a,3\n0.1,b,4\n0.1,a,3\n0.2,a,5\n0.2,b,6\n", "p.csv", o);
  ASSERT_EQ(t.rows(), 6u);
  const int c = t.RequireColumn("az_deg");
  const std::vector<double> kept = {1, 2, 3, 4, 5, 6};
  for (std::size_t r = 0; r < kept.size(); ++r) EXPECT_EQ(t.Double(r, c), kept[r]) << "row " << r;
  ASSERT_EQ(t.skipped().size(), 1u);
  EXPECT_EQ(t.skipped()[0].line, 6u);
  EXPECT_EQ(t.skipped()[0].column, 1u);
  EXPECT_NE(t.skipped()[0].reason.find("repeats for id 'a' (0.1 on line 4)"), std::string::npos)
      << t.skipped()[0].reason;

  const CsvTable plain = CsvTable::Parse("t_s,az_deg\n0.0,1\n0.1,2\n0.1,2\n0.2,3\n", "l.csv", o);
  ASSERT_EQ(plain.rows(), 3u);
  ASSERT_EQ(plain.skipped().size(), 1u);
  EXPECT_EQ(plain.skipped()[0].line, 4u);
  EXPECT_NE(plain.skipped()[0].reason.find("repeats"), std::string::npos) << plain.skipped()[0].reason;
}

// One wild time far ahead (a garbled serial line that still parses) costs that row only, not every
// row after it; a row that jumped back costs only itself.
TEST(CsvBadRows, OneWildTimeAheadCostsOneRow) {
  WarningCapture warnings;
  const CsvTable t =
      CsvTable::Parse("t_s,az_deg\n0.0,1\n0.1,2\n9999.5,3\n0.2,4\n0.3,5\n0.25,6\n0.4,7\n", "s.csv", SkipTurret());
  ASSERT_EQ(t.rows(), 5u);
  const int c = t.RequireColumn("az_deg");
  const std::vector<double> kept = {1, 2, 4, 5, 7};
  for (std::size_t r = 0; r < kept.size(); ++r) EXPECT_EQ(t.Double(r, c), kept[r]) << "row " << r;
  ASSERT_EQ(t.skipped().size(), 2u);
  EXPECT_EQ(t.skipped()[0].line, 4u);
  EXPECT_NE(t.skipped()[0].reason.find("jumps ahead of the rows after it (9999.5 before 0.2 on line 5)"),
            std::string::npos)
      << t.skipped()[0].reason;
  EXPECT_EQ(t.skipped()[1].line, 7u);
  EXPECT_NE(t.skipped()[1].reason.find("goes backwards (0.25 after 0.3 on line 6)"), std::string::npos)
      << t.skipped()[1].reason;
}

TEST(CsvBadRows, RequiredNumbersIntegersAndTexts) {
  WarningCapture warnings;
  CsvReadOptions o;
  o.bad_rows = BadRows::kSkip;
  o.rule.numbers = {"range_m"};
  o.rule.integers = {"frame"};
  o.rule.optional_integers = {"status"};
  o.rule.texts = {"radar"};
  const CsvTable t = CsvTable::Parse(
      "frame,radar,range_m,status\n0,r1,10,0\n1,r1,,0\n2.5,r1,10,0\n3,,10,0\n4,r1,10,x\n5,r1,10,\n", "p.csv", o);
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.Int(0, 0), 0);
  EXPECT_EQ(t.Int(1, 0), 5);
  EXPECT_EQ(t.skipped().size(), 4u);
}

TEST(CsvBadRows, WarnsTwentyThenCounts) {
  WarningCapture warnings;
  std::string text = "t_s,az_deg\n";
  for (int i = 0; i < 50; ++i) text += std::to_string(i) + ",1\nbad\n";
  const CsvTable t = CsvTable::Parse(text, "many.csv", SkipTurret());
  EXPECT_EQ(t.rows(), 50u);
  EXPECT_EQ(t.skipped().size(), 50u);
  ASSERT_EQ(warnings.lines.size(), kMaxSkippedRowWarnings + 1);
  EXPECT_NE(warnings.lines.back().find("skipped 50 bad rows in all"), std::string::npos) << warnings.lines.back();
}

TEST(CsvBadRows, ReadRecordsTheFileAndItsSkippedRows) {
  WarningCapture warnings;
  ClearInputsRead();
  const rk::test::TempDir tmp("bad_rows");
  const std::string path = tmp / "bad_rows.csv";
  const std::string text = "t_s,az_deg\n0,1\nxx,1\n1,2\n";
  {
    std::ofstream f(path);
    f << text;
  }
  const CsvTable t = CsvTable::Read(path, SkipTurret());
  EXPECT_EQ(t.rows(), 2u);
  const auto in = FindInputRead(path);
  ASSERT_TRUE(in.has_value());
  EXPECT_TRUE(in->csv);
  EXPECT_EQ(in->rows_skipped, 1u);
  ASSERT_TRUE(in->bytes.has_value());
  EXPECT_EQ(*in->bytes, text.size());
  std::filesystem::remove(path);
  ClearInputsRead();
}

TEST(CsvBadRows, ParseBadRowsValues) {
  BadRows b = BadRows::kError;
  EXPECT_TRUE(ParseBadRows("skip", &b));
  EXPECT_EQ(b, BadRows::kSkip);
  EXPECT_TRUE(ParseBadRows("error", &b));
  EXPECT_EQ(b, BadRows::kError);
  EXPECT_FALSE(ParseBadRows("ignore", &b));
}

}  // namespace
}  // namespace rk::io

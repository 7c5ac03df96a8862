// CSV text forms and the table's memory (issue 27 items 14 and 16): integers written as numbers,
// RFC 4180 quoted fields over several lines, UTF-16 and the UTF-8 byte-order mark, a file read again
// by windows giving what the same text in memory gives, and the bytes the table holds per row.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/csv.h"
#include "io/error.h"
#include "test_expect_error.h"
#include "rk_test/temp_dir.h"

namespace rk::io {
namespace {

// A file in the test's temporary folder holding `text`; removed by the destructor.
class TempCsv {
 public:
  TempCsv(const std::string& name, const std::string& text)
      : dir_("csv_forms"), path_(dir_ / name) {
    std::ofstream(path_, std::ios::binary) << text;
  }
  const std::string& path() const { return path_; }

 private:
  rk::test::TempDir dir_;
  std::string path_;
};

TEST(CsvForms, IntegersWrittenAsExactNumbersAreIntegers) {
  auto t = CsvTable::Parse("frame\n+0\n0.0\n0e0\n1e3\n-2.000\n1.5\nabc\n1e300\n", "frames.csv");
  const int c = t.RequireColumn("frame");
  EXPECT_EQ(t.Int(0, c), 0);
  EXPECT_EQ(t.Int(1, c), 0);
  EXPECT_EQ(t.Int(2, c), 0);
  EXPECT_EQ(t.Int(3, c), 1000);
  EXPECT_EQ(t.Int(4, c), -2);
  ExpectError([&] { t.Int(5, c); }, ExitCode::kInvalidData, "frames.csv:7:1: column 'frame': '1.5' is not an integer");
  ExpectError([&] { t.Int(6, c); }, ExitCode::kInvalidData, "frames.csv:8:1: column 'frame': 'abc' is not an integer");
  ExpectError([&] { t.Int(7, c); }, ExitCode::kInvalidData, "'1e300' is not an integer");
  // --bad-rows skip judges an integer cell by the same rule.
  CsvReadOptions skip;
  skip.bad_rows = BadRows::kSkip;
  skip.rule.integers = {"frame"};
  auto s = CsvTable::Parse("frame\n+0\n0.0\n1.5\n", "frames.csv", skip);
  EXPECT_EQ(s.rows(), 2u);
  ASSERT_EQ(s.skipped().size(), 1u);
  EXPECT_EQ(s.skipped()[0].line, 4u);
}

TEST(CsvForms, QuotedFieldsMaySpanLinesAndLinesStayTheFilesOwn) {
  const std::string text =
      "id,note,x\n"
      "a,\"one, two\",1\n"
      "b,\"first line\nsecond \"\"quoted\"\" line\",2\n"
      "c,plain,abc\n";
  auto t = CsvTable::Parse(text, "q.csv");
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.Cell(0, 1), "one, two");
  EXPECT_EQ(t.Cell(1, 1), "first line\nsecond \"quoted\" line");
  EXPECT_DOUBLE_EQ(t.Double(1, 2), 2.0);
  EXPECT_EQ(t.Line(1), 3u);
  EXPECT_EQ(t.Line(2), 5u);  // the quoted newline is a line of the file
  ExpectError([&] { t.Double(2, 2); }, ExitCode::kInvalidData, "q.csv:5:9: column 'x'");
  // A cell after the newline inside quotes is named at its own line and column.
  auto u = CsvTable::Parse("id,note,x\nb,\"l1\nl2\",zz\n", "u.csv");
  ExpectError([&] { u.Double(0, 2); }, ExitCode::kInvalidData, "u.csv:3:5: column 'x': 'zz' is not a number");
  ExpectError([&] { CsvTable::Parse("id,note\na,\"never closed\nb,c\n", "n.csv"); }, ExitCode::kInvalidData,
              "n.csv:2:3: a quoted field is never closed");
  ExpectError([&] { CsvTable::Parse("a,b\n\"x\ny\",2,3\n", "w.csv"); }, ExitCode::kInvalidData,
              "w.csv:3:6: row has 3 fields, header has 2");
}

TEST(CsvForms, Utf16IsNotUtf8Text) {
  const std::string le("\xFF\xFEt\0_\0s\0\n\0", 10);
  const std::string be("\xFE\xFF\0t\0_\0s\0\n", 10);
  const std::string no_bom("t\0_\0s\0\n\0" "1\0\n\0", 12);
  for (const std::string& text : {le, be, no_bom}) {
    ExpectError([&] { CsvTable::Parse(text, "u16.csv"); }, ExitCode::kInvalidData, "u16.csv: not UTF-8 text (UTF-16?)");
    TempCsv f("u16.csv", text);
    ExpectError([&] { CsvTable::Read(f.path()); }, ExitCode::kInvalidData, f.path() + ": not UTF-8 text (UTF-16?)");
  }
}

TEST(CsvForms, Utf8ByteOrderMarkIsSkippedWithoutShiftingColumns) {
  const std::string text = "\xEF\xBB\xBFt_s,x\n0.5,abc\n";
  for (int from_file = 0; from_file < 2; ++from_file) {
    TempCsv f("bom.csv", text);
    auto t = from_file ? CsvTable::Read(f.path()) : CsvTable::Parse(text, f.path());
    EXPECT_EQ(t.header()[0], "t_s");
    EXPECT_DOUBLE_EQ(t.Double(0, t.RequireColumn("t_s")), 0.5);
    ExpectError([&] { t.Double(0, 1); }, ExitCode::kInvalidData, f.path() + ":2:5: column 'x'");
    ExpectError([&] { CsvTable::Parse("\xEF\xBB\xBF" "a,a\n", "h.csv"); }, ExitCode::kInvalidData,
                "h.csv:1:3: duplicate column 'a'");
  }
}

// A log big enough that rows cross the 1 MiB windows the file is read by (and one quoted field over
// three lines crosses one): every cell, line and column as from the same text in memory.
std::string LongLog(std::size_t rows) {
  std::string text = "# turret\nt_s,az_deg,el_deg,note\n";
  char line[128];
  for (std::size_t i = 0; i < rows; ++i) {
    const bool quoted = i % 9973 == 0;
    std::snprintf(line, sizeof line, "%.6f,%.8f,%.8f,%s\n", 1000 + 0.001 * static_cast<double>(i),
                  180.0 + 1e-3 * static_cast<double>(i % 1000), -5.0 + 1e-4 * static_cast<double>(i % 777),
                  quoted ? "\"multi\nline, \"\"note\"\"\n\"" : (i % 2 ? "" : "x"));
    text += line;
    if (i % 50000 == 7) text += "# a comment line\n";
  }
  return text;
}

TEST(CsvForms, AFileReadByWindowsGivesWhatTheTextInMemoryGives) {
  const std::string text = LongLog(60000);
  ASSERT_GT(text.size(), 2u << 20);
  TempCsv f("long.csv", text);
  const CsvTable file = CsvTable::Read(f.path());
  const CsvTable mem = CsvTable::Parse(text, f.path());
  ASSERT_EQ(file.rows(), mem.rows());
  ASSERT_EQ(file.rows(), 60000u);
  for (std::size_t r = 0; r < file.rows(); r += 7) {
    ASSERT_EQ(file.Line(r), mem.Line(r)) << r;
    for (int c = 0; c < 3; ++c) ASSERT_EQ(file.Double(r, c), mem.Double(r, c)) << r << "," << c;
    ASSERT_EQ(file.Cell(r, 3), mem.Cell(r, 3)) << r;
    ASSERT_EQ(file.CharColumn(r, 2), mem.CharColumn(r, 2)) << r;
  }
  // Backwards through the file (each row is read again from its own offset).
  for (std::size_t r = file.rows(); r-- > 0;) ASSERT_EQ(file.Double(r, 0), mem.Double(r, 0)) << r;
}

// The common row (one line, no quote) is split by a faster path than a row with a quote: both give the
// same fields, blanks and a CR trimmed, empty fields empty, the column of an error where the field starts;
// a last line without '\n' too. The second table has the same rows, each made to take the general path by
// a quoted field appended.
TEST(CsvForms, RowsWithoutQuotesSplitAsRowsWithQuotes) {
  const std::vector<std::string> rows = {" 1.5 ,\t2\t,,  \r", "7,8, 9,10", ",,,", "\t-3e2 , x ,5,", "4,5,6,7"};
  std::string plain = "a,b,c,d\n", quoted = "a,b,c,d,q\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::string r = rows[i];
    const bool cr = !r.empty() && r.back() == '\r';
    if (cr) r.pop_back();
    plain += rows[i] + (i + 1 < rows.size() ? "\n" : "");  // the last line ends without a newline
    quoted += r + ",\"q\"" + (cr ? "\r" : "") + (i + 1 < rows.size() ? "\n" : "");
  }
  for (const bool from_file : {false, true}) {
    TempCsv fp("plain.csv", plain), fq("quoted.csv", quoted);
    const CsvTable p = from_file ? CsvTable::Read(fp.path()) : CsvTable::Parse(plain, "plain.csv");
    const CsvTable q = from_file ? CsvTable::Read(fq.path()) : CsvTable::Parse(quoted, "quoted.csv");
    ASSERT_EQ(p.rows(), rows.size());
    ASSERT_EQ(q.rows(), rows.size());
    for (std::size_t r = 0; r < p.rows(); ++r) {
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(p.Cell(r, c), q.Cell(r, c)) << r << "," << c;
        EXPECT_EQ(p.IsEmpty(r, c), q.IsEmpty(r, c)) << r << "," << c;
        EXPECT_EQ(p.CharColumn(r, c), q.CharColumn(r, c)) << r << "," << c;
      }
    }
    EXPECT_EQ(p.Cell(0, 0), "1.5");
    EXPECT_EQ(p.Cell(0, 1), "2");
    EXPECT_TRUE(p.IsEmpty(0, 3));  // blanks and the CR
    EXPECT_EQ(p.Double(1, 2), 9.0);
    EXPECT_EQ(p.Double(3, 0), -300.0);
    EXPECT_EQ(p.Double(4, 3), 7.0);  // the last line, without its newline
    ExpectError([&] { p.Double(3, 1); }, ExitCode::kInvalidData, ":5:8:");  // line 5, column 8: after "\t-3e2 ,"
  }
}

// The table holds an index of a few bytes a row (offset, line), not the text: what issue 27 needs
// for peak memory ≤ 1.5 × the input on a 300 MB log (docs/benchmarks.md). The old table kept every
// cell as a std::string with its column: ≈ 200 bytes a row of this log.
constexpr double kMaxHeldBytesPerRow = 8.5;                 // 4 offset + 4 line, vectors at capacity
constexpr std::size_t kWindowAllowance = std::size_t{2} << 20;  // one read window (1 MiB) and the row's fields

TEST(CsvForms, AFileIsHeldAsAFewBytesARow) {
  const std::size_t rows = 120000;
  std::string text = "t_s,az_deg,el_deg\n";
  char line[96];
  for (std::size_t i = 0; i < rows; ++i) {
    std::snprintf(line, sizeof line, "%.6f,%.8f,%.8f\n", 1000 + 0.001 * static_cast<double>(i),
                  180.0 + 1e-3 * static_cast<double>(i % 1000), 12.0);
    text += line;
  }
  TempCsv f("held.csv", text);
  const CsvTable t = CsvTable::Read(f.path());
  double sum = 0.0;
  for (std::size_t r = 0; r < t.rows(); ++r) sum += t.Double(r, 0) + t.Double(r, 1) + t.Double(r, 2);
  EXPECT_GT(sum, 0.0);
  EXPECT_LE(static_cast<double>(t.HeldBytes()),
            kMaxHeldBytesPerRow * static_cast<double>(rows) + static_cast<double>(kWindowAllowance))
      << "file " << text.size() << " bytes";
  // A column asked for as text is kept once (its text and an end offset a row), the others not.
  const std::size_t before = t.HeldBytes();
  EXPECT_EQ(t.Cell(rows - 1, 2), "12.00000000");
  EXPECT_LE(t.HeldBytes() - before, (11 + 8) * rows + 64);
}

}  // namespace
}  // namespace rk::io

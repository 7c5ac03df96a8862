// CSV tables (io/csv.h): reading with errors that name file, line and column, writing, lists.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "io/csv.h"
#include "io/csv_stream.h"
#include "io/error.h"
#include "test_expect_error.h"
#include "rk_test/temp_dir.h"

namespace rk::io {
namespace {

TEST(CsvTable, ColumnsByNameCommentsAndEmptyFields) {
  auto t = CsvTable::Parse("# a comment\nt_s,range_m,status\n0.0,22.1,0\n# mid comment\n0.2,,255\n", "r.csv");
  ASSERT_EQ(t.rows(), 2u);
  int r = t.RequireColumn("range_m");
  EXPECT_DOUBLE_EQ(t.Double(0, r), 22.1);
  EXPECT_FALSE(t.OptionalDouble(1, r).has_value());
  EXPECT_EQ(t.Int(1, t.RequireColumn("status")), 255);
  EXPECT_EQ(t.Line(1), 5u);
  EXPECT_EQ(t.Column("nope"), -1);
}

TEST(CsvTable, ErrorsNameFileLineAndColumn) {
  auto t = CsvTable::Parse("t_s,x_px\n0.0,1.5\n0.05,abc\n", "track.csv");
  int x = t.RequireColumn("x_px");
  ExpectError([&] { t.Double(1, x); }, ExitCode::kInvalidData, "track.csv:3:6:");
  ExpectError([&] { t.RequireColumn("y_px"); }, ExitCode::kInvalidData, "track.csv:1:1: missing column 'y_px'");
}

TEST(CsvTable, RejectsNanInfAndRaggedRows) {
  auto t = CsvTable::Parse("t_s\nnan\ninf\n", "a.csv");
  ExpectError([&] { t.Double(0, 0); }, ExitCode::kInvalidData, "a.csv:2:1:");
  ExpectError([&] { t.Double(1, 0); }, ExitCode::kInvalidData, "a.csv:3:1:");
  ExpectError([&] { CsvTable::Parse("a,b\n1,2,3\n", "b.csv"); }, ExitCode::kInvalidData, "b.csv:2:5:");
  ExpectError([&] { CsvTable::Parse("# only a comment\n", "c.csv"); }, ExitCode::kInvalidData, "no header");
  ExpectError([&] { CsvTable::Parse("a,a\n", "d.csv"); }, ExitCode::kInvalidData, "duplicate column");
}

TEST(CsvTable, TimeGoingBackwardsIsReportedWhereItHappens) {
  auto t = CsvTable::Parse("t_s\n0.0\n0.1\n0.05\n", "f.csv");
  ExpectError([&] { t.RequireNonDecreasing(0); }, ExitCode::kInvalidData, "f.csv:4:1:");
  auto dup = CsvTable::Parse("t_s\n0.0\n0.0\n", "g.csv");
  EXPECT_NO_THROW(dup.RequireNonDecreasing(0));
  ExpectError([&] { dup.RequireIncreasing(0); }, ExitCode::kInvalidData, "g.csv:3:1:");
}

TEST(CsvTable, QuotedFieldsAndCrLf) {
  auto t = CsvTable::Parse("id,note\r\nnose,\"a, b \"\"c\"\"\"\r\n", "q.csv");
  EXPECT_EQ(t.Cell(0, 1), "a, b \"c\"");
}

// What is waiting in a pipe's read end (non-blocking: "" when nothing was written).
std::string Drain(int fd) {
  std::string out;
  char buf[256];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) return out;
    out.append(buf, static_cast<std::size_t>(n));
  }
}

TEST(CsvStream, SendsEndedRowsToADescriptorAtEachFlush) {
  int fds[2];
  ASSERT_EQ(::pipe2(fds, O_NONBLOCK), 0);
  const std::string path = "/dev/fd/" + std::to_string(fds[1]);
  CsvWriter w({"frame", "x_px"});
  CsvStream out(w, path);
  EXPECT_TRUE(out.streaming());
  EXPECT_EQ(Drain(fds[0]), "");  // nothing before the first flush
  w.Add(0).Add(1.5, 1);
  w.EndRow();
  out.Flush();
  EXPECT_EQ(Drain(fds[0]), "frame,x_px\n0,1.5\n");
  w.Add(1);  // a row being built is not sent
  out.Flush();
  EXPECT_EQ(Drain(fds[0]), "");
  w.Add(2.5, 1);
  w.EndRow();
  w.Add(2).AddEmpty();
  w.EndRow();
  out.Flush();
  EXPECT_EQ(Drain(fds[0]), "1,2.5\n2,\n");
  out.Flush();  // nothing new: nothing written
  EXPECT_EQ(Drain(fds[0]), "");
  w.Add(3).Add(4.0, 1);
  w.EndRow();
  out.Finish();  // the rest
  EXPECT_EQ(Drain(fds[0]), "3,4.0\n");
  EXPECT_EQ(w.str(), "frame,x_px\n0,1.5\n1,2.5\n2,\n3,4.0\n");  // the whole table is still there
  ::close(fds[0]);
  ::close(fds[1]);
}

TEST(CsvStream, FilesAreNotStreamedButWrittenAtomicallyAtTheEnd) {
  const rk::test::TempDir tmp("csv_stream");
  const std::filesystem::path dir = tmp.path();
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "out.csv").string();
  CsvWriter w({"frame"});
  CsvStream out(w, path);
  EXPECT_FALSE(out.streaming());
  w.Add(0);
  w.EndRow();
  out.Flush();
  EXPECT_FALSE(std::filesystem::exists(path));  // a file appears only at Finish, whole
  out.Finish();
  std::FILE* f = std::fopen(path.c_str(), "r");
  ASSERT_NE(f, nullptr);
  char buf[64] = {};
  const std::size_t n = std::fread(buf, 1, sizeof buf - 1, f);
  std::fclose(f);
  EXPECT_EQ(std::string(buf, n), "frame\n0\n");
  std::filesystem::remove_all(dir);
}

TEST(CsvWriter, RoundTripsThroughParser) {
  CsvWriter w({"t_s", "x_px", "status"});
  w.Add(1.0 / 3.0, 9).Add(std::optional<double>{}, 3).Add("ok");
  w.EndRow();
  w.Add(-0.0000001, 3).Add(2.5, 3).Add("a,b");
  w.EndRow();
  auto t = CsvTable::Parse(w.str(), "w.csv");
  EXPECT_EQ(t.Cell(0, 0), "0.333333333");
  EXPECT_TRUE(t.IsEmpty(0, 1));
  EXPECT_EQ(t.Cell(1, 0), "0.000");  // never "-0.000"
  EXPECT_EQ(t.Cell(1, 2), "a,b");
}

TEST(SplitList, TrimsAndDropsEmpties) {
  auto v = SplitList(" az_deg, el_deg ,,range_m");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[1], "el_deg");
}

}  // namespace
}  // namespace rk::io

namespace rk::io {
namespace {

// Found by fuzz_csv's review: from_chars after a skipped '+' read "+-5" as -5.
TEST(CsvTable, OneLeadingPlusIsAllowedButNoSecondSign) {
  auto t = CsvTable::Parse("v\n+5\n+-5\n++5\n+\n-5\n", "s.csv");
  const int c = t.RequireColumn("v");
  EXPECT_DOUBLE_EQ(t.Double(0, c), 5.0);
  for (std::size_t r : {1u, 2u, 3u}) {
    try {
      t.Double(r, c);
      FAIL() << "row " << r << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kInvalidData);
      EXPECT_NE(std::string(e.what()).find("s.csv:" + std::to_string(r + 2) + ":1"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("is not a number"), std::string::npos) << e.what();
    }
  }
  EXPECT_DOUBLE_EQ(t.Double(4, c), -5.0);
}

}  // namespace
}  // namespace rk::io

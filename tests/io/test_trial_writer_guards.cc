// Issue 27's io pieces: the one ISO-8601 UTC reader, duplicate JSON keys, a byte-order mark's positions, the
// "inside the folder" guard and the files a tool makes for itself (never through a link).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/error.h"
#include "io/file_util.h"
#include "io/json_positions.h"
#include "io/json_util.h"
#include "io/utc_time.h"
#include "rk_test/temp_dir.h"

namespace rk::io {
namespace {
namespace fs = std::filesystem;

TEST(UtcIso, AcceptsRealTimes) {
  UtcTime t;
  std::string why;
  ASSERT_TRUE(ParseUtcIso("2026-11-21T08:00:00Z", &t, &why)) << why;
  EXPECT_EQ(t.year, 2026);
  EXPECT_EQ(t.month, 11);
  EXPECT_EQ(t.hour, 8);
  ASSERT_TRUE(ParseUtcIso("2024-02-29T23:59:59.125", &t, &why)) << why;  // leap day, no Z
  EXPECT_DOUBLE_EQ(t.second, 59.125);
  EXPECT_TRUE(ParseUtcIso("2016-12-31T23:59:60.5Z", &t, &why)) << why;  // a leap second
}

TEST(UtcIso, RefusesWhatIsNotAUtcTime) {
  UtcTime t;
  std::string why;
  for (const char* bad : {"2026-13-01T00:00:00Z", "2026-02-29T00:00:00Z", "2026-04-31T00:00:00Z",
                          "2026-01-01T25:00:00Z", "2026-01-01T00:60:00Z", "2026-01-01T00:00:60Z",
                          "2026-01-01T00:00:00+01:00", "2026-01-01T00:00:00-0500", "2026-01-01 00:00:00Z",
                          "2026-1-01T00:00:00Z", "2026-01-01T00:00:00.Z", "2026-01-01T00:00:00ZZ", ""}) {
    EXPECT_FALSE(ParseUtcIso(bad, &t, &why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
  }
  ASSERT_FALSE(ParseUtcIso("2026-01-01T00:00:00+01:00", &t, &why));
  EXPECT_NE(why.find("offset"), std::string::npos) << why;
}

TEST(JsonDuplicateKeys, RefusedAtTheSecond) {
  try {
    ParseJson("{\n  \"a\": 1,\n  \"b\": {\"x\": 1, \"x\": 2}\n}\n", "m.json");
    ADD_FAILURE() << "a duplicate key was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("m.json:3:17: duplicate key 'x' (first at line 3:9)"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(ParseJson("{\"a\": {\"x\": 1}, \"b\": {\"x\": 2}}", "m.json"));  // same key, other objects
}

TEST(JsonPositions, AByteOrderMarkIsNotAColumn) {
  const std::string text = "\xEF\xBB\xBF{\n  \"a\": 1,\n  \"b\": true\n}\n";
  const JsonPositions p(text);
  EXPECT_EQ(p.At("/b").line, 3u);
  EXPECT_EQ(p.At("/b").column, 8u);
  EXPECT_EQ(p.At("").column, 1u);
  try {
    ParseJson("\xEF\xBB\xBF{\"a\": x}", "m.json");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("m.json:1:7:"), std::string::npos) << e.what();
  }
}

TEST(JsonPositions, DeepNestingDoesNotRecurseWithoutBound) {
  std::string text;
  for (int i = 0; i < 100000; ++i) text += "[";
  for (int i = 0; i < 100000; ++i) text += "]";
  const JsonPositions p(text);  // must return (partial index), not overflow the stack
  EXPECT_EQ(p.At("").line, 1u);
  ASSERT_TRUE(p.too_deep());
  EXPECT_EQ(p.too_deep()->column, kMaxJsonDepth + 1);
  try {
    ParseJson(text, "deep.json");
    ADD_FAILURE() << "a 100000-deep text was parsed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("deep.json:1:513: nested deeper than 512 levels"), std::string::npos) << e.what();
  }
  std::string fine = "{\"extra\": ";
  for (int i = 0; i < 300; ++i) fine += "[";
  for (int i = 0; i < 300; ++i) fine += "]";
  EXPECT_NO_THROW(ParseJson(fine + "}", "ok.json"));  // deep, but within the limit: kept
}

class Guards : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tmp_.path();
    fs::create_directories(dir_ / "trial/sub");
    std::ofstream(dir_ / "victim") << "precious";
  }
  const rk::test::TempDir tmp_{"guards"};
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  std::string Victim() const {
    std::ifstream in(dir_ / "victim");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  fs::path dir_;
};

TEST_F(Guards, InsideFolderResolvesDotsAndLinks) {
  EXPECT_TRUE(IsInsideFolder(P("trial"), P("trial/a.csv")));
  EXPECT_TRUE(IsInsideFolder(P("trial"), P("trial/sub/../b.csv")));
  EXPECT_TRUE(IsInsideFolder(P("trial"), P("trial/new/not/yet.csv")));
  EXPECT_FALSE(IsInsideFolder(P("trial"), P("trial/../victim")));
  EXPECT_FALSE(IsInsideFolder(P("trial"), P("victim")));
  EXPECT_FALSE(IsInsideFolder(P("trial"), P("trial")));
  EXPECT_FALSE(IsInsideFolder(P("trial"), P("trialx/a.csv")));  // a prefix of the name is not inside
  fs::create_symlink(P("victim"), P("trial/link.csv"));
  EXPECT_FALSE(IsInsideFolder(P("trial"), P("trial/link.csv")));
  fs::create_directory_symlink(dir_, P("trial/up"));
  EXPECT_FALSE(IsInsideFolder(P("trial"), P("trial/up/victim")));
}

TEST_F(Guards, OwnFilesAreNeverWrittenThroughALink) {
  fs::create_symlink(P("victim"), P("trial/last-run.json"));
  EXPECT_THROW(WriteOwnFileAtomic(P("trial/last-run.json"), "{}"), Error);
  EXPECT_THROW(OpenOwnFile(P("trial/last-run.json"), O_WRONLY | O_APPEND), Error);
  EXPECT_EQ(Victim(), "precious");
  EXPECT_TRUE(fs::is_symlink(P("trial/last-run.json")));
  // A regular file is replaced atomically; a new one is created.
  WriteOwnFileAtomic(P("trial/new.json"), "{}\n");
  WriteOwnFileAtomic(P("trial/new.json"), "{\"a\": 1}\n");
  std::ifstream in(P("trial/new.json"));
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "{\"a\": 1}\n");
  const int fd = OpenOwnFile(P("trial/log"), O_WRONLY | O_CREAT | O_APPEND);
  EXPECT_GE(fd, 0);
  ::close(fd);
}

}  // namespace
}  // namespace rk::io

// The append-only stream logs (capture/append_log.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "capture/append_log.h"
#include "capture/durable_file.h"
#include "io/error.h"
#include "io/file_util.h"
#include "rk_test/temp_dir.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

TEST(AppendLog, LinesAndHeader) {
  const rk::test::TempDir dir_tmp("capture_log");
  const std::string dir = dir_tmp.path();
  Syncer syncer(dir, 0.05);
  syncer.Start();
  {
    AppendLog log((fs::path(dir) / "a.csv").string(), "# c\nt_s,x\n", &syncer);
    std::string why;
    for (int i = 0; i < 10; ++i) ASSERT_TRUE(log.Append(std::to_string(i) + ".0," + std::to_string(2 * i), &why));
    EXPECT_EQ(log.lines(), 10);
    EXPECT_THROW(AppendLog((fs::path(dir) / "a.csv").string(), "x\n", &syncer), Error);  // exists
  }
  syncer.Stop();
  EXPECT_GE(syncer.passes(), 1);
  const std::string text = io::ReadFile((fs::path(dir) / "a.csv").string());
  EXPECT_EQ(text.substr(0, 12), "# c\nt_s,x\n0.");
  EXPECT_EQ(text.back(), '\n');
  EXPECT_GE(syncer.free_bytes(), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rk::capture

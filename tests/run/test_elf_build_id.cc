// Unit tests of run/elf_build_id against readelf (run/process runs it).
#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "run/elf_build_id.h"
#include "run/process.h"
#include "run_test_util.h"

namespace rk::run {
namespace {
using testing::TempDir;
using testing::Write;

TEST(ElfBuildId, MatchesReadelf) {
  const std::string self = SelfDir() + "/test_run";
  const std::string id = ElfBuildId(self);
  ASSERT_FALSE(id.empty()) << "Debian's toolchain links a GNU build ID into every executable";
  EXPECT_EQ(id.size() % 2, 0u);
  std::string out;
  if (::access("/usr/bin/readelf", X_OK) == 0) {
    ASSERT_EQ(RunAndCapture({"/usr/bin/readelf", "-n", self}, &out), 0);
    EXPECT_NE(out.find("Build ID: " + id), std::string::npos) << out;
  }
  TempDir d;
  Write(d / "script", "#!/bin/sh\necho hi\n");
  EXPECT_EQ(ElfBuildId(d / "script"), "");
  EXPECT_EQ(ElfBuildId(d / "missing"), "");
}

}  // namespace
}  // namespace rk::run

// What --version prints (io/version.h): the tool, the suite's version and the git commit.
#include <gtest/gtest.h>

#include "io/version.h"

namespace rk {
namespace {

TEST(Version, LineNamesToolVersionAndCommit) {
  const std::string line = VersionLine("rk-locate");
  EXPECT_EQ(line.rfind("rk-locate (rangekit) ", 0), 0u);
  EXPECT_NE(line.find(std::string("(git ") + kGitCommit + ")"), std::string::npos);
}

}  // namespace
}  // namespace rk

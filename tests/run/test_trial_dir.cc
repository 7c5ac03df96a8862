// Unit tests of run/trial_dir: the trial lock, and the out/ swap with its recovery.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/error.h"
#include "run/trial_dir.h"
#include "run_test_util.h"

namespace rk::run {
namespace {
namespace fs = std::filesystem;
using testing::Read;
using testing::TempDir;
using testing::Write;

TEST(TrialDir, LockIsExclusiveAndReleased) {
  TempDir d;
  std::string holder;
  auto first = TrialLock::Acquire(d.path(), 0.0, &holder);
  ASSERT_TRUE(first);
  // flock locks belong to the open file description: a second open in this process conflicts too.
  EXPECT_FALSE(TrialLock::Acquire(d.path(), 0.2, &holder));
  EXPECT_NE(holder.find("pid " + std::to_string(::getpid())), std::string::npos) << holder;
  first.reset();
  EXPECT_TRUE(TrialLock::Acquire(d.path(), 0.0, &holder));
}

TEST(TrialDir, CommitExchangesAndRemovesTheOldOut) {
  TempDir d;
  Write(d / "out/report.json", "old");
  Write(d / "out/a.csv", "old");
  const std::string work = MakeWorkDir(d.path());
  Write(work + "/report.json", "new");
  Write(work + "/a.csv", "new");
  const std::string how = CommitOut(d.path(), work);
  EXPECT_TRUE(how == "exchange" || how == "two-renames") << how;
  EXPECT_EQ(Read(d / "out/a.csv"), "new");
  EXPECT_FALSE(fs::exists(work));
  EXPECT_TRUE(RecoverAndClean(d.path()).empty());
  // First out/: a plain rename.
  TempDir e;
  const std::string w2 = MakeWorkDir(e.path());
  Write(w2 + "/report.json", "r");
  EXPECT_EQ(CommitOut(e.path(), w2), "rename");
  EXPECT_TRUE(fs::exists(e / "out/report.json"));
}

TEST(TrialDir, RecoveryAfterAKilledSwap) {
  TempDir d;
  // Killed between the two renames of the fallback swap: no out/, a complete new folder and the old one.
  Write(d / "out.old.AAAAAA/report.json", "old");
  Write(d / "out.tmp.BBBBBB/report.json", "new");
  Write(d / "out.tmp.CCCCCC/a.csv", "partial (no report.json)");
  const auto notes = RecoverAndClean(d.path());
  EXPECT_EQ(Read(d / "out/report.json"), "new");
  EXPECT_FALSE(fs::exists(d / "out.old.AAAAAA"));
  EXPECT_FALSE(fs::exists(d / "out.tmp.CCCCCC"));
  EXPECT_EQ(notes.size(), 3u);
  // Only the old one complete: it comes back.
  TempDir e;
  Write(e / "out.old.AAAAAA/report.json", "old");
  Write(e / "out.tmp.BBBBBB/a.csv", "partial");
  RecoverAndClean(e.path());
  EXPECT_EQ(Read(e / "out/report.json"), "old");
  // With an out/ present every temporary goes, complete or not.
  TempDir f;
  Write(f / "out/report.json", "current");
  Write(f / "out.tmp.BBBBBB/report.json", "stale");
  RecoverAndClean(f.path());
  EXPECT_EQ(Read(f / "out/report.json"), "current");
  EXPECT_FALSE(fs::exists(f / "out.tmp.BBBBBB"));
}

}  // namespace
}  // namespace rk::run

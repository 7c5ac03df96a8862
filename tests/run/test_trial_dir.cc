// Unit tests of run/trial_dir: the trial lock, and the out/ swap with its recovery.
#include <gtest/gtest.h>

#include <sys/stat.h>

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
  auto first = TrialLock::Acquire(d / ".rk-run.lock", 0.0, &holder);
  ASSERT_TRUE(first);
  // flock locks belong to the open file description: a second open in this process conflicts too.
  EXPECT_FALSE(TrialLock::Acquire(d / ".rk-run.lock", 0.2, &holder));
  EXPECT_NE(holder.find("pid " + std::to_string(::getpid())), std::string::npos) << holder;
  first.reset();
  EXPECT_TRUE(TrialLock::Acquire(d / ".rk-run.lock", 0.0, &holder));
}

TEST(TrialDir, CommitExchangesAndRemovesTheOldOut) {
  TempDir d;
  Write(d / "out/report.json", "old");
  Write(d / "out/a.csv", "old");
  const std::string work = MakeWorkDir(d / "out");
  Write(work + "/report.json", "new");
  Write(work + "/a.csv", "new");
  const std::string how = CommitOut(d / "out", work);
  EXPECT_TRUE(how == "exchange" || how == "two-renames") << how;
  EXPECT_EQ(Read(d / "out/a.csv"), "new");
  EXPECT_FALSE(fs::exists(work));
  EXPECT_TRUE(RecoverAndClean(d / "out").empty());
  // First out/: a plain rename.
  TempDir e;
  const std::string w2 = MakeWorkDir(e / "out");
  Write(w2 + "/report.json", "r");
  EXPECT_EQ(CommitOut(e / "out", w2), "rename");
  EXPECT_TRUE(fs::exists(e / "out/report.json"));
}

TEST(TrialDir, RecoveryAfterAKilledSwap) {
  TempDir d;
  // Killed between the two renames of the fallback swap: no out/, a complete new folder and the old one.
  Write(d / "out.old.AAAAAA/report.json", "old");
  Write(d / "out.tmp.BBBBBB/report.json", "new");
  Write(d / "out.tmp.CCCCCC/a.csv", "partial (no report.json)");
  const auto notes = RecoverAndClean(d / "out");
  EXPECT_EQ(Read(d / "out/report.json"), "new");
  EXPECT_FALSE(fs::exists(d / "out.old.AAAAAA"));
  EXPECT_FALSE(fs::exists(d / "out.tmp.CCCCCC"));
  EXPECT_EQ(notes.size(), 3u);
  // Only the old one complete: it comes back.
  TempDir e;
  Write(e / "out.old.AAAAAA/report.json", "old");
  Write(e / "out.tmp.BBBBBB/a.csv", "partial");
  RecoverAndClean(e / "out");
  EXPECT_EQ(Read(e / "out/report.json"), "old");
  // With an out/ present every temporary goes, complete or not.
  TempDir f;
  Write(f / "out/report.json", "current");
  Write(f / "out.tmp.BBBBBB/report.json", "stale");
  RecoverAndClean(f / "out");
  EXPECT_EQ(Read(f / "out/report.json"), "current");
  EXPECT_FALSE(fs::exists(f / "out.tmp.BBBBBB"));
}

TEST(TrialDir, LockFileIsNeverALink) {
  TempDir d;
  Write(d / "victim", "precious");
  fs::create_symlink(d / "victim", d / ".rk-run.lock");
  std::string holder;
  EXPECT_THROW(TrialLock::Acquire(d / ".rk-run.lock", 0.0, &holder), Error);
  EXPECT_EQ(Read(d / "victim"), "precious");
}

TEST(TrialDir, KeepsWhatRunDidNotMake) {
  TempDir d;
  Write(d / "out/report.json", "old");
  Write(d / "out/a.csv", "old product");
  Write(d / "out/NOTES.txt", "mine");
  Write(d / "out/analysis/x.csv", "mine too");
  const std::string work = MakeWorkDir(d / "out");
  Write(work + "/a.csv", "new product");
  const auto kept = KeepUserEntries(d / "out", work, {"a.csv", "report.json"}, true);
  EXPECT_EQ(kept.size(), 2u);
  EXPECT_EQ(Read(fs::path(work) / "NOTES.txt"), "mine");
  EXPECT_EQ(Read(fs::path(work) / "analysis/x.csv"), "mine too");
  EXPECT_EQ(Read(fs::path(work) / "a.csv"), "new product");
  // A user's file where a product now goes: refused while the record is known, replaced when it is not.
  fs::remove_all(work);
  const std::string w2 = MakeWorkDir(d / "out");
  Write(d / "out/b.csv", "mine");
  Write(w2 + "/b.csv", "new product");
  try {
    KeepUserEntries(d / "out", w2, {"a.csv", "report.json"}, true);
    ADD_FAILURE() << "a user's file under a new product's path was not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("out/b.csv"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(KeepUserEntries(d / "out", w2, {"a.csv", "report.json"}, false));
  EXPECT_EQ(Read(fs::path(w2) / "b.csv"), "new product");
  fs::remove_all(w2);
}

TEST(TrialDir, WorkFolderHasTheUmasksMode) {
  TempDir d;
  const mode_t old = ::umask(022);
  const std::string work = MakeWorkDir(d / "out");
  ::umask(old);
  EXPECT_EQ(fs::status(work).permissions() & fs::perms::all,
            fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                fs::perms::others_exec);
}

}  // namespace
}  // namespace rk::run

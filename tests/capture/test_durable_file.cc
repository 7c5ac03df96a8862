// Crash-safe files (capture/durable_file.h): all-or-nothing appends when the file-size limit is hit, no
// file replaced, the Syncer.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "capture/durable_file.h"
#include "io/error.h"
#include "io/file_util.h"
#include "rk_test/temp_dir.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

// In a child process (the limit is per process): RLIMIT_FSIZE = 1000 bytes; a 600-byte record fits,
// the next one is written only in part by the kernel and must be cut back to the record boundary.
TEST(DurableFile, ShortWriteIsCutBackToTheRecordBoundary) {
  const rk::test::TempDir dir_tmp("capture_fsize");
  const std::string dir = dir_tmp.path();
  const std::string path = (fs::path(dir) / "log.csv").string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    rlimit lim{1000, 1000};
    ::setrlimit(RLIMIT_FSIZE, &lim);
    std::string why;
    auto f = DurableFile::Create(path, false, &why);
    if (!f) ::_exit(10);
    const std::string rec(600, 'a');
    if (!f->Append(rec, &why)) ::_exit(11);
    if (f->Append(rec, &why)) ::_exit(12);           // must fail: 1200 > 1000
    if (why.find("large") == std::string::npos) ::_exit(13);  // "File too large" (EFBIG)
    if (f->size() != 600) ::_exit(14);
    const std::string small(100, 'b');
    if (!f->Append(small, &why)) ::_exit(15);        // still room for a small record
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(fs::file_size(path), 700u);  // 600 + 100, the failed record left nothing
  const std::string data = io::ReadFile(path);
  EXPECT_EQ(data, std::string(600, 'a') + std::string(100, 'b'));
  fs::remove_all(dir);
}

TEST(DurableFile, NeverReplacesAFile) {
  const rk::test::TempDir dir_tmp("capture_excl");
  const std::string dir = dir_tmp.path();
  const std::string path = (fs::path(dir) / "x").string();
  std::ofstream(path) << "precious";
  std::string why;
  EXPECT_EQ(DurableFile::Create(path, false, &why), nullptr);
  EXPECT_NE(why.find("exists"), std::string::npos);
  EXPECT_EQ(io::ReadFile(path), "precious");
  fs::remove_all(dir);
}

TEST(Syncer, FreeSpaceProbeAndRetiredFiles) {
  const rk::test::TempDir dir_tmp("capture_sync");
  const std::string dir = dir_tmp.path();
  Syncer syncer(dir, 1.0);
  syncer.set_free_space_probe([] { return std::int64_t{12345}; });
  std::string why;
  auto f = DurableFile::Create((fs::path(dir) / "v").string(), true, &why);
  ASSERT_TRUE(f);
  syncer.Add(f);
  ASSERT_TRUE(f->Append("FRAME\n", &why));
  f->Retire();
  syncer.SyncNow();
  EXPECT_EQ(syncer.free_bytes(), 12345);
  EXPECT_EQ(f.use_count(), 1);  // the Syncer synced it once more and let it go
  // Between two readings the estimate follows what the writers noted; the next reading replaces it.
  syncer.NoteWritten(2345);
  EXPECT_EQ(syncer.free_bytes(), 10000);
  syncer.NoteWritten(20000);
  EXPECT_EQ(syncer.free_bytes(), 0);
  syncer.SyncNow();
  EXPECT_EQ(syncer.free_bytes(), 12345);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rk::capture

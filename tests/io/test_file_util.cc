// Output paths per SPEC.md §2 ("Writes are atomic"): lib/io/file_util.cc's ResolveOutput and
// WriteFileAtomic on regular files, links, FIFOs, devices and this process's descriptors.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "io/error.h"
#include "io/file_util.h"
#include "test_expect_error.h"
#include "rk_test/temp_dir.h"

namespace rk::io {
namespace {
namespace fs = std::filesystem;

class OutputPaths : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tmp_.path();
    fs::create_directories(dir_ / "elsewhere");
  }
  const rk::test::TempDir tmp_{"outputs"};
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  static std::string Slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  static ino_t Inode(const std::string& path) {
    struct stat st {};
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return st.st_ino;
  }
  std::size_t HiddenTemporaries() const {
    std::size_t n = 0;
    for (const auto& d : {dir_, dir_ / "elsewhere"}) {
      for (const auto& e : fs::directory_iterator(d)) n += e.path().filename().string().rfind(".", 0) == 0;
    }
    return n;
  }
  fs::path dir_;
};

TEST_F(OutputPaths, NewAndRegularFilesAreReplacedAtomically) {
  EXPECT_EQ(ResolveOutput(P("new.csv")).kind, OutputTarget::Kind::kReplace);
  WriteFileAtomic(P("new.csv"), "a\n1\n");
  const ino_t first = Inode(P("new.csv"));
  WriteFileAtomic(P("new.csv"), "a\n2\n");
  EXPECT_EQ(Slurp(P("new.csv")), "a\n2\n");
  EXPECT_NE(Inode(P("new.csv")), first);  // renamed over, not rewritten in place
  EXPECT_EQ(HiddenTemporaries(), 0u);
}

TEST_F(OutputPaths, LinkStaysLinkAndItsTargetIsReplaced) {
  std::ofstream(P("elsewhere/target.csv")) << "old";
  fs::create_symlink("elsewhere/target.csv", P("link.csv"));
  fs::create_symlink("link.csv", P("link2.csv"));  // a chain
  const OutputTarget t = ResolveOutput(P("link2.csv"));
  EXPECT_EQ(t.kind, OutputTarget::Kind::kReplace);
  EXPECT_TRUE(fs::equivalent(t.path, P("elsewhere/target.csv")));
  WriteFileAtomic(P("link2.csv"), "new\n");
  EXPECT_TRUE(fs::is_symlink(P("link.csv")));
  EXPECT_TRUE(fs::is_symlink(P("link2.csv")));
  EXPECT_EQ(Slurp(P("elsewhere/target.csv")), "new\n");
  EXPECT_EQ(HiddenTemporaries(), 0u);
  // A dangling link: its target is created, the link kept.
  fs::create_symlink("elsewhere/later.csv", P("dangling.csv"));
  WriteFileAtomic(P("dangling.csv"), "x\n");
  EXPECT_TRUE(fs::is_symlink(P("dangling.csv")));
  EXPECT_EQ(Slurp(P("elsewhere/later.csv")), "x\n");
}

TEST_F(OutputPaths, FifoWithReaderIsWrittenThroughAndKept) {
  ASSERT_EQ(::mkfifo(P("fifo").c_str(), 0644), 0);
  EXPECT_EQ(ResolveOutput(P("fifo")).kind, OutputTarget::Kind::kWriteThrough);
  std::string got;
  std::thread reader([&] { got = Slurp(P("fifo")); });
  WriteFileAtomic(P("fifo"), "through\n");
  reader.join();
  EXPECT_EQ(got, "through\n");
  EXPECT_TRUE(fs::is_fifo(P("fifo")));
  // Through a link to it as well.
  fs::create_symlink("fifo", P("fifolink"));
  std::thread reader2([&] { got = Slurp(P("fifolink")); });
  WriteFileAtomic(P("fifolink"), "again\n");
  reader2.join();
  EXPECT_EQ(got, "again\n");
  EXPECT_TRUE(fs::is_symlink(P("fifolink")));
  EXPECT_TRUE(fs::is_fifo(P("fifo")));
}

TEST_F(OutputPaths, DeviceIsWrittenThroughNeverReplaced) {
  // A null device of our own (root only; elsewhere the FIFO test covers write-through).
  if (::mknod(P("null").c_str(), S_IFCHR | 0666, ::makedev(1, 3)) != 0) GTEST_SKIP() << "mknod not permitted";
  EXPECT_EQ(ResolveOutput(P("null")).kind, OutputTarget::Kind::kWriteThrough);
  WriteFileAtomic(P("null"), "gone\n");
  EXPECT_TRUE(fs::is_character_file(P("null")));
  EXPECT_EQ(HiddenTemporaries(), 0u);
}

// Runs `write` in a child whose stdout is `log` opened for appending (a shell's ">>"); the child's exit code
// (0: `write` returned, 3: it threw, 2: the file could not be opened).
template <typename F>
int InChildAppendingTo(const std::string& log, F write) {
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_APPEND);
    if (fd < 0 || ::dup2(fd, STDOUT_FILENO) < 0) ::_exit(2);
    try {
      write();
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(0);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

TEST_F(OutputPaths, OwnDescriptorsAreWrittenToTheDescriptor) {
  for (const char* name : {"-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"}) {
    const OutputTarget t = ResolveOutput(name);
    EXPECT_EQ(t.kind, OutputTarget::Kind::kDescriptor) << name;
    EXPECT_EQ(t.fd, 1) << name;
  }
  EXPECT_EQ(ResolveOutput("/dev/stderr").fd, 2);
  EXPECT_EQ(ResolveOutput("/proc/" + std::to_string(::getpid()) + "/fd/1").fd, 1);
  // A child whose stdout is a regular file opened for appending: /dev/stdout appends, keeping what the
  // shell's ">>" file had, and the file is not replaced.
  const std::string log = P("append.log");
  std::ofstream(log) << "first\n";
  const ino_t ino = Inode(log);
  EXPECT_EQ(InChildAppendingTo(log, [] { WriteFileAtomic("/dev/stdout", "second\n"); }), 0);
  EXPECT_EQ(Slurp(log), "first\nsecond\n");
  EXPECT_EQ(Inode(log), ino);
}

// io::OutputFile (an output written in pieces): nothing at the path before Commit, the whole data after it,
// nothing anywhere when it is dropped uncommitted; through a FIFO and a descriptor, all at Commit.
TEST_F(OutputPaths, OutputFileInPiecesIsAtomic) {
  std::ofstream(P("old.csv")) << "old\n";
  {
    OutputFile out(P("old.csv"));
    out.Write("a\n");
    out.Write("1\n");
    EXPECT_EQ(Slurp(P("old.csv")), "old\n");  // not yet
    EXPECT_EQ(HiddenTemporaries(), 1u);
    out.Commit();
  }
  EXPECT_EQ(Slurp(P("old.csv")), "a\n1\n");
  EXPECT_EQ(HiddenTemporaries(), 0u);
  {
    OutputFile out(P("failed.csv"));  // a run that fails before Commit
    out.Write("partial\n");
  }
  EXPECT_FALSE(fs::exists(P("failed.csv")));
  EXPECT_EQ(HiddenTemporaries(), 0u);
  {
    OutputFile out(P("old.csv"));
    out.Write("partial\n");
  }
  EXPECT_EQ(Slurp(P("old.csv")), "a\n1\n");  // the old file stays as it was
  EXPECT_EQ(HiddenTemporaries(), 0u);

  ASSERT_EQ(::mkfifo(P("fifo").c_str(), 0644), 0);
  std::string got;
  std::thread reader([&] { got = Slurp(P("fifo")); });
  {
    OutputFile out(P("fifo"));
    out.Write("through ");
    out.Write("the fifo\n");
    out.Commit();
  }
  reader.join();
  EXPECT_EQ(got, "through the fifo\n");
  EXPECT_TRUE(fs::is_fifo(P("fifo")));

  // A descriptor: a child whose stdout is a file gets the data at Commit, nothing without it.
  for (const bool commit : {true, false}) {
    const std::string log = P(commit ? "committed.log" : "dropped.log");
    std::ofstream(log) << "first\n";
    EXPECT_EQ(InChildAppendingTo(log,
                                 [commit] {
                                   OutputFile out("-");
                                   out.Write("second\n");
                                   if (commit) out.Commit();
                                 }),
              0);
    EXPECT_EQ(Slurp(log), commit ? "first\nsecond\n" : "first\n");
  }
}

TEST_F(OutputPaths, FoldersAreRefused) {
  try {
    WriteFileAtomic(dir_.string(), "x");
    FAIL() << "a folder was accepted as an output file";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kIo);
    EXPECT_NE(std::string(e.what()).find("folder"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(dir_));
}

TEST_F(OutputPaths, OutputFolderBehindALinkResolvesToItsTarget) {
  fs::create_directories(P("elsewhere/out"));
  fs::create_symlink("elsewhere/out", P("out"));
  EXPECT_TRUE(fs::equivalent(ResolveOutputFolder(P("out")), P("elsewhere/out")));
  EXPECT_EQ(ResolveOutputFolder(P("plain")), P("plain"));
  EXPECT_THROW(ResolveOutputFolder("/dev/stdout"), Error);
}

}  // namespace
}  // namespace rk::io

namespace rk::io {
namespace {

TEST(FileUtil, AtomicWriteLeavesNoTemporaryAndRefusesToOverwriteInputs) {
  namespace fs = std::filesystem;
  const rk::test::TempDir tmp("atomic");
  fs::path dir = tmp.path();
  std::string out = (dir / "out.csv").string();
  WriteFileAtomic(out, "a\n1\n");
  WriteFileAtomic(out, "a\n2\n");
  EXPECT_EQ(ReadFile(out), "a\n2\n");
  int files = 0;
  for (auto& e : fs::directory_iterator(dir)) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);
  ExpectError([&] { CheckOutputNotInput(out, {out}); }, ExitCode::kUsage, "refusing");
  EXPECT_NO_THROW(CheckOutputNotInput((dir / "other.csv").string(), {out}));
  ExpectError([&] { WriteFileAtomic((dir / "no/such/dir/x.csv").string(), "x"); }, ExitCode::kIo, "x.csv");
  ExpectError([&] { ReadFile((dir / "missing.csv").string()); }, ExitCode::kIo, "missing.csv");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rk::io

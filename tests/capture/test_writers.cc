// Crash-safe writers: video segments read back bit-exact by the suite's reader (the one rk-extract
// uses), all-or-nothing appends when the file-size limit is hit, the Syncer.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <random>

#include "capture/append_log.h"
#include "capture/durable_file.h"
#include "capture/segment_writer.h"
#include "io/error.h"
#include "io/file_util.h"
#include "video/frame_source.h"
#include "test_temp_dir.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

cv::Mat RandomFrame(int w, int h, int depth, std::uint64_t seed) {
  cv::Mat m(h, w, depth == 16 ? CV_16UC1 : CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0, depth == 16 ? 65536 : 256);
  return m;
}

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Writes 2 segments (3 + 2 frames) and reads them back through video::FrameSource.
void RoundTrip(const std::string& format, int depth) {
  const std::string dir = TempDir(format + std::to_string(depth));
  fs::create_directories(fs::path(dir) / "cam");
  Syncer syncer(dir, 1.0);
  const FrameFormat f{64, 48, depth, 20.0};
  auto w = MakeSegmentWriter(format, dir, "cam", f, &syncer);
  std::vector<cv::Mat> frames;
  std::vector<std::string> segments;
  std::string why;
  for (int k = 0; k < 5; ++k) {
    if (k == 0 || k == 3) {
      ASSERT_TRUE(w->Begin(k == 0 ? 0 : 1, &why)) << why;
      segments.push_back((fs::path(dir) / w->SegmentPath(k == 0 ? 0 : 1)).string());
    }
    frames.push_back(RandomFrame(64, 48, depth, 100 + static_cast<std::uint64_t>(k)));
    ASSERT_TRUE(w->Write(frames.back(), &why)) << why;
  }
  // A frame of the wrong size is refused, nothing written.
  EXPECT_FALSE(w->Write(RandomFrame(32, 48, depth, 1), &why));
  EXPECT_EQ(w->frames_in_segment(), 2);
  w->End();
  syncer.SyncNow();
  video::FrameSource src(segments);
  cv::Mat got;
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(src.Read(&got)) << "frame " << k;
    EXPECT_TRUE(Same(got, frames[static_cast<std::size_t>(k)])) << format << " frame " << k;
  }
  EXPECT_FALSE(src.Read(&got));
  fs::remove_all(dir);
}

TEST(SegmentWriter, Y4mReadsBackBitExact8And16Bit) {
  RoundTrip("y4m", 8);
  RoundTrip("y4m", 16);  // YUV4MPEG2 mono16 = gray16le for ffmpeg
}

TEST(SegmentWriter, PgmReadsBackBitExact8And16Bit) {
  RoundTrip("pgm", 8);
  RoundTrip("pgm", 16);
}

TEST(SegmentWriter, UndoLastRemovesTheFrame) {
  for (const std::string format : {"y4m", "pgm"}) {
    const std::string dir = TempDir("undo" + format);
    fs::create_directories(fs::path(dir) / "cam");
    const FrameFormat f{32, 16, 8, 10.0};
    auto w = MakeSegmentWriter(format, dir, "cam", f, nullptr);
    std::string why;
    ASSERT_TRUE(w->Begin(0, &why));
    const cv::Mat a = RandomFrame(32, 16, 8, 1), b = RandomFrame(32, 16, 8, 2);
    ASSERT_TRUE(w->Write(a, &why));
    ASSERT_TRUE(w->Write(b, &why));
    ASSERT_TRUE(w->UndoLast(&why)) << why;
    EXPECT_EQ(w->frames_in_segment(), 1);
    w->End();
    video::FrameSource src({(fs::path(dir) / w->SegmentPath(0)).string()});
    cv::Mat got;
    ASSERT_TRUE(src.Read(&got));
    EXPECT_TRUE(Same(got, a));
    EXPECT_FALSE(src.Read(&got));
    fs::remove_all(dir);
  }
}

// In a child process (the limit is per process): RLIMIT_FSIZE = 1000 bytes; a 600-byte record fits,
// the next one is written only in part by the kernel and must be cut back to the record boundary.
TEST(DurableFile, ShortWriteIsCutBackToTheRecordBoundary) {
  const std::string dir = TempDir("fsize");
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
  const std::string dir = TempDir("excl");
  const std::string path = (fs::path(dir) / "x").string();
  std::ofstream(path) << "precious";
  std::string why;
  EXPECT_EQ(DurableFile::Create(path, false, &why), nullptr);
  EXPECT_NE(why.find("exists"), std::string::npos);
  EXPECT_EQ(io::ReadFile(path), "precious");
  fs::remove_all(dir);
}

TEST(AppendLog, LinesAndHeader) {
  const std::string dir = TempDir("log");
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

TEST(Syncer, FreeSpaceProbeAndRetiredFiles) {
  const std::string dir = TempDir("sync");
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

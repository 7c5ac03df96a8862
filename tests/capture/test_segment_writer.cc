// Video segments (capture/segment_writer.h): the y4m header, and segments read back bit-exact by the suite's
// reader (the one rk-extract uses).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <random>
#include <string>

#include "capture/durable_file.h"
#include "capture/segment_writer.h"
#include "io/file_util.h"
#include "video/frame_source.h"
#include "rk_test/temp_dir.h"

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
  const rk::test::TempDir dir_tmp(std::string("capture_") + format + std::to_string(depth));
  const std::string dir = dir_tmp.path();
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
    const rk::test::TempDir dir_tmp("capture_undo" + format);
  const std::string dir = dir_tmp.path();
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

TEST(Video, Y4mHeaderRoundTrip) {
  FrameFormat f{2448, 2048, 8, 20.0};
  EXPECT_EQ(Y4mHeader(f), "YUV4MPEG2 W2448 H2048 F20:1 Ip A1:1 Cmono\n");
  f.fps = 29.97;
  f.bit_depth = 16;
  EXPECT_EQ(Y4mHeader(f), "YUV4MPEG2 W2448 H2048 F2997:100 Ip A1:1 Cmono16\n");
  FrameFormat g;
  const std::string h = Y4mHeader(f);
  ASSERT_TRUE(ParseY4mHeader(h.substr(0, h.size() - 1), &g));
  EXPECT_EQ(g.width, 2448);
  EXPECT_EQ(g.height, 2048);
  EXPECT_EQ(g.bit_depth, 16);
  EXPECT_NEAR(g.fps, 29.97, 1e-12);
  EXPECT_FALSE(ParseY4mHeader("YUV4MPEG2 W10 H10 F20:1 C420jpeg", &g));  // colour: not ours
  EXPECT_FALSE(ParseY4mHeader("PNG", &g));
}

}  // namespace
}  // namespace rk::capture

// rk-capture's y4m segments read in-process (video/y4m.h): the frames written by FrameSink's sibling, the
// segment writer's header; a torn last frame is said and not read; a frame without its FRAME line is an
// error with its byte offset.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/error.h"
#include "rk_test/temp_dir.h"
#include "test_pattern.h"
#include "video/frame_source.h"
#include "video/y4m.h"

namespace rk::video {
namespace {
namespace fs = std::filesystem;

std::string Y4mBytes(const FrameFormat& f, int frames) {
  std::string out = Y4mHeader(f);
  for (int k = 0; k < frames; ++k) {
    const cv::Mat m = Pattern(f.width, f.height, f.bit_depth, k);
    out += "FRAME\n";
    out.append(reinterpret_cast<const char*>(m.data), m.total() * m.elemSize());
  }
  return out;
}

TEST(Y4mReader, ReadsEveryFrameOfBothDepthsThroughFrameSource) {
  const rk::test::TempDir tmp("y4m_read");
  for (int depth : {8, 16}) {
    FrameFormat f;
    f.width = 36;
    f.height = 10;
    f.bit_depth = depth;
    f.fps = 29.97;
    const fs::path p = tmp / ("d" + std::to_string(depth) + ".y4m");
    std::ofstream(p, std::ios::binary) << Y4mBytes(f, 4);
    EXPECT_TRUE(IsMonoY4m(p.string()));
    FrameSource src({p.string(), p.string()});  // two segments: frames count on
    cv::Mat m;
    for (int k = 0; k < 8; ++k) {
      ASSERT_TRUE(src.Read(&m));
      EXPECT_EQ(cv::norm(m, Pattern(f.width, f.height, depth, k % 4), cv::NORM_INF), 0.0) << depth << " frame " << k;
    }
    EXPECT_FALSE(src.Read(&m));
    EXPECT_NEAR(Y4mReader(p.string()).format().fps, 29.97, 1e-12);
  }
}

TEST(Y4mReader, TornLastFrameIsSaidAndMissingFrameLineIsAnError) {
  const rk::test::TempDir tmp("y4m_torn");
  FrameFormat f;
  f.width = 8;
  f.height = 4;
  std::string bytes = Y4mBytes(f, 3);
  std::ofstream(tmp / "torn.y4m", std::ios::binary) << bytes.substr(0, bytes.size() - 7);
  Y4mReader torn((tmp / "torn.y4m"));
  cv::Mat m;
  EXPECT_TRUE(torn.Read(&m));
  EXPECT_TRUE(torn.Read(&m));
  EXPECT_FALSE(torn.Read(&m));
  EXPECT_EQ(torn.frames_read(), 2);
  // The second frame's FRAME line damaged: the byte offset of that frame.
  const std::size_t second = Y4mHeader(f).size() + 6 + 32;
  bytes[second] = 'X';
  std::ofstream(tmp / "bad.y4m", std::ios::binary) << bytes;
  Y4mReader bad((tmp / "bad.y4m"));
  EXPECT_TRUE(bad.Read(&m));
  try {
    bad.Read(&m);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.y4m: byte " + std::to_string(second) + ": frame 1 has no FRAME line"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rk::video

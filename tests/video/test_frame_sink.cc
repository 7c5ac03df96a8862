// The frame writer (video/frame_sink.h): lossless, every bit of every frame read back, 8 and 16 bit, FFV1 and PNG.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <tuple>

#include "test_pattern.h"
#include "video/frame_sink.h"
#include "video/frame_source.h"
#include "rk_test/temp_dir.h"

namespace rk::video {
namespace {
namespace fs = std::filesystem;

class VideoRoundTrip : public ::testing::TestWithParam<std::tuple<int, std::string>> {};

// Lossless: every bit of every frame comes back, 8 and 16 bit, FFV1 and PNG.
TEST_P(VideoRoundTrip, IsBitExact) {
  auto [depth, kind] = GetParam();
  const rk::test::TempDir tmp("video_" + std::to_string(depth) + kind);
  fs::path dir = tmp.path();
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string path = kind == "mkv" ? (dir / "v.mkv").string() : (dir / "%06d.png").string();
  constexpr int kW = 64, kH = 48, kFrames = 7;
  {
    FrameSink sink(path, kW, kH, depth, 20.0);
    for (int k = 0; k < kFrames; ++k) sink.Write(Pattern(kW, kH, depth, k));
    sink.Close();
  }
  FrameSource src({path});
  EXPECT_EQ(src.info().bit_depth, depth);
  cv::Mat f;
  int k = 0;
  while (src.Read(&f)) {
    ASSERT_LT(k, kFrames);
    EXPECT_EQ(cv::norm(f, Pattern(kW, kH, depth, k), cv::NORM_INF), 0.0) << "frame " << k;
    ++k;
  }
  EXPECT_EQ(k, kFrames);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(All, VideoRoundTrip,
                         ::testing::Combine(::testing::Values(8, 16), ::testing::Values("mkv", "png")));

}  // namespace
}  // namespace rk::video

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "io/error.h"
#include "video/frame_sink.h"
#include "video/frame_source.h"

namespace rk::video {
namespace {
namespace fs = std::filesystem;

cv::Mat Pattern(int w, int h, int depth, int k) {
  cv::Mat m(h, w, depth == 16 ? CV_16UC1 : CV_8UC1);
  std::mt19937 rng(static_cast<unsigned>(k));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      unsigned v = rng();
      if (depth == 16) {
        m.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(v);
      } else {
        m.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(v);
      }
    }
  }
  return m;
}

class VideoRoundTrip : public ::testing::TestWithParam<std::tuple<int, std::string>> {};

// Lossless: every bit of every frame comes back, 8 and 16 bit, FFV1 and PNG.
TEST_P(VideoRoundTrip, IsBitExact) {
  auto [depth, kind] = GetParam();
  fs::path dir = fs::temp_directory_path() / ("rk_video_" + std::to_string(depth) + kind);
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

TEST(FrameSource, SegmentsCountOnAndTruncationIsAnError) {
  fs::path dir = fs::temp_directory_path() / "rk_video_segments";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string a = (dir / "a.mkv").string(), b = (dir / "b.mkv").string();
  for (const auto& p : {a, b}) {
    FrameSink sink(p, 320, 240, 8, 20.0);
    for (int k = 0; k < 10; ++k) sink.Write(Pattern(320, 240, 8, k));
    sink.Close();
  }
  {
    FrameSource src({a, b});
    cv::Mat f;
    while (src.Read(&f)) {
    }
    EXPECT_EQ(src.frames_read(), 20);
  }
  // Cut the second file in half: reading must fail, not end quietly.
  auto size = fs::file_size(b);
  fs::resize_file(b, size / 2);
  FrameSource src({a, b});
  cv::Mat f;
  try {
    while (src.Read(&f)) {
    }
    FAIL() << "truncated video read without error, frames " << src.frames_read();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("b.mkv"), std::string::npos) << e.what();
  }
  EXPECT_THROW(FrameSource({(dir / "missing.mkv").string()}), Error);
  fs::remove_all(dir);
}

TEST(FrameSource, NotAVideoIsInvalidData) {
  fs::path p = fs::temp_directory_path() / "rk_not_video.mkv";
  std::ofstream(p) << "this is text";
  FrameSource src({p.string()});
  cv::Mat f;
  try {
    src.Read(&f);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
  }
  fs::remove(p);
}

}  // namespace
}  // namespace rk::video

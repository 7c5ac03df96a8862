// The frame reader (video/frame_source.h): segments read on as one video, a truncated or non-video file an error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/error.h"
#include "test_pattern.h"
#include "video/frame_sink.h"
#include "video/frame_source.h"
#include "rk_test/temp_dir.h"

namespace rk::video {
namespace {
namespace fs = std::filesystem;

TEST(FrameSource, SegmentsCountOnAndTruncationIsAnError) {
  const rk::test::TempDir tmp("video_segments");
  fs::path dir = tmp.path();
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
  const rk::test::TempDir tmp("not_video");
  fs::path p = tmp / "not_video.mkv";
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

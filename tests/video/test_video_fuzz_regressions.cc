// Inputs found by the fuzz harness of the image-sequence reader (tests/fuzz/fuzz_pgm.cc); each is also
// in the committed corpus tests/fuzz/corpus/fuzz_pgm/crash-*.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/error.h"
#include "video/frame_source.h"
#include "rk_test/temp_dir.h"

namespace rk::video {
namespace fuzz_regression {

// A PNM header promising 68 888 888 rows made cv::imread throw cv::Exception (its own
// CV_IO_MAX_IMAGE_HEIGHT check), which ProbeVideo and FrameSource let through: rk-extract ended in an
// internal error instead of "file: cannot decode image" with exit code 3.
TEST(VideoFuzzRegression, ImageBeyondOpenCvsSizeLimitIsADataError) {
  const rk::test::TempDir tmp("video_fuzz");
  const std::filesystem::path dir = tmp.path();
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "000000.pgm", std::ios::binary) << "P1\n3 68888888P1\n8888888888888888888888888888888838";
  const std::string pattern = (dir / "%06d.pgm").string();
  for (int way = 0; way < 2; ++way) {
    try {
      if (way == 0) {
        ProbeVideo(pattern);
      } else {
        FrameSource source({pattern});
        cv::Mat frame;
        source.Read(&frame);
      }
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kInvalidData);
      EXPECT_NE(std::string(e.what()).find("000000.pgm: cannot decode image"), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace fuzz_regression
}  // namespace rk::video

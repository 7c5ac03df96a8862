// The image-sequence reader of lib/video (FrameSource on "dir/%06d.pgm"; the decoding itself is
// OpenCV's imread): the input is frame 000000.pgm of a one-frame sequence, read through ProbeVideo and
// FrameSource::Read as rk-extract reads a recording. OpenCV's own image-size limit is lowered to 2^22
// pixels so that a header promising a gigapixel frame is refused instead of exhausting the fuzzer's
// memory limit (the tools keep OpenCV's default).
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "fuzz_util.h"
#include "video/frame_source.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("OPENCV_IO_MAX_IMAGE_PIXELS", "4194304", 1);
  std::filesystem::create_directories(rk::fuzz::ScratchDir() + "/seq");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rk::fuzz::WriteScratch("seq/000000.pgm", rk::fuzz::AsText(data, size));
  const std::string pattern = rk::fuzz::ScratchDir() + "/seq/%06d.pgm";
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::video::VideoInfo info = rk::video::ProbeVideo(pattern);
    rk::video::FrameSource source({pattern});
    cv::Mat frame;
    while (source.Read(&frame)) {
      if (frame.cols != info.width || frame.rows != info.height) std::abort();
      if (frame.depth() != (info.bit_depth == 16 ? CV_16U : CV_8U) || frame.channels() != 1) std::abort();
    }
    if (source.frames_read() != 1) std::abort();
  });
  return 0;
}

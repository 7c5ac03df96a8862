// The in-process y4m reader of lib/video (video::Y4mReader, rk-capture's segments as --video reads them):
// the input is the .y4m file. Promises checked: every frame has the header's size and depth.
#include <cstdint>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <string>

#include "fuzz_util.h"
#include "video/y4m.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rk::fuzz::WriteScratch("s.y4m", rk::fuzz::AsText(data, size));
  rk::fuzz::ExpectOnlyInputErrors([&] {
    rk::video::Y4mReader reader(path);
    const rk::video::FrameFormat f = reader.format();
    if (static_cast<std::uint64_t>(f.width) * static_cast<std::uint64_t>(f.height) > (1u << 22)) return;
    cv::Mat m;
    while (reader.Read(&m)) {
      if (m.cols != f.width || m.rows != f.height) std::abort();
      if (m.depth() != (f.bit_depth == 16 ? CV_16U : CV_8U)) std::abort();
    }
  });
  return 0;
}

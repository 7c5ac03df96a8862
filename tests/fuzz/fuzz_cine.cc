// The Phantom CINE reader of lib/video (video::ParseCine: header, bitmap header, setup, tagged time and
// exposure blocks, image offsets; then every frame unpacked and demosaiced by CameraFileReader, as
// --video reads it): the input is the .cine file. Promises checked: every frame has the header's size and
// a 16-bit or 8-bit single channel, and there is one time per frame.
#include <cstdint>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <string>

#include "fuzz_util.h"
#include "video/camera_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The parser on the buffer itself (what a mapped file gives).
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::video::CameraFile cf = rk::video::ParseCine(rk::video::ByteView(data, size, "fuzz.cine"));
    if (cf.times.frames.size() != cf.frame_offsets.size()) std::abort();
    if (cf.width <= 0 || cf.height <= 0) std::abort();
    // Keep the fuzzer's memory bounded: decode only frames of at most 2^22 pixels.
    if (static_cast<std::uint64_t>(cf.width) * static_cast<std::uint64_t>(cf.height) > (1u << 22)) return;
    const std::string path = rk::fuzz::WriteScratch("f.cine", rk::fuzz::AsText(data, size));
    rk::video::CameraFileReader reader(path);
    cv::Mat m;
    for (std::int64_t i = 0; i < reader.frames() && i < 4; ++i) {
      reader.Read(i, &m);
      if (m.cols != cf.width || m.rows != cf.height || m.channels() != 1) std::abort();
    }
  });
  return 0;
}

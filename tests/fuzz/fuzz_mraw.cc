// The Photron MRAW reader of lib/video (video::ParseCihx with tinyxml2, video::ParseCih, the data size
// check, then every frame by CameraFileReader): byte 0 chooses the header form (even: .cihx, odd: .cih),
// then the header, a line "=====", then the .mraw data. Promises checked: one time per frame, each frame of
// the header's size.
#include <cstdint>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>

#include "fuzz_util.h"
#include "video/camera_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const bool xml = (data[0] & 1u) == 0;
  const std::string_view rest = rk::fuzz::AsText(data + 1, size - 1);
  const std::size_t sep = rest.find("\n=====\n");
  const std::string_view header = rest.substr(0, sep);
  const std::string_view mraw = sep == std::string_view::npos ? std::string_view() : rest.substr(sep + 7);
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::video::ByteView hv(reinterpret_cast<const std::uint8_t*>(header.data()), header.size(), "fuzz.cih");
    const rk::video::CameraFile cf = xml ? rk::video::ParseCihx(hv, "fuzz.mraw", mraw.size())
                                         : rk::video::ParseCih(hv, "fuzz.mraw", mraw.size());
    if (cf.times.frames.size() != cf.frame_offsets.size()) std::abort();
    if (static_cast<std::uint64_t>(cf.width) * static_cast<std::uint64_t>(cf.height) > (1u << 22)) return;
    rk::fuzz::WriteScratch(xml ? "m.cihx" : "m.cih", header);
    const std::string path = rk::fuzz::WriteScratch("m.mraw", mraw);
    // The other header form must not be picked up: remove it.
    std::remove((rk::fuzz::ScratchDir() + (xml ? "/m.cih" : "/m.cihx")).c_str());
    rk::video::CameraFileReader reader(path);
    cv::Mat m;
    for (std::int64_t i = 0; i < reader.frames() && i < 4; ++i) {
      reader.Read(i, &m);
      if (m.cols != cf.width || m.rows != cf.height) std::abort();
    }
  });
  return 0;
}

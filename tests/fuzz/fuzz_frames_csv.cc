// frames.csv against a video (SPEC §2.1 "video frame times"): FrameClock::FromCsv, then the time of
// every frame of a video with `frames` frames, as rk-extract's frame loop asks for them. The first
// input byte is the video's frame count (0 ... 255), the rest the CSV.
#include <cstdint>
#include <string>

#include "formats/frame_times.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::int64_t frames = data[0];
  const std::string path = rk::fuzz::WriteScratch("frames.csv", rk::fuzz::AsText(data + 1, size - 1));
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::formats::FrameClock clock = rk::formats::FrameClock::FromCsv(path);
    if (!clock.from_file() || clock.size() < 1) std::abort();
    double previous = -1e308;
    for (std::int64_t f = 0; f < frames; ++f) {
      const double t = clock.TimeOf(f);  // DataError past the last listed frame
      if (!(t >= previous)) std::abort();  // FromCsv promised finite, non-decreasing times
      previous = t;
    }
  });
  return 0;
}

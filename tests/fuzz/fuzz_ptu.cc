// FLIR PTU replies (lib/capture/ptu.cc): the serial byte stream cut into lines by LineSplitter in
// chunks, as PtuDriver reads it, and every line through ParsePtuReply; numeric replies then go through
// the position → angle map as the driver uses them (only whole positions below 1e12).
// Input: byte 0 = read chunk size, then the bytes on the line.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "capture/ptu.h"
#include "fuzz_util.h"
#include "serial_lines.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::size_t chunk = 1 + data[0] % 64;
  const std::string_view bytes = rk::fuzz::AsText(data + 1, size - 1);
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::capture::PtuAngleMap map;
    for (const std::string& line : rk::fuzz::SerialLines(bytes, chunk)) {
      const rk::capture::PtuReply r = rk::capture::ParsePtuReply(line);
      if (r.kind == rk::capture::PtuReplyKind::kInvalid) (void)rk::capture::EscapeForLog(line);
      if (r.value && !std::isfinite(*r.value)) std::abort();
      if (r.kind == rk::capture::PtuReplyKind::kOk && r.value && std::abs(*r.value) < 1e12 &&
          *r.value == std::floor(*r.value)) {
        const auto pos = static_cast<std::int64_t>(*r.value);
        (void)map.AzimuthDeg(pos, 92.5714);
        (void)map.ElevationDeg(pos, 46.2857);
      }
    }
  });
  return 0;
}

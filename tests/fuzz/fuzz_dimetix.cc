// Dimetix rangefinder replies (lib/capture/dimetix.cc): the serial byte stream is cut into lines by
// LineSplitter in chunks, as DimetixDriver::Pump reads it, and every line goes to ParseDimetixReply.
// Input: byte 0 = device id (mod 10), byte 1 = read chunk size, then the bytes on the line.
#include <cstdint>
#include <string>
#include <vector>

#include "capture/dimetix.h"
#include "fuzz_util.h"
#include "serial_lines.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const int device_id = data[0] % 10;
  const std::size_t chunk = 1 + data[1] % 64;
  const std::string_view bytes = rk::fuzz::AsText(data + 2, size - 2);
  rk::fuzz::ExpectOnlyInputErrors([&] {
    for (const std::string& line : rk::fuzz::SerialLines(bytes, chunk)) {
      const rk::capture::DimetixReply r = rk::capture::ParseDimetixReply(line, device_id);
      if (r.kind == rk::capture::DimetixReplyKind::kInvalid) (void)rk::capture::EscapeForLog(line);
      if (r.kind == rk::capture::DimetixReplyKind::kDistance && (r.value > 9999999999 || r.value < -9999999999)) {
        std::abort();  // at most 10 digits
      }
    }
  });
  return 0;
}

// Shared by the serial-reply harnesses: the byte stream cut into lines by capture::LineSplitter, fed in
// reads of `chunk` bytes as the drivers' poll loops feed it.
#pragma once

#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "capture/serial_port.h"

namespace rk::fuzz {

inline std::vector<std::string> SerialLines(std::string_view bytes, std::size_t chunk) {
  rk::capture::LineSplitter splitter;
  std::vector<std::string> lines;
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    const std::string_view piece = bytes.substr(at, chunk);
    splitter.Feed(piece.data(), piece.size(), &lines);
  }
  for (const std::string& line : lines) {
    if (line.empty() || line.size() > 256) std::abort();  // LineSplitter's promise
  }
  return lines;
}

}  // namespace rk::fuzz

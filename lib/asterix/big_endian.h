// Big-endian fields (ASTERIX items, IP and UDP headers are in network byte order).
#pragma once

#include <cstdint>

namespace rk::asterix {

inline std::uint32_t Be16(const std::uint8_t* p) { return (std::uint32_t{p[0]} << 8) | p[1]; }
inline std::uint32_t Be24(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
}
inline std::uint32_t Be32(const std::uint8_t* p) { return (std::uint32_t{p[0]} << 24) | Be24(p + 1); }

}  // namespace rk::asterix

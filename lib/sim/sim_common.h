// What the simulators share, in one place: their random streams, how far the device logs extend past
// the frames, and the digits they write to trial files.
#pragma once

#include <cstdint>
#include <random>

namespace rk::sim {

// An independent random stream of a simulation: seed_seq{seed, stream, index} (seed_seq keeps the low
// 32 bits of each value). Streams are numbered per simulator, so adding a stream keeps the others.
inline std::mt19937_64 RandomStream(std::uint64_t seed, std::uint64_t stream, std::uint64_t index = 0) {
  std::seed_seq seq{seed, stream, index};
  return std::mt19937_64(seq);
}

// The stream convention of the pose-track and radar simulators: the seed's two 32-bit halves and the
// stream number (all 64 bits of the seed count).
inline std::mt19937_64 SplitSeedStream(std::uint64_t seed, std::uint64_t stream) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed & 0xffffffffu), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(stream)};
  return std::mt19937_64(seq);
}

constexpr double kSampleMarginS = 0.5;  // turret/range logs extend this far beyond the frames
constexpr double kServoMarginS = 1.0;   // the servo is simulated this far beyond the frames

// Digits after the decimal point in simulated trial files.
constexpr int kTimeDecimals = 9;
constexpr int kAngleDecimals = 9;
constexpr int kMetreDecimals = 6;
constexpr int kPixelDecimals = 4;

}  // namespace rk::sim

// What the KML and CZML writers share: the document's name and epoch, the digits of the numbers, the colours.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>

namespace rk::exports {

// The document: its name (rk-export --name, else the input file's name) and the epoch of t_s = 0 as POSIX seconds
// (--epoch-utc; rk-run gives the manifest's epoch_utc), with the text it was given in.
struct ExportHeader {
  std::string name;
  std::optional<double> epoch_unix_s;
  std::string epoch_text;  // "" without an epoch
  std::string source;      // the input file's name (not its folder: the document stays the same where it is moved)
};

// Digits written: 1e-9° (0.1 mm on the earth) for latitude and longitude, 1 µm for heights (a located target writes h_m so), 1e-9 s for the times
// after the epoch (as t_s is written), 1e-4 m for a 1σ; absolute times to the microsecond.
inline constexpr int kDegDecimals = 9;
inline constexpr int kHeightDecimals = 6;
inline constexpr int kTimeDecimals = 9;
inline constexpr int kSigmaDecimals = 4;
inline constexpr int kUtcDecimals = 6;

// A path's colour by its index (ids in order of first appearance): red, green, blue, alpha.
inline std::array<int, 4> PathColour(std::size_t index) {
  static constexpr std::array<std::array<int, 4>, 8> kPalette = {{{255, 200, 0, 255},
                                                                  {0, 200, 255, 255},
                                                                  {255, 80, 80, 255},
                                                                  {120, 255, 120, 255},
                                                                  {255, 120, 255, 255},
                                                                  {255, 255, 255, 255},
                                                                  {255, 150, 40, 255},
                                                                  {150, 150, 255, 255}}};
  return kPalette[index % kPalette.size()];
}

}  // namespace rk::exports

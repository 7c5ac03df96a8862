// Shared by the video tests: a reproducible random grey frame (8 or 16 bit), different for each k.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <random>

namespace rk::video {

inline cv::Mat Pattern(int w, int h, int depth, int k) {
  cv::Mat m(h, w, depth == 16 ? CV_16UC1 : CV_8UC1);
  std::mt19937 rng(static_cast<unsigned>(k));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      unsigned v = rng();
      if (depth == 16) {
        m.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(v);
      } else {
        m.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(v);
      }
    }
  }
  return m;
}

}  // namespace rk::video

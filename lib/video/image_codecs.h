// cv::imread and cv::imwrite of OpenCV's imgcodecs, loaded the first time an image file is read or written.
//
// Why not linked: libopencv_imgcodecs needs 140 shared libraries (GDAL, GDCM, PROJ, codecs ...), and loading and
// relocating them took 0.2 s of every start of rk-extract — longer than reading a 1 GB recording from the page
// cache (docs/benchmarks.md "Reading recordings"). A tool that reads only camera files, y4m or ffmpeg videos now
// never loads them; an image sequence loads them once (dlopen of the library the build linked against, by its
// soname; the two functions by their C++ names, checked at load).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace rk::video {

// cv::imread(path, flags); IoError when OpenCV's imgcodecs cannot be loaded.
cv::Mat ImRead(const std::string& path, int flags);
// cv::imwrite(path, image, params).
bool ImWrite(const std::string& path, const cv::Mat& image, const std::vector<int>& params);

}  // namespace rk::video

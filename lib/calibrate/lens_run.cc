// CalibrateLens: every frame of every input (video::FrameSource: files, image-sequence patterns, videos),
// boards detected on opt.threads threads while the next frames are read, then SolveLens.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "calibrate/lens_calibration.h"
#include "io/error.h"
#include "video/frame_source.h"

namespace rk::calibrate {
namespace {

// An 8-bit copy of a frame (16-bit frames scaled so that their brightest pixel is 255).
cv::Mat ToGray8(const cv::Mat& frame) {
  if (frame.depth() == CV_8U) return frame.clone();
  double lo = 0, hi = 0;
  cv::minMaxLoc(frame, &lo, &hi);
  cv::Mat out;
  frame.convertTo(out, CV_8U, hi > 0 ? 255.0 / hi : 1.0);
  return out;
}

// Names of the frames of one input: the image path for a pattern, the path for a one-frame file, else "path#N".
struct FrameNamer {
  std::string input;
  bool pattern = false;
  std::int64_t first = 0;

  explicit FrameNamer(std::string in) : input(std::move(in)), pattern(video::IsSequencePattern(input)) {
    if (pattern) first = std::filesystem::exists(video::SequenceFramePath(input, 0)) ? 0 : 1;
  }
  std::string Name(std::int64_t i) const {
    return pattern ? video::SequenceFramePath(input, first + i) : input + "#" + std::to_string(i);
  }
};

// Detects the boards of `frames` into `views`, `threads` at a time.
void DetectBatch(const std::vector<cv::Mat>& frames, std::vector<LensView*>& views, const LensOptions& opt,
                 int threads) {
  std::vector<std::thread> pool;
  const std::size_t n = frames.size(), step = static_cast<std::size_t>(threads);
  for (std::size_t t = 0; t < std::min(n, step); ++t) {
    pool.emplace_back([&, t] {
      for (std::size_t i = t; i < n; i += step) DetectBoard(frames[i], opt, views[i]);
    });
  }
  for (auto& th : pool) th.join();
}

}  // namespace

LensResult CalibrateLens(const std::vector<std::string>& inputs, const LensOptions& opt,
                         const std::function<void(std::int64_t)>& progress) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  const auto t0 = std::chrono::steady_clock::now();
  const int threads = opt.threads > 0 ? opt.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::vector<LensView> views;
  views.reserve(1024);
  int width = 0, height = 0;
  std::int64_t read = 0;
  for (const std::string& input : inputs) {
    video::FrameSource source({input});
    const FrameNamer namer(input);
    const std::size_t first_view = views.size();
    std::vector<cv::Mat> batch;
    std::vector<std::size_t> batch_views;
    cv::Mat frame;
    const auto flush = [&] {
      std::vector<LensView*> ptrs;
      for (std::size_t i : batch_views) ptrs.push_back(&views[i]);
      DetectBatch(batch, ptrs, opt, threads);
      batch.clear();
      batch_views.clear();
    };
    while (source.Read(&frame)) {
      if (width == 0) width = frame.cols, height = frame.rows;
      if (frame.cols != width || frame.rows != height) {
        throw DataError(input, 0, 0, "image size " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                                         " differs from the first image's " + std::to_string(width) + "x" +
                                         std::to_string(height));
      }
      LensView v;
      v.name = namer.Name(static_cast<std::int64_t>(views.size() - first_view));
      views.push_back(std::move(v));
      batch.push_back(ToGray8(frame));
      batch_views.push_back(views.size() - 1);
      if (static_cast<int>(batch.size()) >= 2 * threads) flush();
      if (progress) progress(++read);
    }
    flush();
    if (!namer.pattern && views.size() == first_view + 1) views.back().name = input;  // a single image file
    if (views.size() == first_view) throw DataError(input, 0, 0, "no image in this input");
  }
  const double detect_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  LensResult res = SolveLens(std::move(views), width, height, opt);
  res.detect_s = detect_s;
  return res;
}

}  // namespace rk::calibrate

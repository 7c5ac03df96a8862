// The frame loop shared by the rk-extract subcommands (beacon, features, silhouette): every frame of a
// recording, in decode order across its segments, with its time from the frame clock, timed.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "formats/frame_times.h"

namespace rk::extract {

// What every extraction run reports about the video it read.
struct VideoRunStats {
  std::int64_t frames = 0;
  std::int64_t frames_without_time = 0;            // holes in the frames file (--bad-rows skip): not measured
  int width_px = 0, height_px = 0, bit_depth = 8;  // of the first frame
  double wall_s = 0.0;                             // decode + extraction
  double extract_s = 0.0;                          // time spent in `process` only
};

// Wall seconds since `t0` (steady clock), for the run timings.
inline double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Calls process(frame, k, t_s) for every frame k of `videos` (read in the order given) with
// t_s = clock.TimeOf(k) (a frame without a time, a hole of a frames file read with --bad-rows skip, is
// decoded but not processed; one warning counts them), and progress(k) every `progress_every` frames when set. Throws DataError
// naming the frames file if it lists fewer times than the video has frames (FrameClock::TimeOf), and
// naming the last video if that has fewer frames than the frames file lists (truncated).
VideoRunStats ForEachFrame(const std::vector<std::string>& videos, const formats::FrameClock& clock,
                           const std::function<void(const cv::Mat& frame, std::int64_t k, double t_s)>& process,
                           const std::function<void(std::int64_t)>& progress, std::int64_t progress_every);

}  // namespace rk::extract

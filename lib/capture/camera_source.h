// Camera sources of a station (SPEC.md §6 camera "source"):
//   "0", "1", …          V4L2 device index      (OpenCV VideoCapture, CAP_V4L2)
//   "/dev/video0"        V4L2 device path       (OpenCV VideoCapture, CAP_V4L2)
//   "gst:<pipeline>"     GStreamer pipeline ending in appsink (OpenCV VideoCapture, CAP_GSTREAMER);
//                        GigE / USB3 Vision cameras through aravissrc, e.g.
//                        "gst:aravissrc camera-name=X ! video/x-raw,format=GRAY8 ! appsink"
//   "aravis:<id>"        a GigE Vision / USB3 Vision camera through Aravis' own API (aravis_source.h): the
//                        station config's features set in order and read back, the camera's own time stamp
//                        of every frame (camera_ns), stream counters
//   "file:<path>"        a recorded video or image sequence, replayed at its frame rate (tests);
//                        decoded by the suite's own reader (lib/video FrameSource, the one
//                        rk-extract uses), so frames arrive bit-exact, 16-bit kept
//   "cvfile:<path>"      a video file through OpenCV VideoCapture (CAP_FFMPEG), replayed at its
//                        frame rate: the V4L2 / GStreamer code path (grab, retrieve, grey
//                        conversion) on a file, for tests; 8-bit
//   "synthetic:WxH[:16]" frames made in memory at the configured rate (benchmarks and tests):
//                        a fixed random texture with a moving bright spot; the frame's sequence
//                        number is written into its first 8 pixels (SyntheticFrameSeq reads it)
// Frames are delivered as 8- or 16-bit mono (colour converted to grey) and stamped on arrival.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "capture/clock.h"
#include "io/json_util.h"

namespace rk::capture {

struct CameraSourceOptions {
  std::string source;         // as in the station configuration (file: paths already resolved)
  double fps = 20.0;          // requested / replay rate (a file's own rate wins, see FileSource)
  int width = 0, height = 0;  // requested V4L2 size (0 = the device's)
  std::string fourcc;         // requested V4L2 pixel format, e.g. "GREY", "Y16 " (empty = the device's)
  bool loop = false;          // file: start again at the end
  // aravis: GenICam features (name, value as text) in the order the station config gives them.
  std::vector<std::pair<std::string, std::string>> features;
  bool ptp = false;           // aravis: enable IEEE 1588 on the camera (GevIEEE1588 or PtpEnable) and record its status
};

enum class GrabResult { kFrame, kEnd, kError, kStopped };

class CameraSource {
 public:
  virtual ~CameraSource() = default;
  virtual bool Open(std::string* why) = 0;
  virtual void Close() = 0;
  // Waits for the next frame and writes it into `*out` (reusing its buffer when the size and type
  // match), stamped with its arrival.
  virtual GrabResult Grab(cv::Mat* out, Stamp* at, std::string* why, const std::atomic<bool>& stop) = 0;
  // Frame rate of the stream (known after Open).
  virtual double fps() const = 0;
  virtual std::string kind() const = 0;  // "v4l2", "gstreamer", "file", "synthetic", "aravis"
  // A camera with its own clock: the time stamp of the last frame Grab returned, ns on that clock (−1 none).
  virtual bool has_camera_clock() const { return false; }
  virtual std::int64_t camera_ns() const { return -1; }
  // What to subtract from camera_ns for the frame's time (a hardware trigger's delay before the exposure; 0).
  virtual std::int64_t frame_time_shift_ns() const { return 0; }
  // Frames the source knows it lost just before the last one Grab returned (incomplete, never arrived): the
  // recorder's seq jumps by as many, as frames.csv promises.
  virtual std::int64_t lost_before_last() const { return 0; }
  // The stream's counters and the features asked and read back, for the report (null when the source has none).
  virtual io::Json StreamReport() const { return nullptr; }
};

// Throws UsageError for a source string it cannot interpret.
std::unique_ptr<CameraSource> MakeCameraSource(const CameraSourceOptions& options);

// Sequence number written into a synthetic frame (−1 if the frame carries none).
std::int64_t SyntheticFrameSeq(const cv::Mat& frame);

}  // namespace rk::capture

// "aravis:<id>" camera source: a GigE Vision or USB3 Vision camera through Aravis (method in aravis_source.cc).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "capture/camera_source.h"
#include "io/json_util.h"

namespace rk::capture {

struct AravisStreamStats {
  std::uint64_t complete = 0;       // frames delivered whole
  std::uint64_t incomplete = 0;     // buffers with missing packets, timed out or mis-sized: dropped, never written
  std::uint64_t never_arrived = 0;  // frames the camera sent (its frame ids) that never reached the host
  std::uint64_t resent_packets = 0, missing_packets = 0;  // GigE Vision stream (Aravis' counters)
  std::uint64_t lost_buffers = 0;   // frames Aravis had no free buffer for (underruns)
  std::uint64_t timeouts = 0;       // silences longer than the source's limit (a reconnect follows)
};

// The frame's time on a triggered camera (issue 32): with TriggerMode On and a hardware TriggerSource (a line,
// not Software), the frame's time is the trigger's: the camera stamps the frame when its exposure starts, which
// is TriggerDelay (SFNC, µs; older cameras TriggerDelayAbs) after the trigger, so the trigger's time is the
// stamp less that delay. `get` reads a feature's value as text (nullopt: the camera has no such feature).
struct TriggerTiming {
  bool hardware = false;  // a hardware trigger: the frame's time is the trigger's
  std::int64_t delay_ns = 0;  // subtracted from the camera stamp for the frame's time
  io::Json report;        // {"mode", "selector", "source", "delay_s", "delay_feature", "frame_time"} or null
};
TriggerTiming DecideTrigger(const std::function<std::optional<std::string>(const char*)>& get);

struct AravisCameraInfo {
  std::string id, model, serial, address;
};

class AravisSource final : public CameraSource {
 public:
  explicit AravisSource(CameraSourceOptions o);
  ~AravisSource() override;
  bool Open(std::string* why) override;
  void Close() override;
  GrabResult Grab(cv::Mat* out, Stamp* at, std::string* why, const std::atomic<bool>& stop) override;
  double fps() const override { return fps_; }
  std::string kind() const override { return "aravis"; }
  bool has_camera_clock() const override { return true; }
  std::int64_t camera_ns() const override { return camera_ns_; }
  std::int64_t frame_time_shift_ns() const override { return trigger_.delay_ns; }
  std::int64_t lost_before_last() const override { return lost_before_last_; }
  io::Json StreamReport() const override;
  AravisStreamStats stream_stats() const;

  struct FeatureResult {
    std::string name, asked, got, error;
  };
  const std::vector<FeatureResult>& features() const { return features_; }

 private:
  // IEEE 1588 on request: the camera's own switch (SFNC PtpEnable, or GigE Vision's GevIEEE1588), read back, and
  // its status (PtpStatus / GevIEEE1588Status) when it has one.
  void EnablePtp();
  // The stream's receive thread (Aravis starts it when the stream is made; it inherits the scheduling of the
  // thread that makes it): real-time (SCHED_FIFO) where allowed, else a raised nice level, else as it is; said
  // in receive_thread.
  void RaiseForReceiveThread();
  void RestoreAfterReceiveThread();
  // Frames the camera sent that never arrived, from the frame ids (every buffer's, complete or not).
  void CountFrameId(std::uint64_t id);

  CameraSourceOptions o_;
  std::string id_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<FeatureResult> features_;
  AravisStreamStats stats_;
  double fps_ = 0.0;
  bool gv_ = false;
  int packet_size_ = 0, opens_ = 0;
  std::int64_t camera_ns_ = -1;
  std::int64_t lost_before_last_ = 0, lost_pending_ = 0;
  io::Json ptp_ = nullptr;  // asked: {"feature", "enabled", "status"} or {"error"}
  TriggerTiming trigger_;
  std::string receive_thread_;  // what the stream's receive thread got
  int saved_policy_ = 0, saved_nice_ = 0;
  int saved_priority_ = 0;
  bool nice_raised_ = false, policy_raised_ = false;
};

// What Aravis discovers (rk-capture --list-cameras).
std::vector<AravisCameraInfo> ListAravisCameras();

}  // namespace rk::capture

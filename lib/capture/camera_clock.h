// A camera's own clock mapped onto the host's (issue 32): frames.csv `t_s` of a camera with a clock (aravis:)
// comes from its time stamp through this mapping, which is followed as the run goes.
//
// Model, in the camera's time since its first frame c = (camera_ns − first camera_ns)·1e-9 (exact in double,
// whatever epoch the camera's clock counts from): host_s − c = a + b · c + e, with a the host time of the first
// frame's exposure (plus the transfer latency), b the drift (crystal against host; tens of ppm) and e the host arrival's jitter (≥ 0 in
// truth, modelled as white). A two-state Kalman filter (Joseph form) follows (a, b): a random walk on both (the
// oscillator's drift wanders with temperature, NTP slews the host), the drift's prior 0 ± 200 ppm, the jitter's
// variance estimated from the innovations (a robust running mean of their squares, started at 1 ms²). Each
// frame's mapped time uses the state after that frame's update, so the mapping is smooth — a frame's t_s moves
// by the filter's correction, far below a frame period — and does not re-base the camera's relative times. The
// report's fit (CameraStream::ClockFit) is the least-squares line over the whole run, for comparison.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace rk::capture {

class CameraClockMapper {
 public:
  // Host time (s, the host clock of host_s) of a frame the camera stamped camera_ns, after adding this frame
  // (host arrival host_s).
  double Add(std::int64_t camera_ns, double host_s);
  // The mapping now (no new frame).
  double Map(std::int64_t camera_ns) const;
  // A camera whose clock went back (a power cycle): a new mapping.
  void Reset() { n_ = 0; }
  std::int64_t frames() const { return n_; }
  double offset_s() const { return x_(0); }
  double drift_ppm() const { return x_(1) * 1e6; }
  double jitter_s() const;

 private:
  std::int64_t n_ = 0;
  std::int64_t first_ns_ = 0;
  double last_c_ = 0.0;
  double r_ = 1e-6;  // jitter variance estimate (s²)
  Eigen::Vector2d x_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d P_ = Eigen::Matrix2d::Zero();
};

}  // namespace rk::capture

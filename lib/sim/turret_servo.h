// True boresight of a pan/tilt turret that tracks a target, for rk-sim.
//
// Model (per axis, azimuth unwrapped, angles in radians):
//   τ θ'(t) + θ(t) = u(t)            first-order servo lag, u = commanded angle
//   boresight(t) = θ(t) + j(t)       plus mechanical jitter
// u(t) is the azimuth/elevation of the target reference point (AzElFromEnu).
// The ODE is integrated exactly for u linear over each step of h = 4 ms
// (e = θ − u, s = du/dt:  e_{i+1} = −sτ + (e_i + sτ) e^{−h/τ}); between nodes
// θ is a cubic Hermite interpolant using θ' = (u − θ)/τ, so the boresight is
// a smooth function of t. The servo starts in steady state (θ = u − τ u').
// A first-order lag tracks a ramp with a constant error τ·u' — the "lag" of a
// real tracker — and the error grows with the target's angular rate.
// Jitter is band-limited: j(t) = Σ_k a_k sin(2π f_k t + φ_k), K = 8 tones per
// axis, f_k uniform in [f_min, f_max], φ_k uniform, a_k = J·sqrt(2/K), so the
// RMS is J per axis (azimuth-axis and elevation-axis angles, not on-sky).
// Seeded: the same seed gives the same jitter.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/options.h"

namespace rk::sim {

struct TurretServoOptions {
  double lag_s = 0.15;                       // first-order time constant τ (s), [0, 2]; 0 = no lag
  double jitter_arcsec = 5.0;                // J: RMS jitter per axis (arcsec), [0, 0.01 rad]
  double jitter_min_hz = 0.5;                // lowest jitter tone (Hz)
  double jitter_max_hz = 5.0;                // highest jitter tone (Hz)

  double jitter_rms_rad() const { return jitter_arcsec / geo::kArcsecPerRad; }

  static const io::OptionTable<TurretServoOptions>& Table();
  // Table().Check, then min <= max of the jitter band.
  bool Check(std::string* why) const;
};

class TurretServo {
 public:
  // Simulates the servo over [t_begin_s, t_end_s] following the direction
  // of `target_enu(t)` (ENU position, any non-zero vector).
  TurretServo(const TurretServoOptions& opt, const std::function<Eigen::Vector3d(double)>& target_enu,
              double t_begin_s, double t_end_s, std::uint64_t seed);

  // True boresight (lag + jitter) at t in [t_begin, t_end]; az in [0, 2π).
  geo::AzEl Boresight(double t_s) const;
  // The same without jitter (servo state θ only).
  geo::AzEl ServoState(double t_s) const;

 private:
  double Interp(const std::vector<double>& x, const std::vector<double>& dx, double t_s) const;
  double Jitter(const std::vector<double>& f, const std::vector<double>& ph, double t_s) const;

  TurretServoOptions opt_;
  double t_begin_s_ = 0.0;
  double h_s_ = 0.004;
  std::vector<double> az_, daz_, el_, del_;  // unwrapped az, rates (rad, rad/s)
  std::vector<double> f_az_, ph_az_, f_el_, ph_el_;
  double amp_rad_ = 0.0;
};

}  // namespace rk::sim

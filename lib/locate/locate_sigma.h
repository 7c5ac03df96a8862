// 1σ of a located row (SPEC.md §2.1 sigma_az_deg … sigma_u_m): first-order propagation y = g(x),
// Σ_y = J Σ_x Jᵀ, with J by automatic differentiation (ceres::Jet) of rk-locate's own geometry:
//
//   x = (x_px, y_px,  A, E,  az_offset, tilt_north, tilt_east, el_axis_tilt,  mount yaw, pitch, roll,
//        focal_length_mm,  range_m,  δτ)
//   A_t = A + Ȧ·δτ, E_t = E + Ė·δτ, r_t = r + ṙ·δτ                         (time offset error δτ)
//   m   = undistorted normalised ray of the pixel with focal f (linearised undistortion about the pixel)
//   ray = R_enu_turret(A_t, E_t; pointing terms) · R_turret_cam(mount) · m / |·|      (SPEC.md §3.1)
//   y   = (az, el, r_t, r_t·ray)                                                    (az, el, range, e, n, u)
//
// Σ_x is diagonal (the sources are independent of each other), each variance from:
//   pixels         the track's sigma_x_px/sigma_y_px, else --sigma-px
//   A, E           encoder quantisation step²/12 + --turret-sigma-deg² (per axis)
//   pointing terms pointing.json "sigma" (a term without a sigma: 0)
//   mount, focal,  the camera's "calibration": {"sigma": {"mount_deg", "focal_length_mm", "time_offset_s"}}
//   δτ             (absent: 0)
//   range          --range-sigma-mm
// Ȧ, Ė, ṙ are the turret's and the range's rates at the row's time (central differences of the
// interpolated logs). Shared errors: the pointing, mount, focal and time-offset errors are one draw for the
// whole trial and the encoder error one draw per dwell of a still turret; each row's σ is its marginal
// (correct for that row), but rows are not independent and an average over rows does not shrink them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

#include "camera/camera_model.h"
#include "camera/pointing_model.h"

namespace rk::locate {

inline constexpr int kSigmaInputs = 14;
inline constexpr int kSigmaOutputs = 6;  // az, el, range, e, n, u
using SigmaInputVector = Eigen::Matrix<double, kSigmaInputs, 1>;
using LocatedCovariance = Eigen::Matrix<double, kSigmaOutputs, kSigmaOutputs>;
using LocatedJacobian = Eigen::Matrix<double, kSigmaOutputs, kSigmaInputs>;

// The 1σ of every input but the pixels (which come per row). Radians, metres, seconds.
struct SigmaSources {
  double pixel_px = 0.0;                  // fallback pixel σ (track rows without sigma columns)
  double turret_rad = 0.0;                // per axis: √(step²/12 + turret σ²)
  std::array<double, 4> pointing_rad{};   // az_offset, tilt_north, tilt_east, el_axis_tilt
  std::array<double, 3> mount_rad{};      // yaw, pitch, roll
  double focal_mm = 0.0;
  double time_offset_s = 0.0;
  double range_m = 0.0;
};

// The camera's calibration σ (SPEC.md §3.1 keys; absent = 0); DataError naming `where` for a malformed one.
void CameraSigma(const camera::CameraModel& camera, const std::string& where, SigmaSources* s);
void PointingSigma(const camera::PointingModel& pointing, SigmaSources* s);

// One row's linearisation point.
struct SigmaPoint {
  Eigen::Vector2d px = Eigen::Vector2d::Zero();
  Eigen::Vector2d sigma_px = Eigen::Vector2d::Zero();
  double az_rad = 0.0, el_rad = 0.0;           // logged boresight at the row's time
  double az_rate = 0.0, el_rate = 0.0;         // rad/s
  double range_m = 0.0, range_rate_mps = 0.0;  // 0 when the row has no range
};

// Nominal inputs x (δτ = 0) of a row.
SigmaInputVector SigmaNominal(const camera::CameraModel& camera, const geo::PointingTerms& terms,
                              const SigmaPoint& p);
// y = g(x) in doubles, exactly (full undistortion; for checking the Jacobian numerically).
Eigen::Matrix<double, kSigmaOutputs, 1> LocatedFunction(const camera::CameraModel& camera, const SigmaPoint& p,
                                                        const SigmaInputVector& x);
// ∂y/∂x at the nominal point by automatic differentiation.
LocatedJacobian LocatedJacobianAt(const camera::CameraModel& camera, const geo::PointingTerms& terms,
                                  const SigmaPoint& p);
// Σ_y = J Σ_x Jᵀ.
LocatedCovariance LocatedCovarianceAt(const camera::CameraModel& camera, const geo::PointingTerms& terms,
                                      const SigmaPoint& p, const SigmaSources& s);

}  // namespace rk::locate

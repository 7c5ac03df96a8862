// rk-calibrate pointing: the turret pointing model (SPEC.md §3.1), the camera mount, optionally the focal
// length and the camera's time offset, from image points of landmarks and stars.
//
// Model. For observation i of target j in cluster k (pointing_observations.h), with x the parameters
// (az_offset, tilt_north, tilt_east, el_axis_tilt, mount yaw/pitch/roll, focal δf, time offset τ), c_k the
// cluster's turret-reading error (az, el) and t_j the target's direction error:
//   A_i = A_log(t_i + τ) + c_k,az     E_i = E_log(t_i + τ) + c_k,el     (logged angles, linearised in τ)
//   v_cam = R_turret_cam(mount)ᵀ · R_enu_turret(A_i, E_i; pointing)ᵀ · (d_j(t_i + τ) + t_j,1 e1 + t_j,2 e2)
//   pixel_i = distort(v_cam / v_cam,z) scaled by f·(1 + δf), plus the principal point (SPEC.md §3)
// Minimised: Σ_i ρ(|(pixel_i − observed_i) / σ_i|²) + Σ_k |c_k / σ_c,k|² + Σ_j |t_j / σ_t,j|², ρ Huber with
// scale kHuberScale. The c_k and t_j are nuisance parameters with their known priors: the errors the
// observations share (one encoder reading per dwell, one survey error per landmark) enter once, not once
// per frame, so the covariance of x, the x-block of (JᵀJ)⁻¹ at the solution, is the generalised least
// squares covariance that accounts for them (checked by NEES over Monte Carlo runs,
// tests/calibrate/test_pointing_mc.cc).
// τ is estimated by re-evaluating the turret log and the stars at the current τ (up to
// kMaxRelinearisations times). az_offset is initialised from the data (circular median of target
// azimuth − ray azimuth), anything else from zero or the input camera.
// Outliers: after the robust solve an observation whose marginal residual (nuisance zero) has
// χ² = rᵀ S⁻¹ r > kOutlierChi2 (S its covariance, 2 dof) is rejected and the problem solved again.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/pointing_observations.h"
#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "io/options.h"

namespace rk::calibrate {

enum PointingParam {
  kParamAzOffset = 0,
  kParamTiltNorth,
  kParamTiltEast,
  kParamElAxisTilt,
  kParamMountYaw,
  kParamMountPitch,
  kParamMountRoll,
  kParamFocal,       // relative focal-length change δf (f = f0 (1 + δf))
  kParamTimeOffset,  // camera time offset τ (s)
  kNumPointingParams
};
// "az_offset", "tilt_north", ..., "mount_yaw", "focal", "time_offset".
const char* PointingParamName(int param);

using EstimateSet = std::array<bool, kNumPointingParams>;
// SPEC.md §3.1 --estimate: comma-separated az_offset, tilt (both tilts), el_axis_tilt, mount (yaw, pitch,
// roll), focal, time_offset. Throws UsageError for an unknown or empty name.
EstimateSet ParseEstimate(const std::string& list);
EstimateSet DefaultEstimate();  // az_offset,tilt,el_axis_tilt,mount

constexpr double kHuberScale = 3.0;     // robust loss: quadratic up to 3σ of the pixel residual
constexpr double kOutlierChi2 = 28.0;   // χ²(2 dof) > 28: p < 1e-6, a 5σ-class outlier
constexpr int kMaxOutlierRounds = 3;    // solve, reject, solve again at most this often
constexpr int kMaxRelinearisations = 4; // re-evaluations of the turret log at the estimated τ
constexpr double kSeparabilityCorrelation = 0.95;  // |ρ| above this: the pair is named as not separated

struct PointingCalibrationOptions {
  double encoder_step_deg = 0.003;  // turret encoder quantum (deg): σ = step/√12 per dwell reading
  double pixel_sigma_px = 0.1;      // σ of an image point without sigma_x_px,sigma_y_px
  double dut1_s = 0.0;              // UT1 − UTC (s)
  double pressure_hpa = 1013.25;    // refraction of the stars (SPEC.md §3.1 defaults)
  double temperature_c = 10.0;
  double humidity = 0.5;
  double wavelength_um = 0.85;
  double turret_max_gap_s = 1.0;    // longest turret-log interval interpolated across (s)
  int max_iterations = 100;         // Ceres iterations per solve

  static const io::OptionTable<PointingCalibrationOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const;
  double encoder_step_rad() const;
};

struct ObservationResidual {
  std::size_t row = 0;         // index into ImagePoints::rows
  std::string id;
  double target_az_rad = 0.0, target_el_rad = 0.0;  // true direction of the target
  Eigen::Vector2d residual_px = Eigen::Vector2d::Zero();  // predicted − observed, turret error terms zero
  double chi2 = 0.0;           // rᵀ S⁻¹ r of that residual (2 dof)
  bool rejected = false;
};

struct PointingSolution {
  std::array<double, kNumPointingParams> x{};  // radians; focal δf; τ (s)
  EstimateSet estimated{};
  std::vector<int> estimated_params;  // the estimated parameters, in covariance order
  Eigen::MatrixXd covariance;         // of the estimated parameters (radians, δf, s)
  Eigen::MatrixXd correlation;
  std::array<std::optional<double>, kNumPointingParams> sigma;  // 1σ (radians, δf, s)
  std::vector<ObservationResidual> residuals;  // every observation, in file order
  std::size_t used = 0, rejected = 0, clusters = 0, dwells = 0, targets = 0;
  double rms_px = 0.0;       // RMS of the used observations' residual components
  double chi2_per_dof = 0.0; // of the whole fit (pixel and prior terms)
  int iterations = 0;        // Ceres iterations, all solves
  int relinearisations = 0;  // τ re-evaluations
  std::string termination;   // Ceres's of the last solve
  std::vector<std::string> warnings;  // what cannot be separated, doubtful fits (in words)

  double focal_length_mm(const camera::CameraModel& cam) const { return cam.focal_length_mm * (1 + x[kParamFocal]); }
  camera::PointingModel Model() const;                                // pointing terms and their σ
  camera::CameraModel Camera(const camera::CameraModel& input) const;  // mount/focal/τ and calibration.sigma
};

// Builds the observations at a given time offset τ0 (s); called again when τ is estimated.
using ObservationBuilder = std::function<PointingObservations(double tau0_s)>;

// Throws ProcessingError when there are fewer residuals than parameters, the solve fails, or the
// observations leave a parameter undetermined.
// `progress(n)` (optional) is called after each Ceres solve, n = solves done (outlier passes and τ
// re-evaluations: at most (kMaxOutlierRounds + 1) · (kMaxRelinearisations + 1), usually 1 to 3).
PointingSolution SolvePointing(const ObservationBuilder& build, const camera::CameraModel& camera,
                               const EstimateSet& estimate, const PointingCalibrationOptions& options,
                               const std::function<void(std::int64_t)>& progress = {});

// The circular median of target azimuth − ray azimuth (radians, (−π, π]): the azimuth zero's first guess.
double InitialAzOffset(const PointingObservations& obs, const camera::CameraModel& camera);

}  // namespace rk::calibrate

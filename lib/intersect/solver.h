// Intersection of several stations' lines of sight (± ranges) at one time: weighted least squares for
// one point (SPEC.md §7; docs/rk-intersect.md "Method").
//
// Frames. The unknown p is the target in the origin's local ENU frame (a rigid rotation and translation of
// WGS-84 ECEF: exact, not a flat earth). Station i sits at a_i in that frame; its own ENU frame (its own
// vertical and north) is reached by d_i(p) = c_i + M_i p, M_i = R_ecef_enu_iᵀ R_ecef_enu_o (a rotation),
// c_i = R_ecef_enu_iᵀ (o_ecef − s_ecef_i), both from GeographicLib::Geocentric (station_frames.h).
// Model of station i, with h = hypot(d_e, d_n), ρ = |d|:
//   az_i(p) = atan2(d_e, d_n),   el_i(p) = atan2(d_u, h),   range_i(p) = ρ.
// Residuals, whitened by the observation's covariance (so the weight matrix is the identity):
//   z_az = wrap(az_meas − az_i(p)) / σ_az   (= cos(el)·Δaz / (cos(el)·σ_az): the cross-elevation residual)
//   z_el = ((el_meas − el_i(p)) / σ_el − ρ z_az) / sqrt(1 − ρ²),   z_ρ = (ρ_meas − ρ_i(p)) / σ_ρ (with a range),
// ρ the correlation of the az and el errors (rk-locate's corr_az_el, 0 when the file has none): z = L⁻¹ r with
// L the Cholesky factor of [[σ_az², ρσ_azσ_el], [ρσ_azσ_el, σ_el²]]. With ρ = 0 these are r / σ exactly.
// Jacobians (analytic, checked against numerical ones in tests/intersect):
//   ∂az/∂d = (d_n, −d_e, 0) / h²,   ∂el/∂d = (−d_e d_u, −d_n d_u, h²) / (h ρ²),   ∂ρ/∂d = dᵀ/ρ,   ∂d/∂p = M_i.
// Minimise Σ z² by Gauss–Newton, p ← p + (JᵀJ)⁻¹ Jᵀ z with J = ∂(pred/σ)/∂p, from the linear closest
// point of the lines (minimises Σ |(I − u uᵀ)(p − a)|², plus |p − (a + ρ u)|² for a range), until the step
// is below kStepTolerance relative to the size of p (machine level). Covariance P = (JᵀJ)⁻¹ at the
// solution (Gaussian, independent errors; the linearisation error is negligible when σ·range ≪ range).
// Outliers: with ≥ 3 lines of sight, when some normalised residual exceeds k, each station is predicted from
// the others (leave-one-out solution p₋ᵢ, P₋ᵢ): its standardised residuals z_j / sqrt(1 + h_j P₋ᵢ h_jᵀ); the
// station with the largest is dropped when that exceeds k, and the rest is solved again (while ≥ 3 lines).
// Geometry: the largest angle between two used lines at the target (90° best) and
// gdop = sqrt(trace P) / (σ̄ · ρ̄) (σ̄ RMS cross-line angle σ, ρ̄ RMS range: 3-D σ in units of one line's σ).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "formats/stations.h"

namespace rk::intersect {

// Largest number of stations (the per-row station sets are bit masks).
inline constexpr int kMaxStations = static_cast<int>(formats::kMaxStations);  // stations.json's limit
// Gauss–Newton stops when |Δp| ≤ kStepTolerance · (1 m + |p − a_i|max): ~ 200 × machine ε at 50 km.
inline constexpr double kStepTolerance = 1e-12;
inline constexpr int kMaxIterations = 30;
// JᵀJ whose eigenvalue ratio is below this is singular (lines parallel, target on the baseline).
inline constexpr double kMinConditionRatio = 1e-14;

// One station's fixed geometry in the origin ENU frame.
struct StationFrame {
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();  // station ENU from origin ENU (rotation)
  Eigen::Vector3d c = Eigen::Vector3d::Zero();      // origin point in station ENU (m)
  Eigen::Vector3d a = Eigen::Vector3d::Zero();      // station position in origin ENU (m) = −Mᵀc
};

// One station's measurement at the row's time (radians, metres).
struct LineObservation {
  int station = 0;              // index into the frames
  double az_rad = 0.0, el_rad = 0.0;
  double sigma_az_rad = 0.0;    // 1σ of the azimuth angle itself (cross-elevation σ / cos el)
  double sigma_el_rad = 0.0;
  double corr_az_el = 0.0;      // correlation of the azimuth and elevation errors, |ρ| ≤ kMaxCorrelation used
  bool has_range = false;
  double range_m = 0.0, sigma_range_m = 0.0;
};

// Predicted measurement and its Jacobian wrt p (rows az, el, range) for station frame f at p.
struct Prediction {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();  // target in station ENU
  double az = 0.0, el = 0.0, range = 0.0;
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();  // rows ∂az/∂p, ∂el/∂p, ∂ρ/∂p
};
Prediction Predict(const StationFrame& f, const Eigen::Vector3d& p);

// Normalised (whitened) residuals of one observation at p (az, el, range; range 0 without one).
Eigen::Vector3d NormalisedResiduals(const LineObservation& o, const Prediction& pr);
// Their Jacobian with respect to p, up to sign: the rows of pr.J whitened the same way (∂z/∂p = −this).
Eigen::Matrix3d NormalisedJacobian(const LineObservation& o, const Prediction& pr);
// |corr_az_el| is capped here: a correlation of ±1 is a degenerate covariance (one angle the other's copy).
inline constexpr double kMaxCorrelation = 0.999;

enum class SolveStatus { kOk, kTooFew, kSingular, kNotConverged, kBehind };

struct Solution {
  SolveStatus status = SolveStatus::kTooFew;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // origin ENU (m)
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();  // covariance (m²)
  double chi2 = 0.0;                            // Σ z² over the used residuals
  int residuals = 0;                            // number of used residuals
  int iterations = 0;
};

struct RowResult {
  Solution solution;
  std::uint64_t used = 0;      // bit per observation index (not station) used in the final solution
  std::uint64_t rejected = 0;  // bit per observation index dropped as an outlier
  double rms_residual_arcsec = 0.0;  // RMS of the used angle residuals (azimuth × cos el, elevation)
  double intersection_angle_deg = 0.0;
  double gdop = 0.0;
};

struct SolverOptions {
  double reject_sigma = 5.0;  // k (normalised residual); +inf = never reject
};

// True when the observations can fix a point: ≥ 2 lines of sight, or one with a range.
bool Solvable(const LineObservation* obs, int n, std::uint64_t mask);

// Solves with the observations in `mask` (bit i = obs[i]).
Solution SolveMasked(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, std::uint64_t mask);

// The whole row: solve, reject outliers, residual RMS and geometry figures. No allocation.
RowResult SolveRow(const std::vector<StationFrame>& frames, const LineObservation* obs, int n,
                   const SolverOptions& options);

}  // namespace rk::intersect

// Measurement model of mobile radar bias registration (seed 002, Deng et al. 2024, eqs. 1–21;
// SPEC.md §3 "Radar (seed 002)"). One implementation shared by the Bernoulli filter, the
// known-association Kalman filter and the batch maximum-likelihood solve.
//
// Frames (docs/rk-register.md):
//   platform  B: x right, y forward, z up (origin at the radar). A plot (r, θ, φ) is
//             p_B = (r sinθ cosφ, r cosθ cosφ, r sinφ)                         (eq. 3)
//             so θ is clockwise from forward and φ is up from the x-y plane.
//   enu       local East-North-Up at the platform's geodetic position.
//             p_enu = T_ie(ϑ, ϕ, α) p_B with T_ie = Rz(−ϑ)·Rx(−ϕ)·Ry(−α)           (eq. 6)
//             (yaw ϑ clockwise from north; positive pitch ϕ lowers the forward axis; positive
//             roll α raises the right side).
//   ecef      WGS-84 Earth-centred Earth-fixed. p_ecef = T_ic(L, λ) p_enu + X_i     (eqs. 11–12)
//             with T_ic = [east north up] at latitude L, longitude λ.
// Errors: measured = true + bias + noise for (r, θ, φ) and for the platform's (ϑ, ϕ, α). So
// with the per-radar bias b = (Δr, Δθ, Δφ, Δϑ, Δϕ, Δα) the target is at
//   p(b) = X_i + T_ic T_ie(ϑ − Δϑ, ϕ − Δϕ, α − Δα) p_B(r − Δr, θ − Δθ, φ − Δφ)   (exact)
// and, to first order about a linearisation point b0,
//   p(b) ≈ p(b0) + J (b − b0),   J = T_ic T_ie [M, D']                          (eqs. 2, 7, 13)
// with, evaluated at the corrected values (r, θ, φ, ϕ, α all minus b0):
//   M  = −∂p_B/∂(r, θ, φ)                                                       (eq. 4)
//   D' = [u × p_B, v × p_B, e_y × p_B],  u = (cosϕ sinα, −sinϕ, cosϕ cosα),
//        v = (cosα, 0, −sinα), e_y = (0, 1, 0)                                   (eq. 14)
// (D' = −T_ieᵀ ∂(T_ie p_B)/∂(ϑ, ϕ, α); it agrees with the extracted eq. 14, the garbled eq. 9
// is not used). With b0 = 0 this is exactly the paper's linearisation about the measured
// values; rangekit by default linearises about the current estimate instead (see
// Linearization). Noise enters like the bias: ∂p/∂(noise of r, θ, φ) = T_ic T_ie M.
// Two radars a, b seeing one target: p_a(x_a) = p_b(x_b), so with the 12-vector
// x = [x_a; x_b]
//   z = (p_b(b0_b) − J_b b0_b) − (p_a(b0_a) − J_a b0_a) = H x + G v,  H = [J_a, −J_b]
//   G R Gᵀ = A_a R_a A_aᵀ + A_b R_b A_bᵀ,  A_i = T_ic T_ie M_i                    (eqs. 15–20)
// and the innovation for a state m is ν = g_b(m_b) − g_a(m_a), g_i(m) = p_i(b0) + J_i (m − b0):
// the difference of the two bias-corrected (linearised) points.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>

#include "geo/angles.h"
#include "io/options.h"

namespace rk::registration {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat36 = Eigen::Matrix<double, 3, 6>;
inline constexpr int kRadarBiasDim = 6;
inline constexpr int kBiasDim = 12;
using RadarBias = Eigen::Matrix<double, kRadarBiasDim, 1>;  // (Δr m, Δθ, Δφ, Δϑ, Δϕ, Δα rad)
using BiasVector = Eigen::Matrix<double, kBiasDim, 1>;      // [radar a; radar b]   (eq. 17)
using BiasMatrix = Eigen::Matrix<double, kBiasDim, kBiasDim>;

// Index of each bias inside a radar's 6-block.
enum BiasIndex : int { kBiasRange = 0, kBiasAz = 1, kBiasEl = 2, kBiasYaw = 3, kBiasPitch = 4, kBiasRoll = 5 };
// File-column suffixes in bias order: range_m, az_deg, el_deg, yaw_deg, pitch_deg, roll_deg
// (SPEC.md §2.1 radar biases), and the matching 1-sigma suffixes range_sigma_m, az_sigma_deg, ...
const char* BiasColumnSuffix(int index);
const char* BiasSigmaColumnSuffix(int index);
// Short names: range, az, el, yaw, pitch, roll.
const char* BiasName(int index);
// File units per internal unit: 1 for range (m), 180/π for the angles (rad → deg).
double BiasToFileUnit(int index);

// Platform point of a plot (eq. 3). Range (m), azimuth θ and elevation φ (rad).
Vec3 PlatformPointFromSpherical(double range_m, double az_rad, double el_rad);
// Inverse of eq. 3: (range, azimuth in [0, 2π), elevation) of a platform-frame vector.
Eigen::Vector3d SphericalFromPlatformPoint(const Vec3& p_platform);
// M of eq. 4: −∂p_B/∂(r, θ, φ) (the derivative with respect to the bias, which is subtracted).
Mat3 SphericalBiasJacobian(double range_m, double az_rad, double el_rad);
// T_ie of eq. 6: platform frame → local ENU for yaw ϑ, pitch ϕ, roll α (rad, eq. 6's signs).
Mat3 RotationEnuFromPlatform(double yaw_rad, double pitch_rad, double roll_rad);
// T_ic of eq. 12: local ENU → ECEF axes at geodetic latitude L and longitude λ (rad).
Mat3 RotationEcefFromEnu(double lat_rad, double lon_rad);
// D' of eq. 14: ∂(T_ie(ϑ−Δϑ, ϕ−Δϕ, α−Δα) p_B)/∂(Δϑ, Δϕ, Δα) = T_ie D' at Δ = 0.
Mat3 AttitudeBiasJacobian(const Vec3& p_platform, double pitch_rad, double roll_rad);

// Measurement noise 1-sigma of (r, θ, φ), the same for both radars (the paper's set-up). The angles are
// kept in the options' unit (--sigma-az, --sigma-el: deg; default 0.0087 rad); the model reads radians.
struct MeasurementNoise {
  double sigma_range_m = 50.0;                      // > 0
  double sigma_az_deg = geo::RadToDeg(0.0087);      // in (0, 1 rad)
  double sigma_el_deg = geo::RadToDeg(0.0087);      // in (0, 1 rad)
  double sigma_az_rad() const { return geo::DegToRad(sigma_az_deg); }
  double sigma_el_rad() const { return geo::DegToRad(sigma_el_deg); }

  // --sigma-range, --sigma-az, --sigma-el (io/options.h): CLI flags, Check() and the report keys.
  static const io::OptionTable<MeasurementNoise>& Table();
  bool Check(std::string* why) const { return Table().Check(*this, why); }
};

// A platform's navigation solution at one time (as measured: attitude includes its bias).
struct PlatformPose {
  double lat_rad = 0.0, lon_rad = 0.0, h_m = 0.0;      // WGS-84 geodetic
  double yaw_rad = 0.0, pitch_rad = 0.0, roll_rad = 0.0;  // eq. 6 angles
  Vec3 p_ecef = Vec3::Zero();                             // X_i, from geo::EcefFromGeodetic
  Mat3 R_ecef_enu = Mat3::Identity();                     // T_ic (eq. 12)
};
// Fills p_ecef (WGS-84, geo::EcefFromGeodetic) and R_ecef_enu (eq. 12).
PlatformPose MakePlatformPose(double lat_rad, double lon_rad, double h_m, double yaw_rad, double pitch_rad,
                              double roll_rad);

// One measured plot (r, θ, φ) as read from the file, radians inside.
// has_el false: a 2-D radar's plot (el_deg empty). Its el_rad is then no measurement but the elevation the model
// is linearised about, set per pair by FillMissingElevations (docs/rk-register.md "2-D radars"); it carries no
// noise, and the pair's difference is taken only across the direction that elevation moves the plot.
struct RadarMeasurement {
  double range_m = 0.0, az_rad = 0.0, el_rad = 0.0;
  bool has_el = true;
};

// Exact ECEF point of a plot after removing the radar's bias b (see the header comment).
Vec3 CorrectedEcefPoint(const RadarMeasurement& meas, const PlatformPose& pose, const RadarBias& bias);

// First-order model of CorrectedEcefPoint about b0, and the noise covariance in ECEF.
struct PlotLinearization {
  Vec3 point_ecef = Vec3::Zero();    // p(b0)
  Mat36 J = Mat36::Zero();           // ∂p/∂b at b0 = T_ic T_ie [M, D']
  Mat3 noise_cov = Mat3::Zero();     // A R Aᵀ, A = T_ic T_ie M (= J's first three columns)
  RadarBias b0 = RadarBias::Zero();  // linearisation point
  bool has_el = true;                // false: a 2-D plot (noise_cov without σ_φ; el_direction is a nuisance)
  Vec3 el_direction = Vec3::Zero();  // ∂p/∂φ (m/rad, ECEF) = −J's el column: where an unknown elevation moves it
  // g(m) = p(b0) + J (m − b0): the linearised corrected point for bias m.
  Vec3 PointAt(const RadarBias& m) const { return point_ecef + J * (m - b0); }
};
PlotLinearization LinearizePlot(const RadarMeasurement& meas, const PlatformPose& pose, const RadarBias& b0,
                                const MeasurementNoise& noise);

// The paper's pseudo-measurement z = H x + G v for a pair (plot of radar a, plot of radar b),
// built from the two plot linearisations (eqs. 15–20).
struct PairMeasurement {
  Vec3 z = Vec3::Zero();
  Eigen::Matrix<double, 3, kBiasDim> H = Eigen::Matrix<double, 3, kBiasDim>::Zero();
  Mat3 R = Mat3::Zero();  // G R Gᵀ
};
PairMeasurement MakePairMeasurement(const PlotLinearization& a, const PlotLinearization& b);

// --- 2-D plots (docs/rk-register.md "2-D radars") ---
// A 2-D plot (has_el false) puts the target somewhere on the arc p(φ) of its range and azimuth, φ unknown. The
// pair's difference p_b − p_a is then known only across the arcs' directions ∂p/∂φ: with U (3×d, orthonormal
// columns) spanning the complement of the pair's el_directions, d = 3 − (number of 2-D plots), the reduced
// pseudo-measurement is Uᵀ z = Uᵀ H x + Uᵀ G v, noise Uᵀ G R Gᵀ U (the nuisance elevations eliminated exactly
// to first order: Uᵀ ∂p/∂φ = 0). The el bias of a 2-D plot enters only along ∂p/∂φ, so its column vanishes.

// Elevation (rad) that puts a plot of this radar (pose, bias b) closest to the ECEF point p_ecef: the point's
// elevation atan2(z, h) in the bias-corrected platform frame (h along the plot's corrected azimuth), plus b's el
// bias (CorrectedEcefPoint subtracts it). Unclamped: a point behind the radar gives |φ| > π/2.
double ElevationToward(const Vec3& p_ecef, const RadarMeasurement& meas, const PlatformPose& pose, const RadarBias& b);

// Gives a pair's 2-D plots their elevations (no-op for two 3-D plots). One 2-D plot: toward the other plot's
// corrected point. Two: the closest approach of the two arcs — a's elevation by a 2° grid over [−90°, 90°] and a
// golden-section refinement of |p_a(φ_a) − p_b(ElevationToward(p_a(φ_a)))|, then b's toward a's point.
void FillMissingElevations(RadarMeasurement* a, const PlatformPose& pose_a, const RadarBias& b_a,
                           RadarMeasurement* b, const PlatformPose& pose_b, const RadarBias& b_b);

// Both plots linearised about (b0_a, b0_b) with the 2-D plots' elevations filled at those biases.
std::pair<PlotLinearization, PlotLinearization> LinearizePair(const RadarMeasurement& a, const PlatformPose& pose_a,
                                                              const RadarBias& b0_a, const RadarMeasurement& b,
                                                              const PlatformPose& pose_b, const RadarBias& b0_b,
                                                              const MeasurementNoise& noise);

// The pair's reduced pseudo-measurement (above): ν = Uᵀ (g_b(m_b) − g_a(m_a)), H = Uᵀ [J_a, −J_b] with the 2-D
// plots' el columns set to exactly 0, R = Uᵀ (G R Gᵀ) U; dim = d (3 when both plots have el: U = I).
using MatX3 = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
using VecX3 = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
using MatX3B = Eigen::Matrix<double, Eigen::Dynamic, kBiasDim, 0, 3, kBiasDim>;
struct ReducedPair {
  int dim = 3;
  Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 3, 3> Ut;  // dim × 3
  VecX3 nu;
  MatX3B H;
  MatX3 R;
};
ReducedPair ReducePair(const PlotLinearization& a, const PlotLinearization& b, const BiasVector& m);

// The χ²_d quantile with the probability of χ²_3's `gate_d2_3dof` (gates are given for 3 dof, the pair of two
// 3-D plots): 16.27 (0.999) → 13.82 for d = 2, 10.83 for d = 1. Returns gate_d2_3dof for d = 3.
double GateForDimension(double gate_d2_3dof, int dim);

// Where the model is linearised each step.
enum class Linearization {
  kEstimate,  // about the current bias estimate (default: an extended filter; exact at the estimate)
  kMeasured,  // about the measured values, b0 = 0 (the paper's eqs. 2 and 7 literally)
};
bool ParseLinearization(const std::string& name, Linearization* lin);
std::string LinearizationName(Linearization lin);

}  // namespace rk::registration

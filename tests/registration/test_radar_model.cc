// Measurement model of seed 002 (radar_model.h): frames and signs of SPEC.md §3 on hand-checked
// numbers, every Jacobian against a numerical one, and agreement with the simulator's independent
// implementation (elementary rotations + GeographicLib).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <random>

#include "geo/angles.h"
#include "registration/radar_model.h"
#include "sim/radar_scenario.h"

namespace rk::registration {
namespace {

using geo::DegToRad;

constexpr double kWgs84A = 6378137.0;
// Hand-checked points: exact up to the trigonometry's rounding at 6.4e6 m.
constexpr double kHandTolM = 1e-6;
// Rotation matrices built two ways: rounding only.
constexpr double kRotationTol = 1e-14;
// Central differences: step and relative tolerance (truncation error ∝ h², rounding ∝ 1/h).
constexpr double kStepM = 1e-3, kStepRad = 1e-7;
constexpr double kJacobianRelTol = 1e-6;
// Round trip through the simulator's independent SPEC.md §3 code and back (ranges up to 3000 km).
constexpr double kRoundTripTolM = 1e-6;

Mat3 SpecRotation(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(-roll, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

PlatformPose PoseAtEquator(double yaw_deg, double pitch_deg, double roll_deg) {
  return MakePlatformPose(0, 0, 0, DegToRad(yaw_deg), DegToRad(pitch_deg), DegToRad(roll_deg));
}

Vec3 Point(const PlatformPose& pose, double r, double az_deg, double el_deg) {
  return CorrectedEcefPoint({r, DegToRad(az_deg), DegToRad(el_deg)}, pose, RadarBias::Zero());
}

TEST(RadarModel, Eq6IsSpecRotationZXY) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-4.0, 4.0);  // includes pitch beyond ±90°
  for (int i = 0; i < 200; ++i) {
    const double y = u(rng), p = u(rng), r = u(rng);
    EXPECT_LT((RotationEnuFromPlatform(y, p, r) - SpecRotation(y, p, r)).cwiseAbs().maxCoeff(), kRotationTol);
  }
}

TEST(RadarModel, Eq12IsGeographicLibEnuFrame) {
  for (double lat : {-60.0, 0.0, 25.0, 89.0}) {
    for (double lon : {-170.0, 0.0, 110.0}) {
      std::vector<double> M(9);
      double X, Y, Z;
      GeographicLib::Geocentric::WGS84().Forward(lat, lon, 1000.0, X, Y, Z, M);
      const Mat3 T = RotationEcefFromEnu(DegToRad(lat), DegToRad(lon));
      for (int k = 0; k < 9; ++k) EXPECT_NEAR(T(k / 3, k % 3), M[k], kRotationTol) << lat << " " << lon;
    }
  }
}

// Platform at lat 0, lon 0, h 0: ECEF (a, 0, 0); east = +Y, north = +Z, up = +X.
TEST(RadarModel, HandCheckedSignsAtEquator) {
  const double c30 = std::sqrt(3.0) / 2;
  // Forward axis with yaw 90°: east.
  EXPECT_LT((Point(PoseAtEquator(90, 0, 0), 1000, 0, 0) - Vec3(kWgs84A, 1000, 0)).norm(), kHandTolM);
  // θ clockwise from forward: 90° is the right side; with yaw 0 that is east.
  EXPECT_LT((Point(PoseAtEquator(0, 0, 0), 1000, 90, 0) - Vec3(kWgs84A, 1000, 0)).norm(), kHandTolM);
  // Elevation up: (0, r cos30, r sin30) ENU.
  EXPECT_LT((Point(PoseAtEquator(0, 0, 0), 1000, 0, 30) - Vec3(kWgs84A + 500, 0, 1000 * c30)).norm(), kHandTolM);
  // Positive pitch lowers the forward axis: ENU (0, cos30, −sin30)·r.
  EXPECT_LT((Point(PoseAtEquator(0, 30, 0), 1000, 0, 0) - Vec3(kWgs84A - 500, 0, 1000 * c30)).norm(), kHandTolM);
  // Positive roll raises the right side: ENU (cos30, 0, sin30)·r for θ = 90°.
  EXPECT_LT((Point(PoseAtEquator(0, 0, 30), 1000, 90, 0) - Vec3(kWgs84A + 500, 1000 * c30, 0)).norm(), kHandTolM);
  // Yaw then pitch: yaw 90°, pitch 30° → forward ENU (cos30, 0, −sin30).
  EXPECT_LT((Point(PoseAtEquator(90, 30, 0), 1000, 0, 0) - Vec3(kWgs84A - 500, 1000 * c30, 0)).norm(), kHandTolM);
  // Azimuth across 0/360: 359.9° and −0.1° are the same direction.
  EXPECT_LT((Point(PoseAtEquator(10, 2, 3), 5000, 359.9, 1) - Point(PoseAtEquator(10, 2, 3), 5000, -0.1, 1)).norm(),
            kHandTolM);
}

// measured = true + bias: removing the bias from measured values gives the true point.
TEST(RadarModel, BiasIsSubtractedFromMeasuredValues) {
  const RadarBias b = (RadarBias() << 1200, 0.0105, 0.0035, 0.0105, -0.0035, 0.0035).finished();
  const double r = 30000, az = DegToRad(350), el = DegToRad(12), yaw = DegToRad(359), pitch = 0.2, roll = -0.1;
  const PlatformPose true_pose = MakePlatformPose(DegToRad(25), DegToRad(110), 8000, yaw, pitch, roll);
  const Vec3 truth = CorrectedEcefPoint({r, az, el}, true_pose, RadarBias::Zero());
  const PlatformPose measured_pose =
      MakePlatformPose(DegToRad(25), DegToRad(110), 8000, yaw + b[3], pitch + b[4], roll + b[5]);
  const Vec3 corrected = CorrectedEcefPoint({r + b[0], az + b[1], el + b[2]}, measured_pose, b);
  EXPECT_LT((corrected - truth).norm(), kHandTolM);
  // Not removing it misplaces the point by hundreds of metres (the test can fail).
  EXPECT_GT((CorrectedEcefPoint({r + b[0], az + b[1], el + b[2]}, measured_pose, RadarBias::Zero()) - truth).norm(),
            500.0);
}

TEST(RadarModel, SphericalRoundTrip) {
  for (double az : {0.0, 1.0, 3.1, 4.0, 6.28}) {
    for (double el : {-1.2, 0.0, 0.7}) {
      const Eigen::Vector3d s = SphericalFromPlatformPoint(PlatformPointFromSpherical(1234.5, az, el));
      EXPECT_NEAR(s[0], 1234.5, 1e-9);
      EXPECT_NEAR(geo::AngleDiff(s[1], az), 0.0, 1e-12);
      EXPECT_NEAR(s[2], el, 1e-12);
    }
  }
}

// Eq. 4: M = −∂p_B/∂(r, θ, φ).
TEST(RadarModel, MIsMinusTheSphericalJacobian) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ur(1e3, 3e6), ua(-7, 7), ue(-1.5, 1.5);
  for (int t = 0; t < 50; ++t) {
    const double r = ur(rng), az = ua(rng), el = ue(rng);
    const Mat3 M = SphericalBiasJacobian(r, az, el);
    const double h[3] = {kStepM, kStepRad, kStepRad};
    for (int c = 0; c < 3; ++c) {
      double p[3] = {r, az, el}, q[3] = {r, az, el};
      p[c] -= h[c];  // the bias is subtracted: increasing it moves the argument down
      q[c] += h[c];
      const Vec3 num = (PlatformPointFromSpherical(p[0], p[1], p[2]) - PlatformPointFromSpherical(q[0], q[1], q[2])) /
                       (2 * h[c]);
      EXPECT_LT((M.col(c) - num).norm(), kJacobianRelTol * std::max(1.0, num.norm())) << "col " << c;
    }
  }
}

// Eq. 14: ∂(T_ie(ϑ−Δϑ, ϕ−Δϕ, α−Δα) p)/∂Δ = T_ie D'.
TEST(RadarModel, DPrimeMatchesNumericalAttitudeJacobian) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ua(-3.5, 3.5), up(-5e4, 5e4);
  for (int t = 0; t < 50; ++t) {
    const double y = ua(rng), p = ua(rng), r = ua(rng);
    const Vec3 x(up(rng), up(rng), up(rng));
    const Mat3 TD = RotationEnuFromPlatform(y, p, r) * AttitudeBiasJacobian(x, p, r);
    for (int c = 0; c < 3; ++c) {
      double lo[3] = {y, p, r}, hi[3] = {y, p, r};
      lo[c] -= kStepRad;
      hi[c] += kStepRad;
      const Vec3 num = (RotationEnuFromPlatform(lo[0], lo[1], lo[2]) * x - RotationEnuFromPlatform(hi[0], hi[1], hi[2]) * x) /
                       (2 * kStepRad);
      EXPECT_LT((TD.col(c) - num).norm(), kJacobianRelTol * std::max(1.0, num.norm())) << "col " << c;
    }
  }
}

// LinearizePlot's J (= T_ic T_ie [M, D'] at the corrected values) against central differences of
// the exact CorrectedEcefPoint, at the paper's point (b0 = 0) and at a non-zero bias.
TEST(RadarModel, PlotJacobianMatchesNumerical) {
  const MeasurementNoise noise;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> ua(-3.5, 3.5), ur(2e4, 2e6), ue(-1.2, 1.2), ub(-0.02, 0.02);
  for (int t = 0; t < 40; ++t) {
    const RadarMeasurement m{ur(rng), ua(rng), ue(rng)};
    const PlatformPose pose = MakePlatformPose(DegToRad(25 + ub(rng) * 100), DegToRad(110 + ub(rng) * 100), 1e4,
                                               ua(rng), ua(rng), ua(rng));
    RadarBias b0 = RadarBias::Zero();
    if (t % 2) b0 << 1000 + 10000 * ub(rng), ub(rng), ub(rng), ub(rng), ub(rng), ub(rng);
    const PlotLinearization lin = LinearizePlot(m, pose, b0, noise);
    EXPECT_LT((lin.point_ecef - CorrectedEcefPoint(m, pose, b0)).norm(), 1e-6);
    for (int c = 0; c < kRadarBiasDim; ++c) {
      const double h = c == 0 ? kStepM : kStepRad;
      RadarBias lo = b0, hi = b0;
      lo[c] -= h;
      hi[c] += h;
      const Vec3 num = (CorrectedEcefPoint(m, pose, hi) - CorrectedEcefPoint(m, pose, lo)) / (2 * h);
      EXPECT_LT((lin.J.col(c) - num).norm(), kJacobianRelTol * std::max(1.0, num.norm())) << "t " << t << " col " << c;
    }
    // Noise covariance = A R Aᵀ with A the first three columns.
    const Mat3 A = lin.J.leftCols<3>();
    const Vec3 var(noise.sigma_range_m * noise.sigma_range_m, noise.sigma_az_rad() * noise.sigma_az_rad(),
                   noise.sigma_el_rad() * noise.sigma_el_rad());
    EXPECT_LT((lin.noise_cov - A * var.asDiagonal() * A.transpose()).norm(), 1e-9 * lin.noise_cov.norm());
  }
}

// First order: the linearisation error of a 0.01 rad / 1 km bias is second order (metres at
// 100 km), and vanishes when linearising at the bias itself.
TEST(RadarModel, LinearisationErrorIsSecondOrder) {
  const MeasurementNoise noise;
  const RadarMeasurement m{1e5, 0.7, 0.2};
  const PlatformPose pose = MakePlatformPose(DegToRad(25), DegToRad(110), 2e4, 0.3, 0.2, 0.1);
  const RadarBias b = (RadarBias() << 1200, 0.0105, 0.0035, 0.0105, 0.0035, 0.0035).finished();
  const Vec3 exact = CorrectedEcefPoint(m, pose, b);
  const PlotLinearization at0 = LinearizePlot(m, pose, RadarBias::Zero(), noise);
  const double err_paper = (at0.PointAt(b) - exact).norm();
  EXPECT_GT(err_paper, 1.0);     // measurable: why rangekit relinearises at the estimate
  EXPECT_LT(err_paper, 100.0);   // but second order: |b|² r ≈ 1e-4 · 1e5 plus Δr Δθ terms
  const PlotLinearization atb = LinearizePlot(m, pose, b, noise);
  EXPECT_LT((atb.PointAt(b) - exact).norm(), 1e-6);
  // Halving the bias quarters the error (second order).
  const double err_half = (at0.PointAt(0.5 * b) - CorrectedEcefPoint(m, pose, 0.5 * b)).norm();
  EXPECT_NEAR(err_half / err_paper, 0.25, 0.03);
}

// The pair pseudo-measurement z = H x + G v is exact at the linearisation point: for noise-free
// plots of one target linearised at the true biases, z = H x_true.
TEST(RadarModel, PairMeasurementExactAtTruth) {
  const MeasurementNoise noise;
  const RadarBias ba = (RadarBias() << 1200, 0.0105, 0.0035, 0.0105, 0.0035, 0.0035).finished();
  const RadarBias bb = (RadarBias() << 1000, 0.0087, 0.0047, 0.0087, 0.0047, 0.0037).finished();
  const Eigen::Vector3d target(10000, 1000, 50000), pa(-10000, -20000, 40000), pb(20000, 20000, 20000);
  const Eigen::Vector3d att_a(0.3, 0.4, 0.2), att_b(-0.2, 0.1, 0.05);
  const double lat0 = 25, lon0 = 110, h0 = 0;
  GeographicLib::LocalCartesian lc(lat0, lon0, h0);
  auto pose_of = [&](const Eigen::Vector3d& enu, const Eigen::Vector3d& att, const RadarBias& b) {
    double lat, lon, h;
    lc.Reverse(enu.x(), enu.y(), enu.z(), lat, lon, h);
    return MakePlatformPose(DegToRad(lat), DegToRad(lon), h, att[0] + b[3], att[1] + b[4], att[2] + b[5]);
  };
  const Eigen::Vector3d ma = sim::TrueRadarMeasurement(target, pa, att_a, lat0, lon0, h0);
  const Eigen::Vector3d mb = sim::TrueRadarMeasurement(target, pb, att_b, lat0, lon0, h0);
  const RadarMeasurement meas_a{ma[0] + ba[0], ma[1] + ba[1], ma[2] + ba[2]};
  const RadarMeasurement meas_b{mb[0] + bb[0], mb[1] + bb[1], mb[2] + bb[2]};
  const PlatformPose pose_a = pose_of(pa, att_a, ba), pose_b = pose_of(pb, att_b, bb);
  // Both corrected points are the target.
  double X, Y, Z, lat, lon, h;
  lc.Reverse(target.x(), target.y(), target.z(), lat, lon, h);
  GeographicLib::Geocentric::WGS84().Forward(lat, lon, h, X, Y, Z);
  EXPECT_LT((CorrectedEcefPoint(meas_a, pose_a, ba) - Vec3(X, Y, Z)).norm(), kRoundTripTolM);
  EXPECT_LT((CorrectedEcefPoint(meas_b, pose_b, bb) - Vec3(X, Y, Z)).norm(), kRoundTripTolM);
  const PairMeasurement pm = MakePairMeasurement(LinearizePlot(meas_a, pose_a, ba, noise),
                                                 LinearizePlot(meas_b, pose_b, bb, noise));
  BiasVector x;
  x << ba, bb;
  EXPECT_LT((pm.z - pm.H * x).norm(), kRoundTripTolM);
  // With the paper's linearisation about the measured values, z − H x is the second-order remainder.
  const PairMeasurement paper = MakePairMeasurement(LinearizePlot(meas_a, pose_a, RadarBias::Zero(), noise),
                                                    LinearizePlot(meas_b, pose_b, RadarBias::Zero(), noise));
  EXPECT_GT((paper.z - paper.H * x).norm(), 1.0);
  EXPECT_LT((paper.z - paper.H * x).norm(), 200.0);
}

TEST(RadarModel, ParseNames) {
  Linearization lin;
  EXPECT_TRUE(ParseLinearization("measured", &lin));
  EXPECT_EQ(lin, Linearization::kMeasured);
  EXPECT_FALSE(ParseLinearization("paper", &lin));
  EXPECT_STREQ(BiasColumnSuffix(kBiasPitch), "pitch_deg");
  EXPECT_STREQ(BiasSigmaColumnSuffix(kBiasRange), "range_sigma_m");
}

}  // namespace
}  // namespace rk::registration

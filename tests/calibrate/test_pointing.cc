// rk-calibrate pointing's solver: the residual's projection equals the camera model's, its automatic
// Jacobian equals a numerical one, and a simulated session's truth is recovered within its stated σ.
#include <gtest/gtest.h>

#include <ceres/ceres.h>

#include "calibrate/pointing_cost.h"
#include "test_pointing_common.h"

namespace rk::calibrate {
namespace {

using testing::InputsOf;
using testing::TruthOf;

constexpr double kNumericStep = 1e-7;       // rad (or δf, s): truncation ~1e-14 rel., rounding ~1e-9 px / 1e-7
constexpr double kJacobianRelTol = 1e-4;    // relative: slopes are O(1e4–1e7) px per unit (σ-scaled residuals)
constexpr double kAzSumTolDeg = 0.001;      // 3.6″: az_offset + mount yaw from 10 low landmarks
constexpr double kTruthSigmas = 5.0;        // a recovered parameter within 5σ of the truth (one fixed seed)

sim::PointingSimOptions SmallSession(std::uint64_t seed) {
  sim::PointingSimOptions o;
  o.seed = seed;
  o.landmarks = 10;
  o.stars = 20;
  o.dwell_s = 1.0;
  o.frame_rate_hz = 5.0;
  o.validation_s = 0.0;
  return o;
}

// A session whose focal length and latency are exact: what the default --estimate assumes.
sim::PointingSimOptions ExactCameraSession(std::uint64_t seed) {
  sim::PointingSimOptions o = SmallSession(seed);
  o.focal_error = 0.0;
  o.time_offset_s = 0.0;
  return o;
}

TEST(PointingCost, AutomaticJacobianMatchesNumerical) {
  const sim::PointingSession s = sim::SimulatePointingSession(SmallSession(3));
  const testing::SessionInputs in = InputsOf(s);
  PointingCalibrationOptions opt;
  const PointingObservations obs = testing::BuilderOf(in, opt, 0.05)(0.01);
  camera::CameraModel cam = s.camera_nominal;
  cam.distortion = {-0.05, 0.01, 0, 0, 0};
  std::array<double, kNumPointingParams> x = TruthOf(s);
  Eigen::Vector2d c(1e-5, -2e-5), t(3e-6, 1e-6);
  for (std::size_t i = 0; i < obs.obs.size(); i += obs.obs.size() / 7) {
    const PointingPixelCost f(obs.obs[i], cam.ToIntrinsics(), obs.tau0_s);
    ceres::AutoDiffCostFunction<PointingPixelCost, 2, kNumPointingParams, 2, 2> ad(new PointingPixelCost(f));
    const double* params[3] = {x.data(), c.data(), t.data()};
    Eigen::Vector2d r;
    Eigen::Matrix<double, 2, kNumPointingParams, Eigen::RowMajor> jx;
    Eigen::Matrix<double, 2, 2, Eigen::RowMajor> jc, jt;
    double* jac[3] = {jx.data(), jc.data(), jt.data()};
    ASSERT_TRUE(ad.Evaluate(params, r.data(), jac));
    // Central differences of the double functor, block by block.
    double* blocks[3] = {x.data(), c.data(), t.data()};
    const int sizes[3] = {kNumPointingParams, 2, 2};
    double* analytic[3] = {jx.data(), jc.data(), jt.data()};
    for (int b = 0; b < 3; ++b) {
      for (int k = 0; k < sizes[b]; ++k) {
        const double h = kNumericStep, keep = blocks[b][k];
        Eigen::Vector2d rp, rm;
        blocks[b][k] = keep + h;
        ASSERT_TRUE(f(x.data(), c.data(), t.data(), rp.data()));
        blocks[b][k] = keep - h;
        ASSERT_TRUE(f(x.data(), c.data(), t.data(), rm.data()));
        blocks[b][k] = keep;
        for (int row = 0; row < 2; ++row) {
          const double numeric = (rp[row] - rm[row]) / (2 * h), a = analytic[b][row * sizes[b] + k];
          EXPECT_NEAR(a, numeric, kJacobianRelTol * std::max(1.0, std::abs(a))) << "block " << b << " param " << k;
        }
      }
    }
  }
}

TEST(PointingSolve, RecoversTruthOfASimulatedSession) {
  const sim::PointingSession s = sim::SimulatePointingSession(SmallSession(7));
  const testing::SessionInputs in = InputsOf(s);
  PointingCalibrationOptions opt;
  EstimateSet est = DefaultEstimate();
  est[kParamFocal] = est[kParamTimeOffset] = true;
  const PointingSolution sol = SolvePointing(testing::BuilderOf(in, opt, 0.05), s.camera_nominal, est, opt);
  const auto truth = TruthOf(s);
  for (int k = 0; k < kNumPointingParams; ++k) {
    ASSERT_TRUE(sol.sigma[static_cast<std::size_t>(k)].has_value()) << PointingParamName(k);
    const double err = k == kParamAzOffset ? geo::WrapPi(sol.x[static_cast<std::size_t>(k)] - truth[static_cast<std::size_t>(k)])
                                           : sol.x[static_cast<std::size_t>(k)] - truth[static_cast<std::size_t>(k)];
    EXPECT_LT(std::abs(err), kTruthSigmas * *sol.sigma[static_cast<std::size_t>(k)])
        << PointingParamName(k) << " error " << err << " sigma " << *sol.sigma[static_cast<std::size_t>(k)];
  }
  EXPECT_EQ(sol.rejected, 0u);
  EXPECT_LT(sol.chi2_per_dof, 1.5);
}

TEST(PointingSolve, AzimuthZeroAnywhereIsFound) {
  for (double az : {-170.0, 3.0, 250.0}) {
    sim::PointingSimOptions o = ExactCameraSession(11);
    o.az_offset_deg = az;
    o.stars = 0;
    const sim::PointingSession s = sim::SimulatePointingSession(o);
    const testing::SessionInputs in = InputsOf(s);
    PointingCalibrationOptions opt;
    const PointingSolution sol = SolvePointing(testing::BuilderOf(in, opt, 0.05), s.camera_nominal, DefaultEstimate(), opt);
    // Landmarks near the horizon only: the azimuth zero and the mount yaw are one quantity there (the solve
    // warns so); their sum is what must be found.
    const double sum = sol.x[kParamAzOffset] + sol.x[kParamMountYaw];
    const double truth = s.truth.az_offset_rad + s.camera_truth.mount_yaw_rad;
    EXPECT_NEAR(geo::RadToDeg(geo::WrapPi(sum - truth)), 0.0, kAzSumTolDeg) << az;
  }
}

TEST(PointingSolve, OutlierIsRejectedAndNamed) {
  const sim::PointingSession s = sim::SimulatePointingSession(ExactCameraSession(5));
  testing::SessionInputs in = InputsOf(s);
  in.points.rows[40].px += Eigen::Vector2d(25.0, -10.0);
  PointingCalibrationOptions opt;
  const PointingSolution sol = SolvePointing(testing::BuilderOf(in, opt, 0.05), s.camera_nominal, DefaultEstimate(), opt);
  EXPECT_EQ(sol.rejected, 1u);
  EXPECT_TRUE(sol.residuals[40].rejected);
}

TEST(PointingSolve, HorizonOnlyLandmarksWarnAboutAzOffsetAndYaw) {
  sim::PointingSimOptions o = ExactCameraSession(9);
  o.stars = 0;
  o.landmark_min_el_deg = 0.0;
  o.landmark_max_el_deg = 0.5;
  const sim::PointingSession s = sim::SimulatePointingSession(o);
  const testing::SessionInputs in = InputsOf(s);
  PointingCalibrationOptions opt;
  const PointingSolution sol = SolvePointing(testing::BuilderOf(in, opt, 0.05), s.camera_nominal, DefaultEstimate(), opt);
  bool named = false;
  for (const std::string& w : sol.warnings) named |= w.find("az_offset and mount_yaw") != std::string::npos;
  EXPECT_TRUE(named);
}

TEST(PointingSolve, TooFewObservationsIsAProcessingError) {
  sim::PointingSimOptions o = SmallSession(2);
  const sim::PointingSession s = sim::SimulatePointingSession(o);
  testing::SessionInputs in = InputsOf(s);
  in.points.rows.resize(3);
  PointingCalibrationOptions opt;
  EXPECT_THROW(SolvePointing(testing::BuilderOf(in, opt, 0.05), s.camera_nominal, DefaultEstimate(), opt), rk::Error);
}

}  // namespace
}  // namespace rk::calibrate

// The "locate" error-budget model (analysis/budget_locate.h): its autodiff Jacobian against central
// differences, and the pointing model's and the mount's calibrated σ as sources.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/budget.h"
#include "test_locate_model.h"

namespace rk::analysis {
namespace {

TEST(Budget, LocateJacobianMatchesCentralDifferences) {
  for (double az : {0.0, 123.0, 359.9}) {
    for (double el : {-5.0, 30.0, 80.0}) {
      const auto m = Locate(az, el, 2100.0, 300.0);
      Eigen::MatrixXd Jn;
      ASSERT_TRUE(NumericalJacobian(*m, m->NominalInputs(), &Jn));
      const Eigen::MatrixXd J = m->Jacobian();
      EXPECT_LT((J - Jn).cwiseAbs().maxCoeff(), kJacobianRel * Jn.cwiseAbs().maxCoeff()) << az << " " << el;
      // Azimuth error of a boresight azimuth error is exactly 1 for the image centre... roughly here.
      EXPECT_NEAR(J(0, 0), 1.0, 0.05);
    }
  }
}

// An azimuth offset turns every line of sight about the turret's (tilted) vertical axis: ∂az/∂az_offset is 1 up
// to the tilts' second order, so the az_offset source's share of the azimuth σ is its own σ.
constexpr double kOffsetShareRel = 1e-3;
// Monte Carlo σ against the Jacobian's at 20 000 draws: standard error 0.5 %, linear model.
constexpr double kMonteCarloRel = 0.03;

TEST(Budget, LocateTakesThePointingModelsAndTheMountsCalibratedSigma) {
  const auto m = Locate(359.9, 20.0, 1800.0, 400.0);
  camera::CameraModel cam = DistortedCamera();
  cam.calibration = {{"sigma", {{"mount_deg", {{"yaw", 0.01}, {"roll", 0.02}}}}}};
  const std::vector<BudgetSource> sources =
      LocateCalibrationSources(*m, cam, TiltedTurret(), "pointing.json", "budget.json");
  // Three pointing terms carry a σ (el_axis_tilt was not estimated), two mount angles.
  ASSERT_EQ(sources.size(), 5u);
  EXPECT_EQ(sources[0].name, "pointing model az_offset");
  EXPECT_EQ(m->inputs()[sources[0].inputs[0]].name, "az_offset");
  EXPECT_EQ(sources[3].name, "camera mount_yaw");
  EXPECT_NE(sources[0].given.find("pointing.json"), std::string::npos);
  BudgetOptions opt;
  const BudgetResult r = RunBudget(*m, sources, opt);
  EXPECT_NEAR(r.outputs[0].by_source[0], sources[0].sigma_si, kOffsetShareRel * sources[0].sigma_si);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_GT(r.outputs[k].sigma_jacobian, 0.0);
    EXPECT_NEAR(r.outputs[k].sigma_mc, r.outputs[k].sigma_jacobian, kMonteCarloRel * r.outputs[k].sigma_jacobian);
  }
  // A pointing model without σ and a camera without a calibration add nothing.
  EXPECT_TRUE(LocateCalibrationSources(*m, DistortedCamera(), camera::PointingModel(), "p", "b").empty());
}

}  // namespace
}  // namespace rk::analysis

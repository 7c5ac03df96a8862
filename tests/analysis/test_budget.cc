// Error-budget engine (analysis/budget.h) with the "locate" model: autodiff Jacobian against central
// differences, Monte Carlo against the Jacobian in the linear regime, source parsing and its errors.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/budget.h"
#include "analysis/budget_locate.h"
#include "camera/camera_model.h"
#include "geo/angles.h"
#include "io/error.h"

namespace rk::analysis {
namespace {

// Central differences with steps 1e-7 rad / 1e-4 px / 1e-6 m have truncation + rounding ~1e-8 relative.
constexpr double kJacobianRel = 1e-6;
// 20000 draws: σ's standard error is 0.5 %; 3 standard errors plus nonlinearity of 1-arcsec-scale errors.
constexpr double kMcRel = 0.02;

camera::CameraModel DistortedCamera() {
  camera::CameraModel c = camera::DefaultCamera();
  c.distortion = {-0.08, 0.02, 0.001, -0.0005, 0.0};
  c.mount_yaw_rad = geo::DegToRad(0.3);
  c.mount_pitch_rad = geo::DegToRad(-0.2);
  c.mount_roll_rad = geo::DegToRad(0.5);
  return c;
}

std::unique_ptr<BudgetModel> Locate(double az_deg, double el_deg, double x, double y) {
  const io::Json nominal = {{"boresight_az_deg", az_deg}, {"boresight_el_deg", el_deg}, {"x_px", x}, {"y_px", y},
                            {"range_m", 850.0}};
  return MakeLocateBudgetModel(nominal, DistortedCamera(), "budget.json");
}

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

TEST(Budget, MonteCarloAgreesWithJacobianForSmallErrors) {
  const auto m = Locate(359.99, 45.0, 1500.0, 900.0);  // azimuth output crosses north
  const io::Json sources = io::Json::parse(R"([
      {"name": "encoder", "applies_to": "boresight", "sigma_arcsec": 2},
      {"name": "centroid", "applies_to": "pixels", "sigma_px": 0.05},
      {"name": "rangefinder", "applies_to": "range", "sigma_mm": 2, "distribution": "uniform"}])");
  const auto src = ParseBudgetSources(sources, *m, "budget.json");
  ASSERT_EQ(src.size(), 3u);
  EXPECT_NEAR(src[2].sigma_si, 0.002, 1e-15);
  BudgetOptions opt;
  opt.samples = 20000;
  const BudgetResult r = RunBudget(*m, src, opt);
  EXPECT_EQ(r.failed, 0);
  EXPECT_LT(r.jacobian_check_max_rel, kJacobianRel);
  for (std::size_t k = 0; k < m->outputs().size(); ++k) {
    const BudgetOutputResult& o = r.outputs[k];
    EXPECT_NEAR(o.sigma_mc / o.sigma_jacobian, 1.0, kMcRel) << m->outputs()[k].name;
    // Per-source shares add in quadrature to the total.
    double q = 0;
    for (double s : o.by_source) q += s * s;
    EXPECT_NEAR(std::sqrt(q), o.sigma_jacobian, 1e-12 * o.sigma_jacobian);
  }
  // Same seed, same figures.
  const BudgetResult r2 = RunBudget(*m, src, opt);
  EXPECT_EQ(r.outputs[0].sigma_mc, r2.outputs[0].sigma_mc);
  const io::Json j = BudgetResultToJson(*m, src, opt, r);
  EXPECT_EQ(j["outputs"][0]["name"], "az");
  EXPECT_NEAR(j["model_inputs"][0]["sigma_arcmin"].get<double>(), 2.0 / 60.0, 1e-12);
  EXPECT_NE(FormatBudgetTable(*m, src, r).find("sigma_jac"), std::string::npos);
}

TEST(Budget, SourceErrorsNameTheFile) {
  const auto m = Locate(10.0, 10.0, 1000.0, 1000.0);
  auto expect_error = [&](const char* text, const char* what) {
    try {
      ParseBudgetSources(io::Json::parse(text), *m, "b.json");
      ADD_FAILURE() << "no error for " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kInvalidData);
      EXPECT_NE(std::string(e.what()).find("b.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_error(R"([{"name": "x", "applies_to": "wing", "sigma_px": 1}])", "unknown input 'wing'");
  expect_error(R"([{"name": "x", "applies_to": "boresight", "sigma_px": 1}])", "cannot apply");
  expect_error(R"([{"name": "x", "applies_to": "range", "sigma_m": 1, "sigma_mm": 2}])", "exactly one");
  expect_error(R"([{"name": "x", "applies_to": "range", "sigma_m": -1}])", ">= 0");
  expect_error(R"([{"name": "x", "applies_to": "range", "half_width_m": 1}])", "uniform");
  expect_error(R"([])", "non-empty");
}

}  // namespace
}  // namespace rk::analysis

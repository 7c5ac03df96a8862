// The error-budget engine (analysis/budget.h), run on the "locate" model: Monte Carlo against the Jacobian in
// the linear regime, source parsing and its errors.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/budget.h"
#include "io/error.h"
#include "test_locate_model.h"

namespace rk::analysis {
namespace {

// 20000 draws: σ's standard error is 0.5 %; 3 standard errors plus nonlinearity of 1-arcsec-scale errors.
constexpr double kMcRel = 0.02;

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

// numeric::LevenbergMarquardt on a small curve fit with a known answer: convergence, the problem's
// Converged test, and the optional AtMinimum test (stops before a step at a minimum, counts no tries).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "numeric/levenberg_marquardt.h"

namespace rk::numeric {
namespace {

// y = a · exp(b · t) sampled without noise at 20 points; parameters (a, b).
struct ExpFit {
  using Vec = Eigen::Vector2d;
  using Mat = Eigen::Matrix2d;
  Vec x, candidate;
  int evaluations = 0;
  double truth_a = 2.0, truth_b = -0.7;
  double at_minimum_tol = -1.0;  // < 0: AtMinimum never stops
  int at_minimum_calls = 0;

  double Cost(const Vec& p) {
    ++evaluations;
    double c = 0.0;
    for (int i = 0; i < 20; ++i) {
      const double t = 0.1 * i, r = p(0) * std::exp(p(1) * t) - truth_a * std::exp(truth_b * t);
      c += r * r;
    }
    return c;
  }
  bool Linearize(Mat* H, Vec* g) const {
    H->setZero();
    g->setZero();
    for (int i = 0; i < 20; ++i) {
      const double t = 0.1 * i, e = std::exp(x(1) * t);
      const double r = x(0) * e - truth_a * std::exp(truth_b * t);
      const Vec j(e, x(0) * t * e);
      *H += j * j.transpose();
      *g += j * r;
    }
    return true;
  }
  bool TryStep(const Vec& step, double* cost) {
    candidate = x + step;
    *cost = Cost(candidate);
    return true;
  }
  void Accept() { x = candidate; }
  bool Converged(const Vec& step, double, double) const { return step.norm() < 1e-12; }
};

struct ExpFitStoppingAtMinimum : ExpFit {
  bool AtMinimum(const Mat& H, const Vec& g, double) {
    ++at_minimum_calls;
    return g.dot(H.ldlt().solve(g)) <= at_minimum_tol;
  }
};

constexpr double kAnswerTol = 1e-9;  // noise-free data: the minimum is the truth to rounding

template <class Fit>
LmSummary Solve(Fit& fit, const Eigen::Vector2d& start, int max_iterations) {
  fit.x = start;
  Eigen::Matrix2d H;
  Eigen::Vector2d g;
  fit.Linearize(&H, &g);
  const LmDamping damping{.initial = 1e-3, .linearize_at_solution = false};
  return LevenbergMarquardt<2>(fit, fit.Cost(fit.x), damping, max_iterations, &H, &g);
}

TEST(LevenbergMarquardt, ConvergesToTheTruthOfANoiseFreeCurve) {
  ExpFit fit;
  const LmSummary s = Solve(fit, Eigen::Vector2d(1.0, 0.0), 100);
  EXPECT_EQ(s.status, LmStatus::kConverged);
  EXPECT_NEAR(fit.x(0), fit.truth_a, kAnswerTol);
  EXPECT_NEAR(fit.x(1), fit.truth_b, kAnswerTol);
  EXPECT_LT(s.cost, 1e-20);
}

TEST(LevenbergMarquardt, IterationLimitIsReported) {
  ExpFit fit;
  const LmSummary s = Solve(fit, Eigen::Vector2d(1.0, 0.0), 1);
  EXPECT_EQ(s.status, LmStatus::kMaxIterations);
  EXPECT_EQ(s.iterations, 1);
}

TEST(LevenbergMarquardt, AtMinimumStopsAtTheStartWithoutATry) {
  ExpFitStoppingAtMinimum fit;
  fit.at_minimum_tol = 1e-12;
  const LmSummary s = Solve(fit, Eigen::Vector2d(fit.truth_a, fit.truth_b), 100);
  EXPECT_EQ(s.status, LmStatus::kConverged);
  EXPECT_EQ(s.iterations, 0);
  EXPECT_EQ(fit.evaluations, 1);  // the start's cost only: no damped try
  EXPECT_EQ(fit.at_minimum_calls, 1);
}

TEST(LevenbergMarquardt, AtMinimumSavesTheTriesThatFindNoDescent) {
  // Without AtMinimum the loop ends when the Converged test passes or no damped try lowers the cost; with
  // it, as soon as the predicted decrease is below the tolerance: the same answer with fewer evaluations.
  ExpFit plain;
  Solve(plain, Eigen::Vector2d(1.0, 0.0), 100);
  ExpFitStoppingAtMinimum stopping;
  stopping.at_minimum_tol = 1e-24;
  const LmSummary s = Solve(stopping, Eigen::Vector2d(1.0, 0.0), 100);
  EXPECT_EQ(s.status, LmStatus::kConverged);
  EXPECT_NEAR(stopping.x(0), stopping.truth_a, kAnswerTol);
  EXPECT_NEAR(stopping.x(1), stopping.truth_b, kAnswerTol);
  EXPECT_GT(stopping.at_minimum_calls, 1);
  EXPECT_LT(stopping.evaluations, plain.evaluations);
}

}  // namespace
}  // namespace rk::numeric

// The one Levenberg–Marquardt loop of rangekit (Marquardt 1963): small dense problems of N unknowns
// whose normal equations the caller builds (JᵀJ, Jᵀr), with Marquardt's diagonal scaling. Used by the
// marker fit (extract/features_detect.cc), the reprojection polish (pose/reproj_refine.cc) and the
// cylinder image fit (attitude/cylinder_image_fit.cc); each keeps the damping schedule its results were
// tuned with as an LmDamping (they differ in start, factors and floor, and the results depend on them).
//
// Why not ceres::TinySolver: its damping (Nielsen's gain-ratio rule) and stopping tests differ from all
// three, so it would change every tool's printed results; the image fit also needs a step cap (a
// rejected step that is not a cost increase) and the pose a manifold update, which are the problem's
// TryStep here.
//
// Header-only, Eigen only (numeric sits below every estimator module).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <concepts>

namespace rk::numeric {

// How λ moves, and when a step is taken.
struct LmDamping {
  double initial = 1e-3;        // λ at the start
  double diagonal_floor = 0.0;  // H_qq += λ · max(H_qq, diagonal_floor)
  double increase = 10.0;       // λ ×= increase after a rejected step
  double decrease = 0.1;        // λ = max(λ × decrease, min) after an accepted one
  double min = 1e-12;
  int max_tries = 10;             // damped solves per iteration before giving up (no descent left)
  bool accept_equal_cost = true;  // accept a step that leaves the cost unchanged (else only a decrease)
  // Re-linearise after the last accepted step, so that H, g on return belong to the solution (for a
  // covariance); false keeps the last linearisation used for a step (one evaluation fewer).
  bool linearize_at_solution = true;
};

enum class LmStatus {
  kConverged,       // the problem's Converged test passed, or no damped step lowered the cost
  kMaxIterations,   // iteration limit reached
  kNonFiniteStep,   // a damped solve gave a non-finite step (state unchanged by it)
  kLinearizeFailed  // the problem could not be linearised at an accepted state
};

struct LmSummary {
  LmStatus status = LmStatus::kMaxIterations;
  int iterations = 0;  // iterations started
  double cost = 0.0;   // at the returned state
};

// Problem: the state lives in the problem, which offers
//   bool TryStep(const Vector& step, double* cost)  candidate = state ⊞ step and its cost; false rejects
//                                                   it (outside the feasible set, cannot be evaluated)
//   void Accept()                                   the last candidate becomes the state
//   bool Linearize(Matrix* H, Vector* g)            JᵀJ and Jᵀr at the state; false: cannot evaluate
//   bool Converged(const Vector& step, double cost_before, double cost_after)  after an accepted step
// and optionally
//   bool AtMinimum(const Matrix& H, const Vector& g, double cost)  at every linearisation, the start's
//                                                   included: true stops (converged) before another step —
//                                                   e.g. when the Gauss–Newton step's predicted decrease
//                                                   gᵀH⁻¹g is below the cost's noise, which saves the
//                                                   damped tries that would find no descent.
// `cost` is the cost at the start and *H, *g its linearisation (the caller builds them: it often has
// them already). The step solves (H + λ D) step = −g, D = diag(max(H_qq, floor)).
template <int N, class Problem>
LmSummary LevenbergMarquardt(Problem& problem, double cost, const LmDamping& damping, int max_iterations,
                             Eigen::Matrix<double, N, N>* H, Eigen::Matrix<double, N, 1>* g) {
  using Mat = Eigen::Matrix<double, N, N>;
  using Vec = Eigen::Matrix<double, N, 1>;
  LmSummary out;
  double lambda = damping.initial;
  constexpr bool kHasAtMinimum = requires(Problem& p, const Mat& h, const Vec& v, double c) {
    { p.AtMinimum(h, v, c) } -> std::convertible_to<bool>;
  };
  if constexpr (kHasAtMinimum) {
    if (problem.AtMinimum(*H, *g, cost)) {
      out.status = LmStatus::kConverged;
      out.cost = cost;
      return out;
    }
  }
  for (int k = 0; k < max_iterations; ++k) {
    out.iterations = k + 1;
    bool accepted = false;
    Vec step = Vec::Zero();
    double previous = cost;
    for (int tries = 0; tries < damping.max_tries && !accepted; ++tries) {
      Mat A = *H;
      for (int q = 0; q < N; ++q) A(q, q) += lambda * std::max((*H)(q, q), damping.diagonal_floor);
      step = -A.ldlt().solve(*g);
      if (!step.allFinite()) {
        out.status = LmStatus::kNonFiniteStep;
        out.cost = cost;
        return out;
      }
      double c = 0.0;
      if (problem.TryStep(step, &c) && (damping.accept_equal_cost ? c <= cost : c < cost)) {
        problem.Accept();
        previous = cost;
        cost = c;
        lambda = std::max(lambda * damping.decrease, damping.min);
        accepted = true;
      } else {
        lambda *= damping.increase;
      }
    }
    if (!accepted) {  // no descent direction left: at the minimum to rounding
      out.status = LmStatus::kConverged;
      break;
    }
    const bool converged = problem.Converged(step, previous, cost);
    if ((damping.linearize_at_solution || (!converged && k + 1 < max_iterations)) &&
        !problem.Linearize(H, g)) {
      out.status = LmStatus::kLinearizeFailed;
      out.cost = cost;
      return out;
    }
    if (converged) {
      out.status = LmStatus::kConverged;
      break;
    }
    if constexpr (kHasAtMinimum) {
      if (problem.AtMinimum(*H, *g, cost)) {
        out.status = LmStatus::kConverged;
        break;
      }
    }
  }
  out.cost = cost;
  return out;
}

}  // namespace rk::numeric

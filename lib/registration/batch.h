// Offline maximum-likelihood bias registration over the whole trial (seed 002 §1: the
// "offline" family of methods — least squares / ML — that a recursive filter cannot beat,
// since every pair is weighed with the final estimate).
//
// Model. For an associated pair (plot i of radar a, plot j of radar b, same target, same step)
// the exact bias-corrected ECEF points (radar_model.h, no linearisation of the bias) coincide up
// to noise:  e_ij(x) = p_b(x_b) − p_a(x_a),  e ~ N(0, C_ij),  C_ij = A_a R A_aᵀ + A_b R A_bᵀ
// (the plots' noise mapped to ECEF at the current estimate). The target position does not
// appear: for a pair it is eliminated exactly by differencing (the linear-Gaussian marginal).
// The estimate minimises  Σ ρ(‖L_ij⁻¹ e_ij(x)‖²),  C_ij = L_ij L_ijᵀ,  with a robust loss ρ
// (Huber or Cauchy with scale `loss_scale` on the whitened norm; "none" = plain ML), solved by
// Ceres (Levenberg–Marquardt, dense QR) with the analytic Jacobians of radar_model.h.
// Covariance: (Jᵀ J)⁻¹ at the solution (ceres::Covariance), reported as 1-sigma, and the
// a-posteriori variance factor σ0² = Σ‖L⁻¹e‖² / (3n − 12) (≈ 1 when the noise sigmas are right).
// 2-D plots (radar_model.h): a pair with one is the reduced difference (d = 3 − number of 2-D plots rows, the
// elevations re-filled at every evaluation), its gate the χ²_d quantile of gate_d2's probability; a 2-D radar's el
// bias is held constant (it enters no residual); σ0² divides by Σ d − the free biases.
//
// Association (which pairs enter):
//   gate       (default) start from a Bernoulli pass (bernoulli.h) over the trial; then, per
//              step, every pair's d² = eᵀ (H P Hᵀ + C)⁻¹ e with the current whole-trial estimate
//              (x, P), and a greedy one-to-one assignment by increasing d² among the pairs with
//              d² ≤ gate_d2; solve; repeat with the new estimate until the set of pairs no longer
//              changes (at most max_rounds).
//   bernoulli  the pairs the Bernoulli pass selected for its reported component at each step
//              (one solve).
//   track      pairs with the same track_id (known association; a reference, needs track_id).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "io/options.h"
#include "registration/bernoulli.h"
#include "registration/filter_common.h"
#include "registration/input.h"

namespace rk::registration {

enum class BatchAssociation { kGate, kBernoulli, kTrack };
std::string BatchAssociationName(BatchAssociation a);

enum class RobustLoss { kHuber, kCauchy, kNone };
std::string RobustLossName(RobustLoss loss);

struct BatchOptions {
  BernoulliOptions initial;  // the Bernoulli pass (start point, association for kBernoulli); its
                             // filter.noise is the noise of the ML model too
  BatchAssociation association = BatchAssociation::kGate;
  RobustLoss loss = RobustLoss::kHuber;
  double loss_scale = 3.0;    // whitened residual norm where the loss leaves the quadratic, > 0
  double gate_d2 = 16.27;     // chi-square 3 dof 0.999
  int max_rounds = 5;         // association rounds (gate), [1, 50]
  int max_iterations = 100;   // Ceres iterations per solve, [1, 1000]

  // --associate, --loss, --loss-scale, --gate, --rounds, --iterations (io/options.h); the Bernoulli pass's
  // options come from BernoulliOptions::PassTable().
  static const io::OptionTable<BatchOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const;  // the table's keys and initial_bernoulli
};

struct BatchStats {
  int rounds = 0;
  std::int64_t pairs = 0;               // pairs in the final solve
  std::int64_t steps_with_pairs = 0;
  std::int64_t association_changes = 0;  // pairs added or removed by the last round
  std::int64_t downweighted = 0;        // pairs with whitened norm > loss_scale at the solution
  std::int64_t outside_gate = 0;        // pairs with d² > gate_d2 at the solution
  double variance_factor = 0.0;         // σ0² = Σ‖L⁻¹e‖² / (Σ d − free biases); 3n − 12 without 2-D plots
  bool covariance_ok = false;
  std::string termination;              // Ceres' termination type of the last solve
  int iterations = 0;                   // Ceres iterations, all rounds
  double initial_cost = 0.0, final_cost = 0.0;  // Ceres costs of the last solve
  io::Json ToJson() const;
};

struct BatchResult {
  RegistrationResult result;
  BernoulliResult initial;  // the Bernoulli pass it started from
  std::vector<std::vector<std::pair<int, int>>> pairs;  // per step, the pairs of the final solve
  BatchStats stats;
};

// Throws ProcessingError (exit 1) if no pair can be associated or the solve fails; DataError if
// association "track" is asked of plots without track_id.
// Progress (optional): `pass_progress(k)` after each step of the Bernoulli pass (k = steps done), then
// `solve_progress(r)` after each association round's solve (r = rounds done, of at most max_rounds).
BatchResult RunBatch(const RegistrationInput& input, const BatchOptions& options,
                     const std::function<void(std::int64_t)>& pass_progress = {},
                     const std::function<void(std::int64_t)>& solve_progress = {});

}  // namespace rk::registration

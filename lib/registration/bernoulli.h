// Gaussian-mixture Bernoulli filter for radar bias registration with unknown association and
// clutter, with the modified greedy measurement partition (seed 002, Deng et al. 2024, §3;
// Bernoulli filter: Ristic et al. 2013; greedy partition after Saucan et al. 2017).
//
// The biases form one Bernoulli RFS whose existence probability is fixed at 1 (eqs. 23–27),
// so only its spatial density s(x) = Σ_i w_i N(x; m_i, P_i) is propagated.
// Prediction (eqs. 28–30): w and m unchanged, P ← P + Q.
// Measurement set (eq. 22): every pair (plot i of radar a, plot j of radar b) of the step,
// n_a·n_b differences z_ij (radar_model.h), most of them false (clutter, other targets).
// Modified greedy partition + update (§3.3–3.4), for each predicted component:
//   level 1: for every pair compute the cost τ = −ln q(z | component) (eq. 31, q of eq. 36) and
//            keep the K best one-member subsets;
//   level n = 2..L: for each kept subset, the pairs not yet in it (eq. 32; with
//            exclusive_plots() also no plot already used in it: one plot comes from one target)
//            are scored against the component updated sequentially with the subset's members
//            (eqs. 34–39, Joseph form, with eq. 38's lost H restored: P = (I − K H) P); a subset's
//            cost is the sum of its members' costs (= −ln of its joint likelihood, independent of
//            the order); the K best distinct subsets of length n are kept.
//   Each of the M components thus gives K updated components with weights w·Π q (eq. 35),
//   normalised over all M·K (eq. 42).
// Gating and clutter: a pair enters only if its Mahalanobis distance d² ≤ gate_d2, and a member
// is scored against the alternative "this difference is false and the pair's target was
// missed": member score −ln(p_D q / ((1 − p_D) κ)) with κ the density of false differences
// (auto: (n_a n_b − min(n_a, n_b)) / volume of the differences' bounding box). A subset may
// stop growing before L when no further member scores below 0; with p_D = 1 (the paper's "no
// missed detections") it stops only when no pair passes the gate. Subsets of different lengths
// are then comparable. With p_D = 1 and K·M subsets of equal length this is exactly eq. 35/42.
// Pruning and merging (Ristic et al. 2013 / Vo & Ma 2006): drop components with weight below
// prune_weight, merge those within Mahalanobis distance² merge_d2 of the heaviest, keep at most
// max_components. The output is the heaviest component's mean and covariance.
// L = 1 is the filter without partition (one difference per component per step): the paper's
// "before" column.
#pragma once

#include <cstdint>
#include <functional>

#include <string>
#include <utility>
#include <vector>

#include "io/options.h"
#include "registration/filter_common.h"
#include "registration/input.h"

namespace rk::registration {

inline constexpr int kMaxSubsetLength = 32;

struct BernoulliOptions {
  FilterOptions filter;           // its own table (FilterOptions::Table()), registered with the input options
  int subsets = 3;                // K, [1, 64]
  int subset_length = 5;          // L, [1, 32]; 1 = no partition
  double gate_d2 = 16.27;         // chi-square 3 dof at 0.999; > 0
  double detection_probability = 0.95;  // p_D in (0, 1]
  double clutter_density = 0.0;   // κ (false differences per m³); 0 = estimated per step
  double prune_weight = 1e-5;     // [0, 1)
  double merge_d2 = 4.0;          // >= 0; 0 = no merging
  int max_components = 8;         // [1, 256]
  bool allow_plot_reuse = false;  // a subset may use one plot in several pairs
  bool exclusive_plots() const { return !allow_plot_reuse; }  // a subset uses each plot at most once

  // -K, -L, --gate, --pd, --clutter-density, --prune, --merge, --max-components, --allow-plot-reuse
  // (io/options.h): CLI flags, Check() and the report keys.
  static const io::OptionTable<BernoulliOptions>& Table();
  // The same without --gate and --allow-plot-reuse: the options of rk-register batch's Bernoulli pass, which
  // keeps the default gate (batch's own --gate is its association gate) and exclusive plots.
  static const io::OptionTable<BernoulliOptions>& PassTable();
  bool Check(std::string* why) const;
  io::Json ToJson() const;  // filter's keys and the table's
};

struct BernoulliStats {
  FilterCounters counters;
  std::int64_t differences = 0;       // Σ n_a·n_b over the steps with both radars
  std::int64_t gated_pairs = 0;       // pair evaluations that passed the gate
  std::int64_t reported_members = 0;  // Σ length of the reported component's subset
  std::int64_t short_subsets = 0;     // updated steps whose reported subset is shorter than L
  std::int64_t max_components = 0;
  double mean_components = 0.0;
  io::Json ToJson() const;
};

struct BernoulliResult {
  RegistrationResult result;
  // Per step, the pairs (index into plots[0], index into plots[1]) of the subset that updated
  // the reported component (empty when the step had no update).
  std::vector<std::vector<std::pair<int, int>>> selected;
  BernoulliStats stats;
};

// `progress(k)` (optional) is called after each of the input's steps, k = steps done.
BernoulliResult RunBernoulli(const RegistrationInput& input, const BernoulliOptions& options,
                             const std::function<void(std::int64_t)>& progress = {});

}  // namespace rk::registration

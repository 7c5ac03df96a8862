// Maximum-likelihood measurement and process noise of one value column under the constant-acceleration
// (white-jerk) model of rk-smooth aukf (aukf_series.h):
//   x = [p, p', p''],  x_k = Φ(τ_k) x_{k−1} + w_k,  w_k ~ N(0, q Q̃(τ_k)),  z_k = p_k + v_k,  v_k ~ N(0, σ²),
//   Q̃(τ) = [[τ⁵/20, τ⁴/8, τ³/6], [τ⁴/8, τ³/3, τ²/2], [τ³/6, τ²/2, τ]].
// The innovations ν_k and their variances S_k of the linear Kalman filter give the exact Gaussian
// log-likelihood  −½ Σ_k (ln S_k + ν_k²/S_k)  (prediction-error decomposition, Schweppe 1965).
// σ is taken as known (the sensor's specification, or estimated from high-order differences:
// NoiseSigmaFromDifferences in singer_series.h) and q is searched: with σ free as well, the likelihood of
// a poorly sampled, non-white-jerk motion (a head turning at 2 Hz seen at 20 Hz) was measured to run to
// σ → 0 (docs/rk-smooth.md), so σ is not fitted here.
// The search: a grid over log q (16 decades around the start value, ½-decade steps), refined by golden
// section in the best grid cell. The first `burn_in` innovations of each block are left out (the
// filter starts diffuse: var p = σ², var p' = (100σ/T)², var p'' = (10⁴σ/T²)²).
// Angle columns (radians): the state is unwrapped, innovations are wrapped to (−π, π].
// Long series: at most `max_samples` samples are used, in `blocks` equal blocks spread evenly over the
// series (each filtered from its own start), so the cost does not grow with the file.
// Missing values (NaN) are prediction-only steps.
#pragma once

#include <cstddef>

namespace rk::filter {

struct NoiseMlOptions {
  std::size_t max_samples = 6000;  // samples used at most (in `blocks` blocks)
  int blocks = 6;                  // blocks when the series is longer than max_samples
  int burn_in = 10;                // innovations left out at the start of each block
  bool Check(const char** why) const;
};

struct NoiseMlFit {
  double q = 0.0;               // white-jerk intensity (unit²/s⁵)
  double nll = 0.0;             // −log-likelihood at the optimum (without the constant), per innovation
  std::size_t innovations = 0;  // innovations in the likelihood
  int evaluations = 0;          // filter passes
  bool on_bound = false;        // optimum at the edge of the search range (the model may not fit)
  // Upper end of the 95 % profile-likelihood interval of q: −log L(q_upper) = −log L(q) + χ²₁(0.95)/2 (total,
  // not per innovation); q_upper ≥ q, and it approaches q as the innovations grow in number.
  double q_upper = 0.0;
};

// Fits q for the series t_s[i], z[i] (i < n; NaN = missing) with measurement noise sigma > 0; the start
// value q0 > 0 centres the search. Returns false when fewer than burn_in + 10 innovations are usable.
bool FitWhiteJerkQMl(const double* t_s, const double* z, std::size_t n, bool angle, double sigma, double q0,
                     const NoiseMlOptions& options, NoiseMlFit* fit);

}  // namespace rk::filter

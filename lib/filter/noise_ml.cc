#include "filter/noise_ml.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "geo/angles.h"
#include "numeric/golden_section.h"
#include "numeric/robust_stats.h"

namespace rk::filter {

bool NoiseMlOptions::Check(const char** why) const {
  if (blocks < 1) {
    *why = "blocks must be >= 1";
    return false;
  }
  if (burn_in < 0) {
    *why = "burn_in must be >= 0";
    return false;
  }
  if (max_samples < static_cast<std::size_t>(blocks) * static_cast<std::size_t>(burn_in + 10)) {
    *why = "max_samples must leave at least burn_in + 10 samples per block";
    return false;
  }
  return true;
}

namespace {

constexpr double kGridHalfWidth = 8.0;  // decades either side of the start value
constexpr double kGridStep = 0.5;       // decades
constexpr double kGoldenTol = 1e-3;     // decades

struct Sums {
  double nu2_over_s = 0.0;  // Σ ν²/S
  double log_s = 0.0;       // Σ ln S
  std::size_t n = 0;
};

struct Block {
  std::size_t begin, end;
};

class ColumnLikelihood {
 public:
  ColumnLikelihood(const double* t, const double* z, bool angle, std::vector<Block> blocks, double T,
                   int burn_in)
      : t_(t), z_(z), angle_(angle), blocks_(std::move(blocks)), T_(T), burn_in_(burn_in) {}

  // One pass of the linear Kalman filter with measurement noise σ and white-jerk intensity q.
  Sums Evaluate(double sigma, double q) const {
    Sums s;
    const double r = sigma * sigma;
    for (const Block& b : blocks_) {
      std::size_t k = b.begin;
      while (k < b.end && !std::isfinite(z_[k])) ++k;
      if (k >= b.end) continue;
      Eigen::Vector3d x(z_[k], 0.0, 0.0);
      Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
      P(0, 0) = r;
      P(1, 1) = r * 1e4 / (T_ * T_);
      P(2, 2) = r * 1e8 / (T_ * T_ * T_ * T_);
      int updates = 0;
      for (++k; k < b.end; ++k) {
        const double tau = t_[k] - t_[k - 1];
        const double h = 0.5 * tau * tau;
        Eigen::Matrix3d F;
        F << 1, tau, h, 0, 1, tau, 0, 0, 1;
        x = F * x;
        const double t2 = tau * tau, t3 = t2 * tau, t4 = t3 * tau, t5 = t4 * tau;
        Eigen::Matrix3d Q;
        Q << t5 / 20, t4 / 8, t3 / 6, t4 / 8, t3 / 3, t2 / 2, t3 / 6, t2 / 2, tau;
        P = F * P * F.transpose() + q * Q;
        if (!std::isfinite(z_[k])) continue;
        double nu = z_[k] - x(0);
        if (angle_) nu = geo::WrapPi(nu);
        const double S = P(0, 0) + r;
        if (!(S > 0.0)) continue;
        const Eigen::Vector3d K = P.col(0) / S;
        x += K * nu;
        P -= S * K * K.transpose();
        P = 0.5 * (P + P.transpose()).eval();
        if (++updates > burn_in_) {
          s.nu2_over_s += nu * nu / S;
          s.log_s += std::log(S);
          ++s.n;
        }
      }
    }
    return s;
  }

 private:
  const double* t_;
  const double* z_;
  bool angle_;
  std::vector<Block> blocks_;
  double T_;
  int burn_in_;
};

// Minimises f over u on a grid u0 ± kGridHalfWidth, then golden section in the best cell.
double MinimiseLog(const std::function<double(double)>& f, double u0, int* evaluations, bool* on_bound) {
  const int steps = static_cast<int>(std::lround(2 * kGridHalfWidth / kGridStep));
  int best = 0;
  double fbest = HUGE_VAL;
  for (int i = 0; i <= steps; ++i) {
    const double v = f(u0 - kGridHalfWidth + i * kGridStep);
    ++*evaluations;
    if (v < fbest) {
      fbest = v;
      best = i;
    }
  }
  *on_bound = best == 0 || best == steps;
  const double a = u0 - kGridHalfWidth + (best - 1) * kGridStep;
  return numeric::GoldenSectionMinimum(f, a, a + 2 * kGridStep, kGoldenTol, std::numeric_limits<int>::max(),
                                       evaluations);
}

}  // namespace

bool FitWhiteJerkQMl(const double* t_s, const double* z, std::size_t n, bool angle, double sigma, double q0,
                     const NoiseMlOptions& options, NoiseMlFit* fit) {
  const char* why = nullptr;
  if (!options.Check(&why) || n < 2 || !(sigma > 0.0) || !(q0 > 0.0)) return false;
  std::vector<double> dt;
  dt.reserve(n - 1);
  for (std::size_t k = 1; k < n; ++k) dt.push_back(t_s[k] - t_s[k - 1]);
  const double T = numeric::UpperMedianInPlace(dt);
  if (!(T > 0.0)) return false;

  std::vector<Block> blocks;
  if (n <= options.max_samples) {
    blocks.push_back({0, n});
  } else {
    const std::size_t len = options.max_samples / static_cast<std::size_t>(options.blocks);
    const std::size_t nb = static_cast<std::size_t>(options.blocks);
    for (std::size_t b = 0; b < nb; ++b) {
      const std::size_t begin = nb == 1 ? 0 : b * (n - len) / (nb - 1);
      blocks.push_back({begin, begin + len});
    }
  }
  const ColumnLikelihood lik(t_s, z, angle, blocks, T, options.burn_in);
  auto nll = [&](double q, std::size_t* count) {
    const Sums r = lik.Evaluate(sigma, q);
    if (count) *count = r.n;
    return r.n ? 0.5 * (r.log_s + r.nu2_over_s) / static_cast<double>(r.n) : HUGE_VAL;
  };
  std::size_t count = 0;
  nll(q0, &count);
  if (count < 10) return false;
  fit->evaluations = 1;
  fit->q = std::pow(10.0, MinimiseLog([&](double u) { return nll(std::pow(10.0, u), nullptr); },
                                      std::log10(q0), &fit->evaluations, &fit->on_bound));
  fit->nll = nll(fit->q, &fit->innovations);
  ++fit->evaluations;
  // Upper end of the likelihood interval: step up by the grid step until the total −log L has risen by
  // χ²₁(0.95)/2 = 1.92, then bisect (in log q).
  constexpr double kHalfChi2Of95 = 1.920729;
  const double target = fit->nll + kHalfChi2Of95 / static_cast<double>(fit->innovations);
  const double u_best = std::log10(fit->q);
  double lo = u_best, hi = u_best;
  while (hi < u_best + 2 * kGridHalfWidth) {
    hi += kGridStep;
    ++fit->evaluations;
    if (nll(std::pow(10.0, hi), nullptr) > target) break;
    lo = hi;
  }
  for (int i = 0; i < 20 && hi - lo > kGoldenTol; ++i) {
    const double mid = 0.5 * (lo + hi);
    ++fit->evaluations;
    (nll(std::pow(10.0, mid), nullptr) > target ? hi : lo) = mid;
  }
  fit->q_upper = std::pow(10.0, hi);
  return true;
}

}  // namespace rk::filter

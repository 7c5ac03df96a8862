// Simulated PnP problems (sim/attitude_problems.h) and the named tolerances shared by the pose tests.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <vector>

#include "sim/attitude_problems.h"

namespace rk::pose::testing {

using sim::PnpGeometry;
using sim::PnpProblem;

inline constexpr double kRoundoff = 1e-9;         // double-precision algebra on O(1) quantities
inline constexpr double kNoiseFreeRad = 1e-8;     // noise-free pose: iteration tolerances, not noise
inline constexpr double kJacobianRel = 1e-6;      // central differences with h = 1e-6 on smooth residuals

inline std::vector<Eigen::Vector2d> Normalised(const PnpProblem& pb, bool noisy) {
  std::vector<Eigen::Vector2d> xn;
  for (const auto& px : noisy ? pb.px : pb.px_true) {
    xn.emplace_back((px.x() - pb.cx) / pb.fx, (px.y() - pb.cy) / pb.fy);
  }
  return xn;
}
inline std::vector<Eigen::Vector3d> Rays(const std::vector<Eigen::Vector2d>& xn) {
  std::vector<Eigen::Vector3d> r;
  for (const auto& x : xn) r.emplace_back(x.x(), x.y(), 1.0);
  return r;
}
inline PnpProblem Problem(PnpGeometry g, std::uint64_t k, double noise_px, int n_min = 4, int n_max = 12) {
  sim::PnpProblemOptions o;
  o.geometry = g;
  o.noise_min_px = o.noise_max_px = noise_px;
  o.min_points = n_min;
  o.max_points = n_max;
  o.seed = 11;
  return sim::MakePnpProblem(o, k);
}

}  // namespace rk::pose::testing

// Shared scene rendering for the beacon tests: a 5-lamp cluster (the seed 001
// lamp group, Fig. 4) and optional single-spot distractors, rendered with
// rk::sim::AddSpots + Digitise (8-bit default sensor: background 10 DN, read
// noise 2 DN, 40 e-/DN shot noise, peak ≈ 200 DN per lamp).
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "sim/render.h"

namespace rk::extract::testing {

// Issue 2 targets: moving-scene centroid RMS error ≤ 0.05 px; static std ≤ 0.03 px, |bias| ≤ 0.03 px.
inline constexpr double kMovingRmsPx = 0.05;
inline constexpr double kStaticStdPx = 0.03;
inline constexpr double kStaticBiasPx = 0.03;

// Lamp offsets (px) of the cluster: a centre lamp and four around it, a few
// pixels apart (separate local maxima, merged by region growing).
inline std::vector<sim::Spot> Cluster(double cx, double cy, double amplitude_dn = 200.0, double scale = 1.0) {
  const double off[5][2] = {{0, 0}, {3.2, 0.4}, {-2.6, 1.9}, {0.5, -3.4}, {-1.2, 3.0}};
  const double amp[5] = {1.0, 0.85, 0.9, 0.8, 0.95};
  std::vector<sim::Spot> s;
  for (int i = 0; i < 5; ++i) {
    sim::Spot p;
    p.x_px = cx + scale * off[i][0];
    p.y_px = cy + scale * off[i][1];
    p.sigma_px = 1.2;
    p.amplitude_dn = amplitude_dn * amp[i];
    s.push_back(p);
  }
  return s;
}

inline sim::Spot Glint(double x, double y, double amplitude_dn) {
  sim::Spot p;
  p.x_px = x;
  p.y_px = y;
  p.sigma_px = 1.1;
  p.amplitude_dn = amplitude_dn;
  return p;
}

inline cv::Mat Render(int w, int h, const std::vector<sim::Spot>& spots, std::mt19937_64& rng, int bit_depth = 8,
                      double scale_dn = 1.0) {
  cv::Mat signal = cv::Mat::zeros(h, w, CV_32FC1);
  std::vector<sim::Spot> s = spots;
  for (auto& p : s) p.amplitude_dn *= scale_dn;
  sim::AddSpots(&signal, s);
  sim::SensorOptions so;
  so.bit_depth = bit_depth;
  so.background_dn *= scale_dn;
  so.read_noise_dn *= scale_dn;
  so.gain_e_per_dn /= scale_dn;
  return sim::Digitise(signal, so, rng);
}

}  // namespace rk::extract::testing

// Cramér–Rao bounds of the 12 radar biases on seed 002's scenarios (issue 5, docs/benchmarks.md):
// the information limit against which rk-register's accuracy is judged.
//
//   pairs   what bernoulli / kf / batch use: every true pair's difference z = p_b − p_a with
//           covariance C = A_a R A_aᵀ + A_b R A_bᵀ; FIM = Σ Hᵀ C⁻¹ H (target positions eliminated by
//           the difference, no assumption on their motion).
//   cv      the same plots, with each target additionally known to move at constant velocity
//           (6 parameters per target, marginalised by the Schur complement): the bound of an
//           offline solve that also fitted target tracks. Not implemented in rk-register (real
//           targets manoeuvre); printed to show what such a model could add.
// Usage: register_crlb [scenario 1|2|3] [steps] [index-unit second|step]
// Prints, per radar, the bound 1σ (m, rad) and the accuracy it allows, 100 (1 − 0.798 σ/|truth|)
// (= the expected acc_final of an efficient unbiased estimator: E|e| = 0.798 σ for a Gaussian).
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <Eigen/Dense>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "geo/angles.h"
#include "registration/radar_model.h"
#include "sim/radar_scenario.h"

using namespace rk;
using registration::BiasVector;
using registration::RadarBias;
using registration::Vec3;

namespace {

constexpr double kStep[6] = {1e-3, 1e-8, 1e-8, 1e-8, 1e-8, 1e-8};  // central-difference steps (m, rad)

struct Geometry {
  GeographicLib::LocalCartesian lc;
  explicit Geometry(const sim::RadarSimOptions& o) : lc(o.origin_lat_deg, o.origin_lon_deg, o.origin_h_m) {}
  Vec3 Ecef(const Eigen::Vector3d& enu) const {
    double lat, lon, h, X, Y, Z;
    lc.Reverse(enu.x(), enu.y(), enu.z(), lat, lon, h);
    GeographicLib::Geocentric::WGS84().Forward(lat, lon, h, X, Y, Z);
    return Vec3(X, Y, Z);
  }
};

// Measured (r, θ, φ) of the ECEF point X by a radar with measured nav `pose` and bias b.
Eigen::Vector3d Measure(const Vec3& X, const registration::PlatformPose& pose, const RadarBias& b) {
  const Vec3 d_enu = pose.R_ecef_enu.transpose() * (X - pose.p_ecef);
  const Vec3 d_b = registration::RotationEnuFromPlatform(pose.yaw_rad - b[3], pose.pitch_rad - b[4],
                                                         pose.roll_rad - b[5]).transpose() * d_enu;
  Eigen::Vector3d m = registration::SphericalFromPlatformPoint(d_b);
  m[1] = geo::WrapPi(m[1]);
  return m + b.head<3>();
}

}  // namespace

int main(int argc, char** argv) {
  sim::RadarSimOptions o;
  o.scenario = argc > 1 ? std::atoi(argv[1]) : 3;
  o.steps = argc > 2 ? std::atoi(argv[2]) : 1000;
  if (argc > 3 && std::string(argv[3]) == "step") o.index_unit = sim::RadarIndexUnit::kStep;
  o.clutter_rate = 0;  // clutter carries no information
  const sim::RadarSimulator sim(o);
  const Geometry geo_(o);
  const registration::MeasurementNoise noise;
  BiasVector truth;
  for (int r = 0; r < 2; ++r)
    for (int i = 0; i < 6; ++i) truth[6 * r + i] = sim.platforms()[r].bias[i];
  const int nt = o.targets, np = 12 + 6 * nt;
  Eigen::MatrixXd F_cv = Eigen::MatrixXd::Zero(np, np);
  Eigen::Matrix<double, 12, 12> F_pair = Eigen::Matrix<double, 12, 12>::Zero();
  const Eigen::Vector3d rinv(1 / (noise.sigma_range_m * noise.sigma_range_m), 1 / (noise.sigma_az_rad() * noise.sigma_az_rad()),
                             1 / (noise.sigma_el_rad() * noise.sigma_el_rad()));
  for (int k = 0; k < o.steps; ++k) {
    const double t = sim.ScanTime(0, k);
    registration::PlatformPose pose[2];
    for (int r = 0; r < 2; ++r) {
      const Eigen::Vector3d g = sim.Geodetic(sim.PlatformEnu(r, t)), att = sim.PlatformAttitude(r, t);
      const auto& b = sim.platforms()[r].bias;
      pose[r] = registration::MakePlatformPose(geo::DegToRad(g[0]), geo::DegToRad(g[1]), g[2], att[0] + b[3],
                                               att[1] + b[4], att[2] + b[5]);
    }
    for (int i = 0; i < nt; ++i) {
      const Vec3 X = geo_.Ecef(sim.TargetEnu(i, t));
      const double dt = t - o.t0_s;
      // Pair FIM at the truth.
      registration::PlotLinearization lin[2];
      for (int r = 0; r < 2; ++r) {
        const RadarBias b = truth.segment<6>(6 * r);
        const Eigen::Vector3d m = Measure(X, pose[r], b);
        lin[r] = registration::LinearizePlot({m[0], m[1], m[2]}, pose[r], b, noise);
      }
      const registration::PairMeasurement pm = registration::MakePairMeasurement(lin[0], lin[1]);
      F_pair += pm.H.transpose() * pm.R.inverse() * pm.H;
      // CV FIM: each plot's measurement against (its radar's biases, the target's X0 and V).
      for (int r = 0; r < 2; ++r) {
        Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, np);
        const RadarBias b = truth.segment<6>(6 * r);
        for (int c = 0; c < 6; ++c) {
          RadarBias lo = b, hi = b;
          lo[c] -= kStep[c];
          hi[c] += kStep[c];
          Eigen::Vector3d d = Measure(X, pose[r], hi) - Measure(X, pose[r], lo);
          d[1] = geo::WrapPi(d[1]);
          J.col(6 * r + c) = d / (2 * kStep[c]);
        }
        for (int c = 0; c < 3; ++c) {
          const double h = 1e-2;
          Vec3 lo = X, hi = X;
          lo[c] -= h;
          hi[c] += h;
          Eigen::Vector3d d = Measure(hi, pose[r], b) - Measure(lo, pose[r], b);
          d[1] = geo::WrapPi(d[1]);
          J.col(12 + 6 * i + c) = d / (2 * h);          // ∂/∂X0
          J.col(12 + 6 * i + 3 + c) = d / (2 * h) * dt;  // ∂/∂V
        }
        F_cv += J.transpose() * rinv.asDiagonal() * J;
      }
    }
  }
  const Eigen::Matrix<double, 12, 12> C_pair = F_pair.inverse();
  const Eigen::MatrixXd C_cv = F_cv.inverse();
  std::printf("# CRLB of the 12 biases, scenario %d, %d steps, %d targets, index unit %s\n", o.scenario, o.steps, nt,
              o.index_unit == sim::RadarIndexUnit::kStep ? "step" : "second");
  std::printf("%-8s %-6s %12s %12s %10s %10s\n", "radar", "bias", "sigma_pairs", "sigma_cv", "acc_pairs", "acc_cv");
  const char* names[6] = {"range", "az", "el", "yaw", "pitch", "roll"};
  for (int j = 0; j < 12; ++j) {
    const double sp = std::sqrt(C_pair(j, j)), sc = std::sqrt(C_cv(j, j));
    std::printf("%-8s %-6s %12.4g %12.4g %9.2f%% %9.2f%%\n", o.names[j / 6].c_str(), names[j % 6], sp, sc,
                100 * (1 - 0.798 * sp / std::abs(truth[j])), 100 * (1 - 0.798 * sc / std::abs(truth[j])));
  }
  return 0;
}

// Shared helpers of the pointing-calibration tests and benchmarks: a simulated session turned into solver
// input, and the Monte Carlo NEES of the solver's σ (the one owner of that loop: tests/calibrate/
// test_pointing_mc.cc and bench/pointing_mc.cc both call RunMonteCarlo).
#pragma once

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "calibrate/pointing_observations.h"
#include "calibrate/pointing_solve.h"
#include "geo/angles.h"
#include "track/boresight.h"
#include "sim/pointing_scenario.h"

namespace rk::calibrate::testing {

// The solver's inputs for a simulated session: image points, targets, turret.
struct SessionInputs {
  ImagePoints points;
  TargetCatalogue targets;
  track::BoresightSource turret = track::BoresightSource::Fixed(0, 0);
};

inline SessionInputs InputsOf(const sim::PointingSession& s) {
  SessionInputs in;
  in.points.source = "points.csv";
  for (std::size_t i = 0; i < s.observations.size(); ++i) {
    const auto& o = s.observations[i];
    ImagePoint p;
    p.frame = o.frame;
    p.t_s = o.t_s;
    p.id = o.id;
    p.px = o.px;
    p.line = i + 2;
    p.id_column = 1;
    in.points.rows.push_back(p);
  }
  in.targets.landmarks = s.landmarks;
  in.targets.stars = s.stars;
  in.targets.station = s.station;
  in.targets.epoch_utc = s.epoch;
  formats::TurretLog log;
  log.source = "turret.csv";
  log.t_s = s.turret_t_s;
  for (std::size_t k = 0; k < s.turret_t_s.size(); ++k) {
    log.az_rad.push_back(geo::DegToRad(s.turret_az_deg[k]));
    log.el_rad.push_back(geo::DegToRad(s.turret_el_deg[k]));
  }
  in.turret = track::BoresightSource::FromLog(log, track::InterpMethod::kLinear, 1.0);
  return in;
}

inline ObservationBuilder BuilderOf(const SessionInputs& in, const PointingCalibrationOptions& opt, double sigma_px) {
  return [&in, opt, sigma_px](double tau) {
    return BuildObservations(in.points, in.targets, in.turret, opt.encoder_step_rad(), sigma_px, tau);
  };
}

// The true parameter vector of a session (radians, δf, s).
inline std::array<double, kNumPointingParams> TruthOf(const sim::PointingSession& s) {
  return {s.truth.az_offset_rad,
          s.truth.tilt_north_rad,
          s.truth.tilt_east_rad,
          s.truth.el_axis_tilt_rad,
          s.camera_truth.mount_yaw_rad,
          s.camera_truth.mount_pitch_rad,
          s.camera_truth.mount_roll_rad,
          s.camera_truth.focal_length_mm / s.camera_nominal.focal_length_mm - 1.0,
          s.camera_truth.time_offset_s};
}

// Monte Carlo figures over sessions with seeds first_seed, first_seed + 1, ...: per estimated parameter the
// mean NEES (x̂ − x)²/σ², the mean squared error and the mean reported σ; the mean joint NEES
// (x̂ − x)ᵀ P⁻¹ (x̂ − x) / n over the n estimated parameters (1 on average when the covariance P is right).
struct McFigures {
  std::array<double, kNumPointingParams> nees{}, err2{}, sigma{};
  double joint_nees = 0.0, solve_s = 0.0, observations = 0.0;
  double chi2_per_dof = 0.0;  // mean over the runs of the fit's χ²/dof (pixel and prior terms)
  int runs = 0;
};

// The CI Monte Carlo's sessions (tests/calibrate/test_pointing_mc.cc; `pointing_mc RUNS SEED small` prints
// the same figures in a Release build): 3 landmarks, 5 stars, 1 s dwells at 1.5 Hz, about 160 image points
// (most of them during the slews, as in a full session), so that a run costs about a second under ASan.
inline sim::PointingSimOptions SmallMcSession() {
  sim::PointingSimOptions o;
  o.landmarks = 3;
  o.stars = 5;
  o.dwell_s = 1.0;
  o.frame_rate_hz = 1.5;
  o.validation_s = 0.0;
  return o;
}

inline EstimateSet EveryParameter() {
  EstimateSet est{};
  est.fill(true);
  return est;
}

inline McFigures RunMonteCarlo(const sim::PointingSimOptions& base, int runs, std::uint64_t first_seed,
                               const EstimateSet& est = EveryParameter()) {
  McFigures f;
  f.runs = runs;
  for (int run = 0; run < runs; ++run) {
    sim::PointingSimOptions o = base;
    o.seed = first_seed + static_cast<std::uint64_t>(run);
    const sim::PointingSession s = sim::SimulatePointingSession(o);
    const SessionInputs in = InputsOf(s);
    PointingCalibrationOptions opt;
    opt.encoder_step_deg = o.encoder_step_deg;
    const auto t0 = std::chrono::steady_clock::now();
    const PointingSolution sol = SolvePointing(BuilderOf(in, opt, o.centroid_sigma_px), s.camera_nominal, est, opt);
    f.solve_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / runs;
    f.observations += static_cast<double>(sol.used) / runs;
    f.chi2_per_dof += sol.chi2_per_dof / runs;
    const auto truth = TruthOf(s);
    Eigen::VectorXd e(static_cast<Eigen::Index>(sol.estimated_params.size()));
    for (std::size_t a = 0; a < sol.estimated_params.size(); ++a) {
      const int k = sol.estimated_params[a];
      const auto ku = static_cast<std::size_t>(k);
      double ek = sol.x[ku] - truth[ku];
      if (k == kParamAzOffset) ek = geo::WrapPi(ek);
      e(static_cast<Eigen::Index>(a)) = ek;
      f.nees[ku] += ek * ek / (*sol.sigma[ku] * *sol.sigma[ku]) / runs;
      f.err2[ku] += ek * ek / runs;
      f.sigma[ku] += *sol.sigma[ku] / runs;
    }
    f.joint_nees += e.dot(sol.covariance.ldlt().solve(e)) / static_cast<double>(e.size()) / runs;
  }
  return f;
}

inline void PrintMcFigures(const McFigures& f, const EstimateSet& est = EveryParameter()) {
  std::printf("%d runs, mean %.0f observations used, mean solve %.3f s, mean joint NEES per parameter %.3f, "
              "mean chi2/dof %.3f\n",
              f.runs, f.observations, f.solve_s, f.joint_nees, f.chi2_per_dof);
  std::printf("%-13s %9s %14s %14s  unit\n", "parameter", "mean NEES", "RMS error", "mean sigma");
  for (int k = 0; k < kNumPointingParams; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    if (!est[ku]) continue;
    double scale = geo::kArcsecPerRad;
    const char* unit = "arcsec";
    if (k == kParamFocal) scale = 100.0, unit = "% of focal";
    if (k == kParamTimeOffset) scale = 1e3, unit = "ms";
    std::printf("%-13s %9.3f %14.5f %14.5f  %s\n", PointingParamName(k), f.nees[ku], std::sqrt(f.err2[ku]) * scale,
                f.sigma[ku] * scale, unit);
  }
}

}  // namespace rk::calibrate::testing

// Shared helpers of the pointing-calibration tests: a simulated session turned into solver input.
#pragma once

#include <string>

#include "calibrate/pointing_observations.h"
#include "calibrate/pointing_solve.h"
#include "geo/angles.h"
#include "locate/boresight.h"
#include "sim/pointing_scenario.h"

namespace rk::calibrate::testing {

// The solver's inputs for a simulated session: image points, targets, turret.
struct SessionInputs {
  ImagePoints points;
  TargetCatalogue targets;
  locate::BoresightSource turret = locate::BoresightSource::Fixed(0, 0);
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
  locate::TurretLog log;
  log.source = "turret.csv";
  log.t_s = s.turret_t_s;
  for (std::size_t k = 0; k < s.turret_t_s.size(); ++k) {
    log.az_rad.push_back(geo::DegToRad(s.turret_az_deg[k]));
    log.el_rad.push_back(geo::DegToRad(s.turret_el_deg[k]));
  }
  in.turret = locate::BoresightSource::FromLog(log, track::InterpMethod::kLinear, 1.0);
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

}  // namespace rk::calibrate::testing

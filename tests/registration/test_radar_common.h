// Shared helpers of the registration tests: a seed 002 trial simulated in memory and read through
// the real CSV path (ReadRegistrationInput), and the truth bias vector.
#pragma once

#include <cmath>
#include <string>

#include "geo/angles.h"
#include "io/csv.h"
#include "registration/input.h"
#include "sim/radar_scenario.h"

namespace rk::registration::testing {

// Files as rk-sim radar writes them (same columns and decimals), parsed from memory.
// fold_pitch: write the nav attitude as a writer keeping pitch within ±90° would, (ϑ + 180°,
// 180° − ϕ, α + 180°) where |ϕ| > 90° (the same rotation).
inline RegistrationInput ReadSimulated(const sim::RadarSimulator& sim, const InputOptions& opt = {},
                                       bool with_track_id = true, bool fold_pitch = false) {
  const auto& so = sim.options();
  std::vector<std::string> cols{"t_s", "radar", "range_m", "az_deg", "el_deg"};
  if (with_track_id) cols.push_back("track_id");
  io::CsvWriter plots(cols);
  for (const sim::SimRadarPlot& p : sim.plots()) {
    plots.Add(p.t_s, 9).Add(so.names[p.radar]).Add(p.range_m, 3);
    plots.Add(geo::WrapDeg360(geo::RadToDeg(p.az_rad)), 9);
    if (so.two_d[p.radar]) {
      plots.AddEmpty();  // a 2-D radar's plot, as rk-sim radar --2d writes it
    } else {
      plots.Add(geo::RadToDeg(p.el_rad), 9);
    }
    if (with_track_id) {
      if (p.target >= 0) {
        plots.Add(p.target + 1);
      } else {
        plots.AddEmpty();
      }
    }
    plots.EndRow();
  }
  io::CsvWriter nav({"t_s", "radar", "lat_deg", "lon_deg", "h_m", "yaw_deg", "pitch_deg", "roll_deg"});
  for (const sim::SimNavRow& n : sim.nav()) {
    double yaw = geo::RadToDeg(n.yaw_rad), pitch = geo::WrapDeg180(geo::RadToDeg(n.pitch_rad)),
           roll = geo::RadToDeg(n.roll_rad);
    if (fold_pitch && std::abs(pitch) > 90) {
      yaw += 180;
      pitch = geo::WrapDeg180(180 - pitch);
      roll += 180;
    }
    nav.Add(n.t_s, 9).Add(so.names[n.radar]).Add(n.lat_deg, 10).Add(n.lon_deg, 10).Add(n.h_m, 4);
    nav.Add(geo::WrapDeg360(yaw), 9).Add(pitch, 9).Add(geo::WrapDeg180(roll), 9).EndRow();
  }
  return ReadRegistrationInput(io::CsvTable::Parse(plots.str(), "plots.csv"), io::CsvTable::Parse(nav.str(), "nav.csv"),
                               opt);
}

inline BiasVector TruthBiases(const sim::RadarSimulator& sim) {
  BiasVector x;
  for (int r = 0; r < 2; ++r) {
    for (int i = 0; i < kRadarBiasDim; ++i) x[r * kRadarBiasDim + i] = sim.platforms()[r].bias[i];
  }
  return x;
}

inline sim::RadarSimOptions Scenario(int scenario, int steps, std::uint64_t seed) {
  sim::RadarSimOptions o;
  o.scenario = scenario;
  o.steps = steps;
  o.seed = seed;
  return o;
}

}  // namespace rk::registration::testing

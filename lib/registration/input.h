// Reading a registration trial: radar plots + platform nav (SPEC.md §2.1) → steps of paired scans.
//
// plots: t_s,radar,range_m,az_deg,el_deg (+ optional track_id: target id, empty for clutter; other columns, such as
//        rk-import asterix's sac,sic,flight_level,height_m,mode3a,address,el_source, are ignored). An empty el_deg
//        is a 2-D plot (RadarMeasurement::has_el false).
// nav:   t_s,radar,lat_deg,lon_deg,h_m,yaw_deg,pitch_deg,roll_deg
// Exactly two radars, named by the files (sorted by name: the first is "a" of the paper, the
// second "b"). Both files have rows in non-decreasing t_s; nav times of one radar are strictly
// increasing. The nav of each radar is interpolated linearly to every plot's own time
// (lat, h linearly; lon and the three attitude angles on their unwrapped sequences); a plot
// outside its radar's nav span is an error naming the plot's file, line and column.
//
// Steps. Plots are grouped in time order: a step starts at the first plot not yet grouped and
// takes every plot (of either radar) whose time is within `pair_tol_s` of that first time. So
// the two radars' scans of one sampling instant are paired even when their time stamps differ
// slightly (e.g. radar b reporting 0.2 s after radar a); the tolerance must stay below half the
// sampling interval. Target motion between the two radars' times is not modelled (it adds
// v·Δt to the difference of the two points). The step's time is its latest plot time (the
// estimate is causal: it uses nothing later).
//
// Values: range_m > 0; el_deg empty or in [−90, 90]; lat_deg in [−90, 90]; every other value finite.
// Pitch may lie outside [−90, 90] (seed 002's scenarios drive the eq. 6 pitch past 90°; folding
// it would flip the sign of the pitch bias), see docs/rk-register.md.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "io/csv.h"
#include "io/json_util.h"
#include "io/options.h"
#include "registration/radar_model.h"

namespace rk::registration {

struct PlotRecord {
  double t_s = 0.0;
  RadarMeasurement meas;  // measured (r, θ, φ), radians
  PlatformPose pose;      // nav at t_s (measured attitude)
  int track = -1;         // index into RegistrationInput::track_ids; −1 = no id (clutter)
  std::size_t line = 0;   // line of the plot in its file
};

struct RegistrationStep {
  double t_s = 0.0;        // latest plot time of the step
  double t_first_s = 0.0;  // earliest plot time of the step
  std::array<std::vector<PlotRecord>, 2> plots;  // per radar
  bool HasBothRadars() const { return !plots[0].empty() && !plots[1].empty(); }
};

struct InputOptions {
  double pair_tol_s = 0.5;        // [0, 60] s
  bool require_track_id = false;  // rk-register kf: the plots must carry track_id (set by the subcommand)
  // --pair-tol (io/options.h).
  static const io::OptionTable<InputOptions>& Table();
  bool Check(std::string* why) const { return Table().Check(*this, why); }
};

struct InputSummary {
  std::array<std::size_t, 2> plots{0, 0};     // per radar
  std::array<std::size_t, 2> nav_rows{0, 0};  // per radar
  std::array<std::size_t, 2> nav_unfolded_rows{0, 0};  // attitude rows converted to the continuous triple
  std::array<std::size_t, 2> plots_without_el{0, 0};   // plots with an empty el_deg (2-D plots), per radar
  std::size_t steps = 0;
  std::size_t steps_one_radar = 0;  // steps with plots of one radar only (no update possible)
  std::size_t clutter_plots = 0;    // plots with an empty track_id (when the column exists)
  double max_pair_offset_s = 0.0;   // largest time spread inside one step
  io::Json ToJson(const std::array<std::string, 2>& radars) const;
};

struct RegistrationInput {
  std::array<std::string, 2> radars;  // sorted by name
  std::string plots_source, nav_source;
  bool has_track_id = false;
  // Per radar: every plot has an empty el_deg (a 2-D radar: its el bias is unobservable, docs/rk-register.md
  // "2-D radars"). A radar with some empty el_deg is not 2-D: its 3-D plots carry the el bias, its 2-D ones are
  // used with their elevation unknown.
  std::array<bool, 2> two_d{false, false};
  std::vector<std::string> track_ids;  // distinct non-empty track_id values, in order of appearance
  std::vector<RegistrationStep> steps;
  InputSummary summary;
};

// Median over radar b's scan times of the signed offset to radar a's nearest scan time (s): what
// --pair-tol must cover. 0 when either radar has no plots.
double MedianRadarOffset(const RegistrationInput& input);

// Throws ProcessingError (exit 1) when no step has plots of both radars (nothing can be estimated),
// naming the radars' typical time offset and the tolerance.
void RequirePairedSteps(const RegistrationInput& input, double pair_tol_s);

// Throws DataError (exit 3) naming file:line:col for every problem listed in the header; ProcessingError (exit 1)
// when both radars are 2-D (docs/rk-register.md "2-D radars": not estimated with honest sigmas).
RegistrationInput ReadRegistrationInput(const io::CsvTable& plots, const io::CsvTable& nav,
                                        const InputOptions& options);
// The cells ReadRegistrationInput needs of every plots / nav row (io::CsvReadOptions::rule).
io::CsvRowRule PlotsRowRule();
io::CsvRowRule NavRowRule();

}  // namespace rk::registration

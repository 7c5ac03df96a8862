#include "registration/input.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "geo/angles.h"
#include "io/error.h"
#include "io/number_text.h"
#include "numeric/robust_stats.h"
#include "track/interp.h"

namespace rk::registration {
namespace {

constexpr double kMaxPairTolS = 60.0;

std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s;
}

std::string FormatTime(double t) { return io::NumberText(t); }

// Nav of one radar: six interpolated channels.
struct NavSeries {
  std::vector<double> t;
  std::vector<std::optional<double>> lat, lon, h, yaw, pitch, roll;
  std::unique_ptr<track::TimeSeriesInterpolator> i_lat, i_lon, i_h, i_yaw, i_pitch, i_roll;

  // Makes the attitude sequence continuous across a folded pitch: (ϑ, ϕ, α) and (ϑ + π, π − ϕ,
  // α + π) are the same eq. 6 rotation; a writer that keeps pitch within ±90° switches between
  // them. Each row keeps the triple closest to the previous row's; returns the rows converted.
  std::size_t Unfold() {
    std::size_t converted = 0;
    for (std::size_t k = 1; k < t.size(); ++k) {
      const double y = *yaw[k], p = *pitch[k], r = *roll[k];
      const double dy = geo::AngleDiff(y, *yaw[k - 1]), dp = geo::AngleDiff(p, *pitch[k - 1]),
                   dr = geo::AngleDiff(r, *roll[k - 1]);
      const double ey = geo::AngleDiff(y + geo::kPi, *yaw[k - 1]), ep = geo::AngleDiff(geo::kPi - p, *pitch[k - 1]),
                   er = geo::AngleDiff(r + geo::kPi, *roll[k - 1]);
      const double keep = std::max({std::abs(dy), std::abs(dp), std::abs(dr)});
      const double flip = std::max({std::abs(ey), std::abs(ep), std::abs(er)});
      if (flip < keep) {
        yaw[k] = y + geo::kPi;
        pitch[k] = geo::kPi - p;
        roll[k] = r + geo::kPi;
        ++converted;
      }
    }
    return converted;
  }

  void Build() {
    track::InterpOptions lin;
    track::InterpOptions ang;
    ang.angle = true;
    i_lat = std::make_unique<track::TimeSeriesInterpolator>(t, lat, lin);
    i_lon = std::make_unique<track::TimeSeriesInterpolator>(t, track::UnwrapAngles(lon), ang);
    i_h = std::make_unique<track::TimeSeriesInterpolator>(t, h, lin);
    i_yaw = std::make_unique<track::TimeSeriesInterpolator>(t, track::UnwrapAngles(yaw), ang);
    i_pitch = std::make_unique<track::TimeSeriesInterpolator>(t, track::UnwrapAngles(pitch), ang);
    i_roll = std::make_unique<track::TimeSeriesInterpolator>(t, track::UnwrapAngles(roll), ang);
  }
  bool At(double ts, PlatformPose* pose) const {
    const track::InterpValue a = i_lat->At(ts), b = i_lon->At(ts), c = i_h->At(ts), d = i_yaw->At(ts),
                             e = i_pitch->At(ts), f = i_roll->At(ts);
    if (!(a.ok() && b.ok() && c.ok() && d.ok() && e.ok() && f.ok())) return false;
    *pose = MakePlatformPose(a.value, b.value, c.value, d.value, e.value, f.value);
    return true;
  }
};

}  // namespace

const io::OptionTable<InputOptions>& InputOptions::Table() {
  static const io::OptionTable<InputOptions> table = io::OptionTable<InputOptions>().Real(
      "--pair-tol", &InputOptions::pair_tol_s, "s", io::Bounds::Closed(0.0, kMaxPairTolS),
      "Plots of both radars within this many seconds of a step's first plot form one step (s)");
  return table;
}

io::Json InputSummary::ToJson(const std::array<std::string, 2>& radars) const {
  io::Json j;
  for (int r = 0; r < 2; ++r) {
    j["plots"][radars[r]] = plots[r];
    j["nav_rows"][radars[r]] = nav_rows[r];
    j["nav_unfolded_rows"][radars[r]] = nav_unfolded_rows[r];
  }
  if (plots_without_el[0] + plots_without_el[1] > 0) {  // 2-D plots only: a 3-D trial's report stays as it was
    for (int r = 0; r < 2; ++r) j["plots_without_el"][radars[r]] = plots_without_el[r];
  }
  j["steps"] = steps;
  j["steps_one_radar"] = steps_one_radar;
  j["clutter_plots"] = clutter_plots;
  j["max_pair_offset_s"] = max_pair_offset_s;
  return j;
}

double MedianRadarOffset(const RegistrationInput& in) {
  std::array<std::vector<double>, 2> times;
  for (const RegistrationStep& st : in.steps) {
    for (int r = 0; r < 2; ++r) {
      for (const PlotRecord& p : st.plots[r]) {
        if (times[r].empty() || times[r].back() != p.t_s) times[r].push_back(p.t_s);
      }
    }
  }
  if (times[0].empty() || times[1].empty()) return 0.0;
  std::vector<double> off;
  for (double tb : times[1]) {
    auto it = std::lower_bound(times[0].begin(), times[0].end(), tb);
    double best = INFINITY;
    if (it != times[0].end()) best = *it - tb;
    if (it != times[0].begin() && std::abs(*(it - 1) - tb) < std::abs(best)) best = *(it - 1) - tb;
    off.push_back(-best);  // t_b − t_a
  }
  return numeric::UpperMedianInPlace(off);
}

void RequirePairedSteps(const RegistrationInput& in, double pair_tol_s) {
  if (in.summary.steps_one_radar < in.summary.steps) return;
  throw ProcessingError("no step has plots of both radars within --pair-tol " + FormatTime(pair_tol_s) +
                        " s (radar '" + in.radars[1] + "' reports typically " + FormatTime(MedianRadarOffset(in)) +
                        " s after radar '" + in.radars[0] + "'): nothing to estimate; raise --pair-tol");
}

namespace {

// The nav of the two radars (exactly two, each with increasing times), unfolded and ready to interpolate;
// sets in->radars (sorted by name) and the nav counts of in->summary.
std::map<std::string, NavSeries> ReadNav(const io::CsvTable& nav, RegistrationInput* in_out) {
  RegistrationInput& in = *in_out;
  const int n_t = nav.RequireColumn("t_s"), n_radar = nav.RequireColumn("radar"),
            n_lat = nav.RequireColumn("lat_deg"), n_lon = nav.RequireColumn("lon_deg"),
            n_h = nav.RequireColumn("h_m"), n_yaw = nav.RequireColumn("yaw_deg"),
            n_pitch = nav.RequireColumn("pitch_deg"), n_roll = nav.RequireColumn("roll_deg");
  if (nav.rows() == 0) throw DataError(nav.name(), 0, 0, "no nav rows");
  nav.RequireNonDecreasing(n_t);
  std::vector<std::string> nav_names;  // in order of appearance
  std::map<std::string, NavSeries> series;
  for (std::size_t r = 0; r < nav.rows(); ++r) {
    const std::string name(nav.Cell(r, n_radar));
    if (name.empty()) throw nav.CellError(r, n_radar, "empty radar name");
    auto it = series.find(name);
    if (it == series.end()) {
      if (nav_names.size() == 2) {
        throw nav.CellError(r, n_radar, "a third radar '" + name + "': rk-register works with exactly two (" +
                                            Join(nav_names) + ")");
      }
      nav_names.push_back(name);
      it = series.emplace(name, NavSeries{}).first;
    }
    NavSeries& s = it->second;
    const double t = nav.Double(r, n_t);
    if (!s.t.empty() && t <= s.t.back()) {
      throw nav.CellError(r, n_t, "radar '" + name + "' repeats the time " + std::string(nav.Cell(r, n_t)));
    }
    const double lat = nav.Double(r, n_lat);
    if (!(lat >= -90 && lat <= 90)) throw nav.CellError(r, n_lat, "latitude outside [-90, 90] deg");
    s.t.push_back(t);
    s.lat.push_back(geo::DegToRad(lat));
    s.lon.push_back(geo::DegToRad(nav.Double(r, n_lon)));
    s.h.push_back(nav.Double(r, n_h));
    s.yaw.push_back(geo::DegToRad(nav.Double(r, n_yaw)));
    s.pitch.push_back(geo::DegToRad(nav.Double(r, n_pitch)));
    s.roll.push_back(geo::DegToRad(nav.Double(r, n_roll)));
  }
  if (nav_names.size() < 2) {
    throw DataError(nav.name(), 0, 0,
                    "nav of one radar only ('" + nav_names[0] + "'): rk-register needs exactly two radars");
  }
  std::vector<std::string> sorted = nav_names;
  std::sort(sorted.begin(), sorted.end());
  in.radars = {sorted[0], sorted[1]};
  for (int k = 0; k < 2; ++k) {
    NavSeries& s = series.at(in.radars[k]);
    in.summary.nav_rows[k] = s.t.size();
    in.summary.nav_unfolded_rows[k] = s.Unfold();
    s.Build();
  }
  return series;
}

}  // namespace

RegistrationInput ReadRegistrationInput(const io::CsvTable& plots, const io::CsvTable& nav,
                                        const InputOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  RegistrationInput in;
  in.plots_source = plots.name();
  in.nav_source = nav.name();

  const std::map<std::string, NavSeries> series = ReadNav(nav, &in);

  // --- plots ---
  const int p_t = plots.RequireColumn("t_s"), p_radar = plots.RequireColumn("radar"),
            p_range = plots.RequireColumn("range_m"), p_az = plots.RequireColumn("az_deg"),
            p_el = plots.RequireColumn("el_deg");
  const int p_track = plots.Column("track_id");
  in.has_track_id = p_track >= 0;
  if (options.require_track_id && !in.has_track_id) {
    throw DataError(plots.name(), plots.header_line(), 1,
                    "missing column 'track_id': this method needs the known association of every plot");
  }
  if (plots.rows() == 0) throw DataError(plots.name(), 0, 0, "no plots");
  plots.RequireNonDecreasing(p_t);
  std::map<std::string, int> track_index;
  RegistrationStep* step = nullptr;
  for (std::size_t r = 0; r < plots.rows(); ++r) {
    const std::string name(plots.Cell(r, p_radar));
    int k = -1;
    if (name == in.radars[0]) k = 0;
    if (name == in.radars[1]) k = 1;
    if (k < 0) {
      throw plots.CellError(r, p_radar, "unknown radar '" + name + "' (" + nav.name() + " has " +
                                            in.radars[0] + ", " + in.radars[1] + ")");
    }
    PlotRecord p;
    p.t_s = plots.Double(r, p_t);
    p.line = plots.Line(r);
    p.meas.range_m = plots.Double(r, p_range);
    if (!(p.meas.range_m > 0)) throw plots.CellError(r, p_range, "range must be > 0 m");
    p.meas.az_rad = geo::DegToRad(plots.Double(r, p_az));
    if (const std::optional<double> el = plots.OptionalDouble(r, p_el)) {
      if (!(*el >= -90 && *el <= 90)) throw plots.CellError(r, p_el, "elevation outside [-90, 90] deg");
      p.meas.el_rad = geo::DegToRad(*el);
    } else {
      p.meas.has_el = false;  // a 2-D plot: el_rad is filled per pair (FillMissingElevations)
      ++in.summary.plots_without_el[k];
    }
    if (p_track >= 0) {
      const std::string id(plots.Cell(r, p_track));
      if (id.empty()) {
        ++in.summary.clutter_plots;
      } else {
        auto it = track_index.find(id);
        if (it == track_index.end()) {
          it = track_index.emplace(id, static_cast<int>(in.track_ids.size())).first;
          in.track_ids.push_back(id);
        }
        p.track = it->second;
      }
    }
    const NavSeries& s = series.at(name);
    if (!s.At(p.t_s, &p.pose)) {
      throw plots.CellError(r, p_t, "no nav of radar '" + name + "' at t_s = " + FormatTime(p.t_s) + " (" +
                                        nav.name() + " covers " + FormatTime(s.t.front()) + " to " +
                                        FormatTime(s.t.back()) + " s)");
    }
    ++in.summary.plots[k];
    if (step == nullptr || p.t_s - step->t_first_s > options.pair_tol_s) {
      in.steps.emplace_back();
      step = &in.steps.back();
      step->t_first_s = p.t_s;
    }
    step->t_s = p.t_s;
    in.summary.max_pair_offset_s = std::max(in.summary.max_pair_offset_s, p.t_s - step->t_first_s);
    step->plots[k].push_back(p);
  }
  for (int k = 0; k < 2; ++k) {
    if (in.summary.plots[k] == 0) {
      throw DataError(plots.name(), 0, 0,
                      "no plots of radar '" + in.radars[k] + "' (one radar missing; need plots of both)");
    }
  }
  for (int k = 0; k < 2; ++k) in.two_d[k] = in.summary.plots_without_el[k] == in.summary.plots[k];
  if (in.two_d[0] && in.two_d[1]) {
    throw ProcessingError("both radars are 2-D (no el_deg in any plot of '" + in.radars[0] + "' or '" +
                          in.radars[1] + "'): a pair of plots then gives one equation, and on simulated trials the "
                          "biases come out many sigmas off (docs/rk-register.md \"2-D radars\"); nothing is "
                          "estimated: at least one radar must measure elevation");
  }
  in.summary.steps = in.steps.size();
  for (const RegistrationStep& st : in.steps) {
    if (!st.HasBothRadars()) ++in.summary.steps_one_radar;
  }
  return in;
}

io::CsvRowRule PlotsRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.texts = {"radar"};
  rule.numbers = {"range_m", "az_deg"};
  rule.optional_numbers = {"el_deg"};  // empty: a 2-D radar's plot
  return rule;
}

io::CsvRowRule NavRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.texts = {"radar"};
  rule.numbers = {"lat_deg", "lon_deg", "h_m", "yaw_deg", "pitch_deg", "roll_deg"};
  return rule;
}

}  // namespace rk::registration

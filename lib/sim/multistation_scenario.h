// rk-sim multistation: two to four stations kilometres apart at different heights observe one target
// (issue 18): each station with its own frame times (own rate and phase), azimuth and elevation with white
// noise (σ across the line of sight: σ_el = σ, σ_az = σ / cos el) and optionally a laser range; the target
// flies a ballistic arc (to 15 km by default), a straight crossing at constant height, or a climbing turn.
// Layouts: `triangle` (stations spread around the area) or `line` (nearly on a line along east, the
// geometry where a clock offset and a shift of a crossing along the line look alike).
// Clocks: --time-offsets s2:X,... gives a station's clock offset X (s): its located rows' t_s read the true
// time minus X (SPEC.md §7: t_s + X is the common clock); truth.csv is on the true clock.
//
// Truth chain (independent of any estimator, geo/wgs84.h only): the trajectory is defined in the origin's
// ENU frame → WGS-84 (geo::LocalEnu at the origin) → each station's own ENU frame (geo::LocalEnu at the
// station: its own vertical and north) → az = atan2(e, n), el = atan2(u, hypot(e, n)), range = |ENU|.
// The ballistic arc is a parabola in the origin ENU frame (constant g = 9.80665 m/s² along −u of the origin):
// a kinematic test path, not a flight model.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/csv.h"
#include "io/json_util.h"
#include "io/options.h"

namespace rk::sim {

enum class MultistationPath { kBallistic, kCrossing, kTurn };
std::string MultistationPathName(MultistationPath p);  // "ballistic", "crossing", "turn"
enum class MultistationLayout { kTriangle, kLine };

struct MultistationOptions {
  int stations = 3;                 // [2, 4]
  double baseline_km = 20.0;        // distance from station 1 to station 2 (the others scale with it), > 0
  double duration_s = 60.0;         // > 0
  double rate_hz = 20.0;            // station 1's frame rate; stations 2.. run at 1.25, 0.8, 1.5 × it
  double sigma_angle_arcsec = 5.0;  // 1σ across the line of sight, > 0
  int range_stations = 0;           // the first N stations have a rangefinder, [0, stations]
  double sigma_range_m = 1.0;       // > 0
  double apex_m = 15000.0;          // ballistic apex height above the origin (m), > 0
  double speed_mps = 250.0;         // crossing speed (m/s), > 0
  double height_m = 3000.0;         // crossing height above the origin (m), > 0
  MultistationPath path = MultistationPath::kBallistic;
  MultistationLayout layout = MultistationLayout::kTriangle;
  std::string time_offsets;         // "s2:0.0043,s3:-0.0117": per station clock offsets (s), others 0 (the
                                    // app's --time-offsets: a text option, outside Table; ToJson adds it)
  // "none", or the video format of a trial folder rk-run runs (docs/rk-sim.md "Rendered stations"): each
  // station rendered as by rk-sim beacon (small camera on a turret, one beacon camera "az") into "mkv" or "png".
  std::string video = "none";
  double origin_lat_deg = 47.0, origin_lon_deg = 8.0, origin_h_m = 400.0;
  std::uint64_t seed = 1;

  static const io::OptionTable<MultistationOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const {
    io::Json j = Table().ToJson(*this);
    j["time_offsets"] = time_offsets;
    return j;
  }
  // The clock offset of every station (s), from time_offsets; false (and why) for a malformed list.
  bool ParseTimeOffsets(std::vector<double>* offsets, std::string* why) const;
};

struct SimStation {
  std::string name;
  double lat_deg = 0.0, lon_deg = 0.0, h_m = 0.0;
  Eigen::Vector3d p_enu = Eigen::Vector3d::Zero();  // in the origin ENU frame (m)
  bool has_range = false;
  double time_offset_s = 0.0;       // its clock: t_s = true time − this
  std::vector<double> t_s, az_deg, el_deg, range_m, sigma_az_deg, sigma_el_deg;  // measured (noisy), its clock
  std::vector<double> true_t_s;     // the rows' true times
  std::vector<double> true_az_deg, true_el_deg, true_range_m;
};

class MultistationScenario {
 public:
  explicit MultistationScenario(const MultistationOptions& options);
  ~MultistationScenario();

  // Target truth in the origin ENU frame at t (m, m/s).
  Eigen::Vector3d Position(double t_s) const;
  Eigen::Vector3d Velocity(double t_s) const;
  // Origin ENU → WGS-84 (lat_deg, lon_deg, h_m).
  Eigen::Vector3d Geodetic(const Eigen::Vector3d& p_enu) const;
  // p_enu (origin ENU) in station s's own ENU frame (m), through WGS-84.
  Eigen::Vector3d StationEnu(std::size_t s, const Eigen::Vector3d& p_enu) const;
  // Azimuth, elevation (rad) and range (m) of p_enu from station s, through WGS-84 (header).
  Eigen::Vector3d AzElRange(std::size_t s, const Eigen::Vector3d& p_enu) const;

  const MultistationOptions& options() const { return o_; }
  const std::vector<SimStation>& stations() const { return stations_; }

  // located.csv of station s (SPEC.md §2.1 located target + 1σ columns).
  io::CsvWriter LocatedCsv(std::size_t s) const;
  // stations.json with located paths "<name>/located.csv".
  io::Json StationsJson() const;
  // truth.csv at the union of the stations' frame times: t_s, e/n/u_m, lat/lon_deg, h_m, ve/vn/vu_mps.
  io::CsvWriter TruthCsv() const;

 private:
  void Measure(std::size_t s, std::uint64_t stream);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  MultistationOptions o_;
  std::vector<SimStation> stations_;
};

// Writes <out>/stations.json, <out>/<name>/located.csv, <out>/truth.csv atomically (TrialFolder); with a video
// format (options().video) also the trial rk-run runs: <out>/trial.json (docs/rk-run.md "Several stations") and
// per station what rk-sim beacon writes for its one station (sim::WriteBeaconStation) under <out>/<name>/.
void WriteMultistationTrial(const MultistationScenario& sim, const std::string& out_dir, bool force);

}  // namespace rk::sim

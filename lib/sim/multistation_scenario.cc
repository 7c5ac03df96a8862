// rk-sim multistation; see multistation_scenario.h.
#include "sim/multistation_scenario.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

#include "formats/located.h"
#include "formats/stations.h"
#include "geo/angles.h"
#include "geo/wgs84.h"
#include "io/file_util.h"
#include "sim/sim_common.h"
#include "sim/beacon_trial.h"
#include "sim/trial_folder.h"
#include "trial/layout.h"
#include "trial/manifest.h"

namespace rk::sim {
namespace {

constexpr double kGravityMps2 = 9.80665;
// Station layout in units of the baseline (origin ENU, x east, y north) and heights above the origin (m).
constexpr double kLayout[4][3] = {{0.0, 0.0, 0.0}, {1.0, 0.0, 350.0}, {0.45, 0.75, 900.0}, {-0.3, 0.6, 150.0}};
// `line`: along east, a few hundred metres off it at a 20 km baseline.
constexpr double kLineLayout[4][3] = {{0.0, 0.0, 0.0}, {1.0, 0.01, 350.0}, {0.5, -0.012, 900.0}, {1.5, 0.006, 150.0}};
// `turn`: a climbing turn about (0.5, 0.35) baselines, radius 0.3 baselines, climbing this fast.
constexpr double kTurnCentre[2] = {0.5, 0.35}, kTurnRadius = 0.3, kTurnClimbMps = 20.0;
constexpr double kMaxTimeOffsetS = 10.0;
constexpr double kRateFactor[4] = {1.0, 1.25, 0.8, 1.5};
constexpr std::uint64_t kStreamNoise = 1, kStreamPhase = 2;
// Rendered stations (--video): lamp peak (8-bit DN; five lamps merged in one spot stay below 255), the seed of
// station s = seed · stride + s + 1, the trial epoch.
constexpr double kRenderedPeakDn = 45.0;
constexpr std::uint64_t kStationSeedStride = 16;
constexpr const char* kRenderedEpochUtc = "2026-01-01T00:00:00Z";

}  // namespace

std::string MultistationPathName(MultistationPath p) {
  switch (p) {
    case MultistationPath::kBallistic:
      return "ballistic";
    case MultistationPath::kCrossing:
      return "crossing";
    case MultistationPath::kTurn:
      return "turn";
  }
  return "?";
}

const io::OptionTable<MultistationOptions>& MultistationOptions::Table() {
  using O = MultistationOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Integer("--stations", &O::stations, "", io::Bounds::Closed(2, 4), "Number of stations, 2..4")
          .Real("--baseline", &O::baseline_km, "km", io::Bounds::Positive().Finite(),
                "Distance from station 1 to station 2 (km); the other stations scale with it")
          .Real("--duration", &O::duration_s, "s", io::Bounds::Positive().Finite(), "Length of the trial (s)")
          .Real("--rate", &O::rate_hz, "Hz", io::Bounds::Positive().Finite(),
                "Frame rate of station 1 (Hz); stations 2, 3, 4 run at 1.25, 0.8, 1.5 times it, each with a "
                "random phase")
          .Real("--sigma-angle", &O::sigma_angle_arcsec, "arcsec", io::Bounds::Positive().Finite(),
                "1 sigma of the angle noise across the line of sight (arcsec)")
          .Integer("--range-stations", &O::range_stations, "", io::Bounds::Closed(0, 4),
                   "The first N stations also measure range")
          .Real("--sigma-range", &O::sigma_range_m, "m", io::Bounds::Positive().Finite(), "1 sigma of a range (m)")
          .Choice("--path", &O::path, {MultistationPath::kBallistic, MultistationPath::kCrossing, MultistationPath::kTurn},
                  MultistationPathName,
                  "Target path: ballistic (arc to --apex), crossing (straight level pass eastward at --speed, "
                  "--height) or turn (climbing turn at --speed from --height)")
          .Choice("--layout", &O::layout, {{MultistationLayout::kTriangle, "triangle"}, {MultistationLayout::kLine, "line"}},
                  "Stations spread around the area (triangle) or nearly on a line eastward (line)")
          .Choice("--video", &O::video, {{"none", "none"}, {"mkv", "mkv"}, {"png", "png"}},
                  "Also write a trial folder for rk-run: each station rendered (mkv or png frames), with its frame "
                  "times, camera model, turret log and trial.json; none: only the located files")
          .Real("--apex", &O::apex_m, "m", io::Bounds::Positive().Finite(), "Ballistic apex height (m)")
          .Real("--speed", &O::speed_mps, "m/s", io::Bounds::Positive().Finite(), "Crossing speed (m/s)")
          .Real("--height", &O::height_m, "m", io::Bounds::Positive().Finite(), "Crossing height (m)")
          .Real("--origin-lat", &O::origin_lat_deg, "deg", io::Bounds::Closed(-89.0, 89.0), "Origin latitude (deg)")
          .Real("--origin-lon", &O::origin_lon_deg, "deg", io::Bounds::Closed(-180.0, 180.0),
                "Origin longitude (deg)")
          .Real("--origin-h", &O::origin_h_m, "m", io::Bounds::Closed(-500.0, 9000.0),
                "Origin ellipsoidal height (m)")
          .Count("--seed", &O::seed, "", io::Bounds::Any(), "Random seed");
  return table;
}

bool MultistationOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (range_stations > stations) {
    if (why) *why = "--range-stations must be <= --stations";
    return false;
  }
  std::vector<double> offsets;
  std::string w;
  if (!ParseTimeOffsets(&offsets, &w)) {
    if (why) *why = w;
    return false;
  }
  return true;
}

bool MultistationOptions::ParseTimeOffsets(std::vector<double>* offsets, std::string* why) const {
  offsets->assign(static_cast<std::size_t>(stations), 0.0);
  std::size_t pos = 0;
  while (pos < time_offsets.size()) {
    std::size_t end = time_offsets.find(',', pos);
    if (end == std::string::npos) end = time_offsets.size();
    const std::string item = time_offsets.substr(pos, end - pos);
    pos = end + 1;
    const std::size_t colon = item.find(':');
    const std::string name = item.substr(0, colon == std::string::npos ? item.size() : colon);
    int index = -1;
    for (int s = 0; s < stations; ++s) {
      if (name == "s" + std::to_string(s + 1)) index = s;
    }
    if (colon == std::string::npos || index < 0) {
      *why = "--time-offsets: '" + item + "' is not STATION:SECONDS with STATION one of s1..s" + std::to_string(stations);
      return false;
    }
    const std::string value = item.substr(colon + 1);
    char* stop = nullptr;
    const double x = std::strtod(value.c_str(), &stop);
    if (value.empty() || *stop != '\0' || !std::isfinite(x) || std::abs(x) > kMaxTimeOffsetS) {
      *why = "--time-offsets: '" + value + "' (for " + name + ") is not a number of seconds within ±10";
      return false;
    }
    (*offsets)[static_cast<std::size_t>(index)] = x;
  }
  return true;
}

struct MultistationScenario::Impl {
  geo::LocalEnu origin;
  std::vector<geo::LocalEnu> station;
  explicit Impl(const geo::Geodetic& o) : origin(o) {}
};

MultistationScenario::~MultistationScenario() = default;

MultistationScenario::MultistationScenario(const MultistationOptions& options)
    : o_(options) {
  std::string why;
  if (!o_.Check(&why)) throw UsageError(why);
  impl_ = std::make_unique<Impl>(geo::Geodetic{o_.origin_lat_deg, o_.origin_lon_deg, o_.origin_h_m});
  const double b = 1000.0 * o_.baseline_km;
  std::vector<double> offsets;
  o_.ParseTimeOffsets(&offsets, &why);
  const auto& layout = o_.layout == MultistationLayout::kLine ? kLineLayout : kLayout;
  for (int s = 0; s < o_.stations; ++s) {
    SimStation st;
    st.name = "s" + std::to_string(s + 1);
    st.time_offset_s = offsets[static_cast<std::size_t>(s)];
    st.p_enu = {layout[s][0] * b, layout[s][1] * b, layout[s][2]};
    const geo::Geodetic g = impl_->origin.ToGeodetic(st.p_enu);
    st.lat_deg = g.lat_deg;
    st.lon_deg = g.lon_deg;
    st.h_m = g.h_m;
    impl_->station.emplace_back(g);
    st.has_range = s < o_.range_stations;
    stations_.push_back(st);
  }
  for (std::size_t s = 0; s < stations_.size(); ++s) Measure(s, s);
}

Eigen::Vector3d MultistationScenario::Position(double t) const {
  const double b = 1000.0 * o_.baseline_km;
  if (o_.path == MultistationPath::kBallistic) {
    const double vu = std::sqrt(2.0 * kGravityMps2 * o_.apex_m);
    const Eigen::Vector3d p0(0.5 * b, 0.35 * b, 0.0), v0(120.0, 160.0, vu);
    return p0 + v0 * t + Eigen::Vector3d(0.0, 0.0, -0.5 * kGravityMps2 * t * t);
  }
  if (o_.path == MultistationPath::kTurn) {
    const double r = kTurnRadius * b, w = o_.speed_mps / r;
    return {kTurnCentre[0] * b + r * std::cos(w * t), kTurnCentre[1] * b + r * std::sin(w * t),
            o_.height_m + kTurnClimbMps * t};
  }
  const Eigen::Vector3d p0(0.5 * b - 0.5 * o_.speed_mps * o_.duration_s, 0.45 * b, o_.height_m);
  return p0 + Eigen::Vector3d(o_.speed_mps, 0.0, 0.0) * t;
}

Eigen::Vector3d MultistationScenario::Velocity(double t) const {
  if (o_.path == MultistationPath::kBallistic) {
    const double vu = std::sqrt(2.0 * kGravityMps2 * o_.apex_m);
    return {120.0, 160.0, vu - kGravityMps2 * t};
  }
  if (o_.path == MultistationPath::kTurn) {
    const double r = kTurnRadius * 1000.0 * o_.baseline_km, w = o_.speed_mps / r;
    return {-o_.speed_mps * std::sin(w * t), o_.speed_mps * std::cos(w * t), kTurnClimbMps};
  }
  return {o_.speed_mps, 0.0, 0.0};
}

Eigen::Vector3d MultistationScenario::Geodetic(const Eigen::Vector3d& p) const {
  const geo::Geodetic g = impl_->origin.ToGeodetic(p);
  return {g.lat_deg, g.lon_deg, g.h_m};
}

Eigen::Vector3d MultistationScenario::AzElRange(std::size_t s, const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = StationEnu(s, p);
  return {geo::WrapTwoPi(std::atan2(d(0), d(1))), std::atan2(d(2), std::hypot(d(0), d(1))), d.norm()};
}

void MultistationScenario::Measure(std::size_t s, std::uint64_t index) {
  SimStation& st = stations_[s];
  std::mt19937_64 phase_rng = RandomStream(o_.seed, kStreamPhase, index);
  std::mt19937_64 rng = RandomStream(o_.seed, kStreamNoise, index);
  std::normal_distribution<double> n01(0.0, 1.0);
  const double rate = o_.rate_hz * kRateFactor[s];
  const double phase = std::uniform_real_distribution<double>(0.0, 1.0 / rate)(phase_rng);
  const double sigma = o_.sigma_angle_arcsec / geo::kArcsecPerRad;
  for (long k = 0;; ++k) {
    const double t = phase + static_cast<double>(k) / rate;
    if (t > o_.duration_s) break;
    const Eigen::Vector3d aer = AzElRange(s, Position(t));
    const double saz = sigma / std::max(std::cos(aer(1)), 1e-6);
    st.true_t_s.push_back(t);
    st.t_s.push_back(t - st.time_offset_s);
    st.true_az_deg.push_back(geo::RadToDeg(aer(0)));
    st.true_el_deg.push_back(geo::RadToDeg(aer(1)));
    st.true_range_m.push_back(aer(2));
    st.az_deg.push_back(geo::WrapDeg360(geo::RadToDeg(aer(0) + saz * n01(rng))));
    st.el_deg.push_back(geo::RadToDeg(aer(1) + sigma * n01(rng)));
    st.range_m.push_back(aer(2) + o_.sigma_range_m * n01(rng));
    st.sigma_az_deg.push_back(geo::RadToDeg(saz));
    st.sigma_el_deg.push_back(geo::RadToDeg(sigma));
  }
}

io::CsvWriter MultistationScenario::LocatedCsv(std::size_t s) const {
  const SimStation& st = stations_[s];
  formats::LocatedLayout layout;
  layout.sigma_angle_decimals = 12;
  layout.sigma_length_decimals = kMetreDecimals;
  formats::LocatedWriter w(layout);
  for (std::size_t i = 0; i < st.t_s.size(); ++i) {
    formats::LocatedRecord r;
    r.t_s = st.t_s[i];
    const double a = geo::DegToRad(st.az_deg[i]), e = geo::DegToRad(st.el_deg[i]);
    r.az_rad = a;
    r.el_rad = e;
    if (st.has_range) {
      const double range = st.range_m[i];
      r.range_m = range;
      r.enu_m = Eigen::Vector3d(range * std::sin(a) * std::cos(e), range * std::cos(a) * std::cos(e), range * std::sin(e));
      r.sigma_range_m = o_.sigma_range_m;
    }
    r.sigma_az_rad = geo::DegToRad(st.sigma_az_deg[i]);
    r.sigma_el_rad = geo::DegToRad(st.sigma_el_deg[i]);
    w.Add(r);
  }
  return w.Take();
}

io::Json MultistationScenario::StationsJson() const {
  formats::StationsFile f;
  f.origin = {o_.origin_lat_deg, o_.origin_lon_deg, o_.origin_h_m};
  f.origin_given = true;
  for (const SimStation& st : stations_) {
    formats::StationSpec spec;
    spec.name = st.name;
    spec.position = {st.lat_deg, st.lon_deg, st.h_m};
    spec.located = st.name + "/located.csv";
    f.stations.push_back(spec);
  }
  return formats::StationsJson(f);
}

io::CsvWriter MultistationScenario::TruthCsv() const {
  std::vector<double> t;
  for (const SimStation& st : stations_) t.insert(t.end(), st.true_t_s.begin(), st.true_t_s.end());
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  io::CsvWriter w({"t_s", "e_m", "n_m", "u_m", "lat_deg", "lon_deg", "h_m", "ve_mps", "vn_mps", "vu_mps"});
  for (double ts : t) {
    const Eigen::Vector3d p = Position(ts), g = Geodetic(p), v = Velocity(ts);
    w.Add(ts, kTimeDecimals);
    for (int c = 0; c < 3; ++c) w.Add(p(c), kMetreDecimals);
    w.Add(g(0), 10).Add(g(1), 10).Add(g(2), kMetreDecimals);
    for (int c = 0; c < 3; ++c) w.Add(v(c), kMetreDecimals);
    w.EndRow();
  }
  return w;
}

Eigen::Vector3d MultistationScenario::StationEnu(std::size_t s, const Eigen::Vector3d& p_enu) const {
  return impl_->station[s].ToEnu(impl_->origin.ToGeodetic(p_enu));
}

namespace {

// The beacon simulation of station s (its own frame rate and phase, the target as seen from it).
BeaconSimOptions RenderedStation(const MultistationScenario& sim, std::size_t s) {
  const MultistationOptions& o = sim.options();
  const SimStation& st = sim.stations()[s];
  BeaconSimOptions b;
  CameraPreset("small", &b.camera);
  b.camera_preset = "small";
  b.fps = o.rate_hz * kRateFactor[s];
  b.t0_s = st.t_s.front();  // the station's phase, as its located rows
  b.duration_s = o.duration_s - b.t0_s;
  // The lamps merge into one spot at kilometres: a peak that stays below saturation when they add up.
  b.peak_dn = kRenderedPeakDn;
  b.range_noise_mm = 1000.0 * o.sigma_range_m;
  b.seed = o.seed * kStationSeedStride + s + 1;
  // The station's camera clock reads t; the target is where it is at the true time t + offset.
  const double offset = st.time_offset_s;
  b.target_enu = [&sim, s, offset](double t) { return sim.StationEnu(s, sim.Position(t + offset)); };
  return b;
}

// trial.json of the rendered stations.
void WriteRenderedManifest(const MultistationScenario& sim, const TrialFolder& folder,
                           std::vector<trial::StationEntry> stations, const io::Json& summaries) {
  const MultistationOptions& o = sim.options();
  trial::Manifest m;
  m.name = folder.stem();
  m.epoch_utc = kRenderedEpochUtc;
  m.stations = std::move(stations);
  m.origin = {{"lat_deg", o.origin_lat_deg}, {"lon_deg", o.origin_lon_deg}, {"h_m", o.origin_h_m}};
  m.steps = {{"intersect", {{"smooth", true}}}};
  io::Json simj;
  simj["generator"] = "rk-sim multistation";
  simj["seed"] = o.seed;
  simj["options"] = o.ToJson();
  simj["truth"] = {{"trajectory", "truth.csv"}, {"stations", "<station>/truth/"}};
  simj["summary"] = summaries;
  m.extra["sim"] = simj;
  trial::WriteManifest(folder.Path(trial::kManifestFile), m);
}

}  // namespace

void WriteMultistationTrial(const MultistationScenario& sim, const std::string& out_dir, bool force) {
  TrialFolder folder(out_dir, force);
  for (std::size_t s = 0; s < sim.stations().size(); ++s) {
    folder.MakeSubfolder(sim.stations()[s].name);
    io::WriteFileAtomic(folder.Path(sim.stations()[s].name + "/located.csv"), sim.LocatedCsv(s).str());
  }
  io::WriteFileAtomic(folder.Path("stations.json"), sim.StationsJson().dump(2) + "\n");
  io::WriteFileAtomic(folder.Path("truth.csv"), sim.TruthCsv().str());
  if (sim.options().video != "none") {
    std::vector<trial::StationEntry> entries;
    io::Json summaries = io::Json::object();
    for (std::size_t s = 0; s < sim.stations().size(); ++s) {
      const SimStation& st = sim.stations()[s];
      const BeaconSimulator beacon(RenderedStation(sim, s));
      TrialWriteOptions w;
      w.format = sim.options().video;
      w.station_lat_deg = st.lat_deg;
      w.station_lon_deg = st.lon_deg;
      w.station_h_m = st.h_m;
      TrialSummary sum;
      entries.push_back(WriteBeaconStation(beacon, w, folder.Path(""), st.name, st.has_range, &sum));
      summaries[st.name] = sum.ToJson();
    }
    WriteRenderedManifest(sim, folder, std::move(entries), summaries);
  }
  folder.Commit();
}

}  // namespace rk::sim

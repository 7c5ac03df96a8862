#include "sim/radar_scenario.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "geo/angles.h"
#include "geo/wgs84.h"
#include "io/csv.h"
#include "io/error.h"
#include "sim/trial_folder.h"
#include "trial/layout.h"
#include "trial/manifest.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace {

constexpr int kRangeDecimals = 3;
constexpr int kLatLonDecimals = 10;
constexpr int kHeightDecimals = 4;
constexpr int kPaperTargets = 5;
// Random extra targets: horizontal speed range (m/s).
constexpr double kExtraMinSpeed = 50.0, kExtraMaxSpeed = 400.0;
// Clutter box when there is no target to span it.
constexpr double kNoTargetMinRangeM = 1000.0, kNoTargetMaxRangeM = 300000.0;
constexpr double kNoTargetMinElRad = -geo::kPi / 6, kNoTargetMaxElRad = geo::kPi / 3;


// WGS-84 geometry of the common frame (geo/wgs84.h).
struct CommonFrame {
  Eigen::Vector3d origin_ecef;
  Eigen::Matrix3d R_ecef_enu0;
  CommonFrame(double lat0, double lon0, double h0) { origin_ecef = geo::EcefFromGeodetic({lat0, lon0, h0}, &R_ecef_enu0); }
  Eigen::Vector3d Ecef(const Eigen::Vector3d& enu) const { return origin_ecef + R_ecef_enu0 * enu; }
  // Geodetic (deg, deg, m) and the local ENU axes there.
  Eigen::Vector3d Geodetic(const Eigen::Vector3d& enu, Eigen::Matrix3d* R_ecef_enu) const {
    const geo::Geodetic g = geo::GeodeticFromEcef(Ecef(enu));
    if (R_ecef_enu) geo::EcefFromGeodetic(g, R_ecef_enu);
    return Eigen::Vector3d(g.lat_deg, g.lon_deg, g.h_m);
  }
};

// SPEC.md §3: R_enu_B = Rz(−ϑ)·Rx(−ϕ)·Ry(−α) from elementary rotations.
Eigen::Matrix3d RotationEnuFromBody(const Eigen::Vector3d& att) {
  return (Eigen::AngleAxisd(-att[0], Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(-att[1], Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(-att[2], Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

// (r, θ, φ) of a body-frame vector (x right, y forward, z up): θ clockwise from forward.
Eigen::Vector3d Spherical(const Eigen::Vector3d& d) {
  return Eigen::Vector3d(d.norm(), geo::WrapTwoPi(std::atan2(d.x(), d.y())), std::atan2(d.z(), std::hypot(d.x(), d.y())));
}

Eigen::Vector3d Measure(const CommonFrame& frame, const Eigen::Vector3d& target_enu, const Eigen::Vector3d& platform_enu,
                        const Eigen::Matrix3d& R_ecef_enu_platform, const Eigen::Vector3d& att) {
  const Eigen::Vector3d d_ecef = frame.Ecef(target_enu) - frame.Ecef(platform_enu);
  const Eigen::Vector3d d_enu = R_ecef_enu_platform.transpose() * d_ecef;
  return Spherical(RotationEnuFromBody(att).transpose() * d_enu);
}

}  // namespace

Eigen::Vector3d TrueRadarMeasurement(const Eigen::Vector3d& target_enu, const Eigen::Vector3d& platform_enu,
                                     const Eigen::Vector3d& attitude, double origin_lat_deg, double origin_lon_deg,
                                     double origin_h_m) {
  const CommonFrame frame(origin_lat_deg, origin_lon_deg, origin_h_m);
  Eigen::Matrix3d R;
  frame.Geodetic(platform_enu, &R);
  return Measure(frame, target_enu, platform_enu, R, attitude);
}

const io::OptionTable<RadarSimOptions>& RadarSimOptions::Table() {
  using O = RadarSimOptions;
  using io::Bounds;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Integer("--scenario", &O::scenario, "", Bounds::Closed(1, 3),
                   "1 (attitude rates 2e-3 rad/s), 2 (slow attitude: 8e-4 rad/s), 3 (scenario 1 + "
                   "Poisson clutter, mean 5 per radar per scan)")
          .Integer("--steps", &O::steps, "", Bounds::Closed(1, 100000), "Scans per radar")
          .Real("--dt", &O::dt_s, "s", Bounds::LeftOpen(0, 3600), "Scan interval (s)")
          .Real("--t0", &O::t0_s, "s", Bounds::AtLeast(0), "Time of scan 0 since the epoch (s)")
          .Integer("--targets", &O::targets, "", Bounds::Closed(0, 100),
                   "Number of targets (the first five are the paper's; more are random)")
          .Real("--pd", &O::detection_probability, "", Bounds::LeftOpen(0, 1),
                "Detection probability of each target per scan")
          .Count("--seed", &O::seed, "", Bounds::Any(), "Random seed (same seed, same files)")
          .Real("--time-offset-b", &O::time_offset_b_s, "s", Bounds::Any(),
                "Radar b scans this many seconds after radar a")
          .Real("--nav-rate", &O::nav_rate_hz, "Hz", Bounds::Closed(0, 1000),
                "Nav log rate (Hz); 0 = nav rows at the plot times")
          .Real("--attitude-noise-deg", &O::attitude_noise_deg, "deg", Bounds::RightOpen(0, geo::RadToDeg(0.1)),
                "1-sigma noise of the nav attitude angles (deg)")
          .Choice("--index-unit", &O::index_unit, {{RadarIndexUnit::kStep, "step"}, {RadarIndexUnit::kSecond, "second"}},
                  "Reading of k in the paper's platform motion s(k) and attitudes v(k): second (k = t - t0 in s, "
                  "the paper's m/s and rad/s) or step (k = scan index)")
          .Real("--clutter-margin-m", &O::clutter_margin_m, "m", Bounds::AtLeast(0),
                "Clutter box margin in range around the targets (m)")
          .Real("--clutter-margin-deg", &O::clutter_margin_deg, "deg", Bounds::RightOpen(0, 180),
                "Clutter box margin in azimuth and elevation around the targets (deg)");
  return table;
}

const io::OptionTable<RadarTrialWriteOptions>& RadarTrialWriteOptions::Table() {
  static const io::OptionTable<RadarTrialWriteOptions> table = io::OptionTable<RadarTrialWriteOptions>().Flag(
      "--force", &RadarTrialWriteOptions::force, "Replace an existing non-empty --out folder");
  return table;
}

bool RadarSimOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!Table().Check(*this, why)) return false;
  if (!std::isfinite(t0_s)) return fail("--t0 must be finite");
  if (!(std::isfinite(clutter_rate) && clutter_rate <= 1000)) return fail("clutter rate must be <= 1000 per scan");
  if (!(origin_lat_deg >= -89 && origin_lat_deg <= 89)) return fail("origin latitude must be in [-89, 89] deg");
  if (!std::isfinite(origin_lon_deg) || !(std::abs(origin_h_m) <= 1e5)) return fail("origin longitude/height invalid");
  if (!(std::abs(time_offset_b_s) < 0.5 * dt_s)) return fail("radar b time offset must be below half the scan interval");
  if (t0_s + std::min(0.0, time_offset_b_s) < 0) return fail("t0 + radar b time offset must be >= 0 s");
  if (names[0].empty() || names[1].empty() || names[0] == names[1]) return fail("radar names must be two distinct names");
  for (const auto& n : names) {
    if (n.find_first_of(",\"\n\r") != std::string::npos) return fail("radar names must not contain , \" or line breaks");
  }
  return true;
}

io::Json RadarSimOptions::ToJson() const {
  const io::Json sim = RadarSimOptionsToJson(*this);
  io::Json j = Table().ToJson(*this);
  for (const char* key : {"clutter_rate", "origin", "names", "two_d"}) {
    if (sim.contains(key)) j[key] = sim[key];
  }
  return j;
}

io::Json RadarSimOptionsToJson(const RadarSimOptions& o) {
  io::Json j;
  j["scenario"] = o.scenario;
  j["steps"] = o.steps;
  j["dt_s"] = o.dt_s;
  j["t0_s"] = o.t0_s;
  j["targets"] = o.targets;
  j["clutter_rate"] = o.ClutterRate();
  j["detection_probability"] = o.detection_probability;
  j["origin"] = {{"lat_deg", o.origin_lat_deg}, {"lon_deg", o.origin_lon_deg}, {"h_m", o.origin_h_m}};
  j["time_offset_b_s"] = o.time_offset_b_s;
  j["nav_rate_hz"] = o.nav_rate_hz;
  j["attitude_noise_deg"] = geo::RadToDeg(o.attitude_noise_rad());
  j["index_unit"] = o.index_unit == RadarIndexUnit::kStep ? "step" : "second";
  j["clutter_margin_m"] = o.clutter_margin_m;
  j["clutter_margin_deg"] = geo::RadToDeg(o.clutter_margin_rad());
  j["names"] = {o.names[0], o.names[1]};
  if (o.two_d[0] || o.two_d[1]) {  // only with --2d: the files of a 3-D trial stay as they were
    j["two_d"] = io::Json::array();
    for (int r = 0; r < 2; ++r) {
      if (o.two_d[r]) j["two_d"].push_back(o.names[r]);
    }
  }
  j["seed"] = o.seed;
  return j;
}

namespace {

// The two platforms of seed 002 §4.1: positions, motion, biases; attitude rates per scenario.
std::array<RadarPlatformSpec, 2> PaperPlatforms(int scenario) {
  std::array<RadarPlatformSpec, 2> platforms;
  RadarPlatformSpec& a = platforms[0];
  a.p0_enu = Eigen::Vector3d(-10000, -20000, 40000);
  a.p_rate = Eigen::Vector3d(0, 200, 0);
  a.bias = {1200.0, 0.0105, 0.0035, 0.0105, 0.0035, 0.0035};
  RadarPlatformSpec& b = platforms[1];
  b.p0_enu = Eigen::Vector3d(20000, 20000, 20000);
  b.p_rate = Eigen::Vector3d(10, 8, 0);
  b.bias = {1000.0, 0.0087, 0.0047, 0.0087, 0.0047, 0.0037};
  if (scenario == 2) {
    a.att0 = Eigen::Vector3d(0, 0.01, 0.01);
    a.att_rate = Eigen::Vector3d(8e-4, 8e-4, 8e-4);
    b.att_rate = Eigen::Vector3d(8e-4, 4e-4, 4e-4);
  } else {
    a.att0 = Eigen::Vector3d(0, 0.01, 0.01);
    a.att_rate = Eigen::Vector3d(0.002, 0.002, 0.002);
    b.att_rate = Eigen::Vector3d(0.002, 0.001, 0.001);
  }
  return platforms;
}

// The paper's five targets, then random ones (stream 1).
std::vector<RadarTargetSpec> MakeTargets(const RadarSimOptions& opt) {
  std::vector<RadarTargetSpec> targets;
  const double paper[kPaperTargets][6] = {{10000, 55, 1000, 150, 50000, 0},
                                          {9000, 50, 900, 150, 50000, 0},
                                          {1000, 250, 3000, -10, 10000, 0},
                                          {15000, -10, 500, 50, 15000, 0},
                                          {3000, 300, 3600, 400, 20000, 0}};
  std::mt19937_64 rng_targets = SplitSeedStream(opt.seed, 1);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int i = 0; i < opt.targets; ++i) {
    RadarTargetSpec t;
    if (i < kPaperTargets) {
      t.p0_enu = Eigen::Vector3d(paper[i][0], paper[i][2], paper[i][4]);
      t.v_enu = Eigen::Vector3d(paper[i][1], paper[i][3], paper[i][5]);
    } else {
      t.p0_enu = Eigen::Vector3d(1000 + 14000 * u01(rng_targets), 500 + 3100 * u01(rng_targets),
                                 10000 + 40000 * u01(rng_targets));
      const double speed = kExtraMinSpeed + (kExtraMaxSpeed - kExtraMinSpeed) * u01(rng_targets);
      const double dir = geo::kTwoPi * u01(rng_targets);
      t.v_enu = Eigen::Vector3d(speed * std::sin(dir), speed * std::cos(dir), 0);
    }
    targets.push_back(t);
  }
  return targets;
}

// Where a scan's clutter falls: around the true measurements of the targets (range, elevation, azimuth
// offsets from their circular mean a_mid) widened by the margins, or a fixed box without targets.
struct ClutterBox {
  double r_lo, r_hi, e_lo, e_hi, a_lo, a_hi, a_mid;
};
ClutterBox ClutterBoxOf(const RadarSimOptions& opt, double rmin, double rmax, double emin, double emax, double ss,
                        double cs, const std::vector<double>& az_true) {
  double r_lo = kNoTargetMinRangeM, r_hi = kNoTargetMaxRangeM, e_lo = kNoTargetMinElRad, e_hi = kNoTargetMaxElRad;
  double a_lo = 0, a_hi = geo::kTwoPi, a_mid = 0;
  if (opt.targets > 0) {
    r_lo = std::max(1.0, rmin - opt.clutter_margin_m);
    r_hi = rmax + opt.clutter_margin_m;
    e_lo = std::max(-geo::kPi / 2, emin - opt.clutter_margin_rad());
    e_hi = std::min(geo::kPi / 2, emax + opt.clutter_margin_rad());
    a_mid = std::atan2(ss, cs);
    double off_lo = INFINITY, off_hi = -INFINITY;
    for (double az : az_true) {
      const double off = geo::WrapPi(az - a_mid);
      off_lo = std::min(off_lo, off);
      off_hi = std::max(off_hi, off);
    }
    a_lo = off_lo - opt.clutter_margin_rad();
    a_hi = off_hi + opt.clutter_margin_rad();
    if (a_hi - a_lo >= geo::kTwoPi) {
      a_lo = 0;
      a_hi = geo::kTwoPi;
      a_mid = 0;
    }
  }
  return {r_lo, r_hi, e_lo, e_hi, a_lo, a_hi, a_mid};
}

}  // namespace

RadarSimulator::RadarSimulator(RadarSimOptions opt) : opt_(std::move(opt)) {
  std::string why;
  if (!opt_.Check(&why)) throw UsageError(why);
  platforms_ = PaperPlatforms(opt_.scenario);
  targets_ = MakeTargets(opt_);
  // One normal distribution for the plot noise and the nav noise: it keeps the second value of each
  // pair it draws, and the nav's first draw may be the plots' last one.
  std::normal_distribution<double> gauss(0.0, 1.0);
  SimulateScans(&gauss);
  SimulateNav(&gauss);
}

void RadarSimulator::SimulateScans(std::normal_distribution<double>* gauss_noise) {
  std::normal_distribution<double>& gauss = *gauss_noise;
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const CommonFrame frame(opt_.origin_lat_deg, opt_.origin_lon_deg, opt_.origin_h_m);
  std::array<std::mt19937_64, 2> rng_noise{SplitSeedStream(opt_.seed, 2), SplitSeedStream(opt_.seed, 3)};
  std::mt19937_64 rng_detect = SplitSeedStream(opt_.seed, 4), rng_clutter = SplitSeedStream(opt_.seed, 5),
                  rng_shuffle = SplitSeedStream(opt_.seed, 6);
  std::poisson_distribution<int> poisson(std::max(opt_.ClutterRate(), 1e-300));
  const bool clutter = opt_.ClutterRate() > 0;

  std::vector<SimRadarPlot> scan;
  for (int k = 0; k < opt_.steps; ++k) {
    for (int r = 0; r < 2; ++r) {
      const RadarPlatformSpec& ps = platforms_[r];
      const double t = ScanTime(r, k);
      const Eigen::Vector3d s_enu = PlatformEnu(r, t), att = PlatformAttitude(r, t);
      Eigen::Matrix3d R_ecef_enu;
      frame.Geodetic(s_enu, &R_ecef_enu);
      scan.clear();
      double rmin = INFINITY, rmax = -INFINITY, emin = INFINITY, emax = -INFINITY;
      double ss = 0, cs = 0;
      std::vector<double> az_true;
      for (int i = 0; i < opt_.targets; ++i) {
        const Eigen::Vector3d m = Measure(frame, TargetEnu(i, t), s_enu, R_ecef_enu, att);
        rmin = std::min(rmin, m[0]);
        rmax = std::max(rmax, m[0]);
        emin = std::min(emin, m[2]);
        emax = std::max(emax, m[2]);
        ss += std::sin(m[1]);
        cs += std::cos(m[1]);
        az_true.push_back(m[1]);
        const double n0 = gauss(rng_noise[r]), n1 = gauss(rng_noise[r]), n2 = gauss(rng_noise[r]);
        if (u01(rng_detect) >= opt_.detection_probability) {
          ++missed_;
          continue;
        }
        SimRadarPlot p;
        p.t_s = t;
        p.radar = r;
        p.target = i;
        p.range_m = m[0] + ps.bias[0] + ps.sigma_range_m * n0;
        p.az_rad = geo::WrapTwoPi(m[1] + ps.bias[1] + ps.sigma_az_rad * n1);
        p.el_rad = m[2] + ps.bias[2] + ps.sigma_el_rad * n2;
        if (std::abs(p.el_rad) > geo::kPi / 2) {
          p.el_rad = std::copysign(geo::kPi / 2, p.el_rad);
          ++el_clamped_;
        }
        scan.push_back(p);
      }
      if (clutter) {
        const auto [r_lo, r_hi, e_lo, e_hi, a_lo, a_hi, a_mid] =
            ClutterBoxOf(opt_, rmin, rmax, emin, emax, ss, cs, az_true);
        const int n = poisson(rng_clutter);
        for (int c = 0; c < n; ++c) {
          SimRadarPlot p;
          p.t_s = t;
          p.radar = r;
          p.range_m = r_lo + (r_hi - r_lo) * u01(rng_clutter);
          p.az_rad = geo::WrapTwoPi(a_mid + a_lo + (a_hi - a_lo) * u01(rng_clutter));
          p.el_rad = e_lo + (e_hi - e_lo) * u01(rng_clutter);
          scan.push_back(p);
          ++clutter_plots_;
        }
      }
      std::shuffle(scan.begin(), scan.end(), rng_shuffle);
      plots_.insert(plots_.end(), scan.begin(), scan.end());
    }
  }
  std::stable_sort(plots_.begin(), plots_.end(),
                   [](const SimRadarPlot& x, const SimRadarPlot& y) { return x.t_s < y.t_s; });
}

void RadarSimulator::SimulateNav(std::normal_distribution<double>* gauss_noise) {
  std::normal_distribution<double>& gauss = *gauss_noise;
  const CommonFrame frame(opt_.origin_lat_deg, opt_.origin_lon_deg, opt_.origin_h_m);
  std::mt19937_64 rng_nav = SplitSeedStream(opt_.seed, 7);
  std::vector<std::pair<double, int>> nav_times;
  if (opt_.nav_rate_hz > 0) {
    double tmin = INFINITY, tmax = -INFINITY;
    for (int r = 0; r < 2; ++r) {
      tmin = std::min(tmin, ScanTime(r, 0));
      tmax = std::max(tmax, ScanTime(r, opt_.steps - 1));
    }
    const long j0 = static_cast<long>(std::floor((tmin - opt_.t0_s) * opt_.nav_rate_hz));
    const long j1 = static_cast<long>(std::ceil((tmax - opt_.t0_s) * opt_.nav_rate_hz));
    for (long j = std::max(0L, j0); j <= j1; ++j) {
      for (int r = 0; r < 2; ++r) nav_times.emplace_back(opt_.t0_s + static_cast<double>(j) / opt_.nav_rate_hz, r);
    }
  } else {
    for (int k = 0; k < opt_.steps; ++k) {
      for (int r = 0; r < 2; ++r) nav_times.emplace_back(ScanTime(r, k), r);
    }
    std::stable_sort(nav_times.begin(), nav_times.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
  }
  for (const auto& [t, r] : nav_times) {
    SimNavRow row;
    row.t_s = t;
    row.radar = r;
    const Eigen::Vector3d g = frame.Geodetic(PlatformEnu(r, t), nullptr);
    row.lat_deg = g[0];
    row.lon_deg = g[1];
    row.h_m = g[2];
    const Eigen::Vector3d att = PlatformAttitude(r, t);
    const auto& bias = platforms_[r].bias;
    const double n0 = gauss(rng_nav), n1 = gauss(rng_nav), n2 = gauss(rng_nav);
    row.yaw_rad = att[0] + bias[3] + opt_.attitude_noise_rad() * n0;
    row.pitch_rad = att[1] + bias[4] + opt_.attitude_noise_rad() * n1;
    row.roll_rad = att[2] + bias[5] + opt_.attitude_noise_rad() * n2;
    nav_.push_back(row);
  }}

double RadarSimulator::Kappa(double t_s) const {
  const double dt = t_s - opt_.t0_s;
  return opt_.index_unit == RadarIndexUnit::kStep ? dt / opt_.dt_s : dt;
}

Eigen::Vector3d RadarSimulator::PlatformEnu(int radar, double t_s) const {
  return platforms_[radar].p0_enu + platforms_[radar].p_rate * Kappa(t_s);
}

Eigen::Vector3d RadarSimulator::PlatformAttitude(int radar, double t_s) const {
  return platforms_[radar].att0 + platforms_[radar].att_rate * Kappa(t_s);
}

Eigen::Vector3d RadarSimulator::TargetEnu(int target, double t_s) const {
  return targets_[target].p0_enu + targets_[target].v_enu * (t_s - opt_.t0_s);
}

Eigen::Vector3d RadarSimulator::Geodetic(const Eigen::Vector3d& enu) const {
  return CommonFrame(opt_.origin_lat_deg, opt_.origin_lon_deg, opt_.origin_h_m).Geodetic(enu, nullptr);
}

double RadarSimulator::ScanTime(int radar, int k) const {
  return opt_.t0_s + k * opt_.dt_s + (radar == 1 ? opt_.time_offset_b_s : 0.0);
}

io::Json RadarTrialSummary::ToJson() const {
  io::Json j;
  j["plots"] = plots;
  j["target_plots"] = target_plots;
  j["clutter_plots"] = clutter_plots;
  j["missed_detections"] = missed_detections;
  j["nav_rows"] = nav_rows;
  j["elevation_clamped"] = elevation_clamped;
  j["min_range_m"] = min_range_m;
  j["max_range_m"] = max_range_m;
  j["max_abs_pitch_deg"] = max_abs_pitch_deg;
  return j;
}

namespace {

// plots.csv; the plot counts and the range extremes of the target plots in `sum`.
io::CsvWriter PlotsCsv(const RadarSimulator& sim, RadarTrialSummary* out) {
  const RadarSimOptions& so = sim.options();
  RadarTrialSummary& sum = *out;
  sum.min_range_m = INFINITY;
  io::CsvWriter plots({"t_s", "radar", "range_m", "az_deg", "el_deg", "track_id"});
  for (const SimRadarPlot& p : sim.plots()) {
    plots.Add(p.t_s, kTimeDecimals).Add(so.names[p.radar]).Add(p.range_m, kRangeDecimals);
    plots.Add(geo::WrapDeg360(geo::RadToDeg(p.az_rad)), kAngleDecimals);
    if (so.two_d[p.radar]) {
      plots.AddEmpty();  // a 2-D radar's plot (SPEC.md §2.1)
    } else {
      plots.Add(geo::RadToDeg(p.el_rad), kAngleDecimals);
    }
    if (p.target >= 0) {
      plots.Add(p.target + 1);
      ++sum.target_plots;
      sum.min_range_m = std::min(sum.min_range_m, p.range_m);
      sum.max_range_m = std::max(sum.max_range_m, p.range_m);
    } else {
      plots.AddEmpty();
    }
    plots.EndRow();
  }
  if (sum.target_plots == 0) sum.min_range_m = 0;
  sum.plots = static_cast<std::int64_t>(sim.plots().size());
  sum.clutter_plots = sim.clutter_plots();
  sum.missed_detections = sim.missed_detections();
  sum.elevation_clamped = sim.elevation_clamped();
  return plots;
}

io::CsvWriter NavCsv(const RadarSimulator& sim, RadarTrialSummary* out) {
  const RadarSimOptions& so = sim.options();
  io::CsvWriter nav({"t_s", "radar", "lat_deg", "lon_deg", "h_m", "yaw_deg", "pitch_deg", "roll_deg"});
  for (const SimNavRow& n : sim.nav()) {
    nav.Add(n.t_s, kTimeDecimals).Add(so.names[n.radar]).Add(n.lat_deg, kLatLonDecimals).Add(n.lon_deg, kLatLonDecimals);
    nav.Add(n.h_m, kHeightDecimals).Add(geo::WrapDeg360(geo::RadToDeg(n.yaw_rad)), kAngleDecimals);
    nav.Add(geo::WrapDeg180(geo::RadToDeg(n.pitch_rad)), kAngleDecimals);
    nav.Add(geo::WrapDeg180(geo::RadToDeg(n.roll_rad)), kAngleDecimals);
    nav.EndRow();
  }
  out->nav_rows = static_cast<std::int64_t>(sim.nav().size());
  return nav;
}

// truth/biases.csv, truth/targets.csv, truth/platforms.csv; the largest |pitch| in `sum`.
void WriteTruthTables(const RadarSimulator& sim, const TrialFolder& folder, RadarTrialSummary* out) {
  const RadarSimOptions& so = sim.options();
  RadarTrialSummary& sum = *out;
  // Truth: biases per scan (file units, the columns rk-register writes), targets, platforms.
  static const char* const kSuffix[6] = {"range_m", "az_deg", "el_deg", "yaw_deg", "pitch_deg", "roll_deg"};
  std::vector<std::string> bias_cols{"t_s"};
  for (int r = 0; r < 2; ++r) {
    for (const char* s : kSuffix) bias_cols.push_back(so.names[r] + "_" + s);
  }
  io::CsvWriter biases(bias_cols);
  io::CsvWriter targets({"t_s", "target", "e_m", "n_m", "u_m"});
  io::CsvWriter platforms(
      {"t_s", "radar", "e_m", "n_m", "u_m", "lat_deg", "lon_deg", "h_m", "yaw_deg", "pitch_deg", "roll_deg"});
  for (int k = 0; k < so.steps; ++k) {
    const double t_step = std::max(sim.ScanTime(0, k), sim.ScanTime(1, k));
    biases.Add(t_step, kTimeDecimals);
    for (int r = 0; r < 2; ++r) {
      for (int i = 0; i < 6; ++i) {
        const double b = sim.platforms()[r].bias[i];
        biases.Add(i == 0 ? b : geo::RadToDeg(b), kAngleDecimals);
      }
    }
    biases.EndRow();
    const double t = sim.ScanTime(0, k);
    for (int i = 0; i < so.targets; ++i) {
      const Eigen::Vector3d p = sim.TargetEnu(i, t);
      targets.Add(t, kTimeDecimals).Add(i + 1).Add(p.x(), kRangeDecimals).Add(p.y(), kRangeDecimals);
      targets.Add(p.z(), kRangeDecimals).EndRow();
    }
    for (int r = 0; r < 2; ++r) {
      const double tr = sim.ScanTime(r, k);
      const Eigen::Vector3d p = sim.PlatformEnu(r, tr), att = sim.PlatformAttitude(r, tr), g = sim.Geodetic(p);
      sum.max_abs_pitch_deg = std::max(sum.max_abs_pitch_deg, std::abs(geo::RadToDeg(att[1])));
      platforms.Add(tr, kTimeDecimals).Add(so.names[r]).Add(p.x(), kRangeDecimals).Add(p.y(), kRangeDecimals);
      platforms.Add(p.z(), kRangeDecimals).Add(g[0], kLatLonDecimals).Add(g[1], kLatLonDecimals).Add(g[2], kHeightDecimals);
      platforms.Add(geo::WrapDeg360(geo::RadToDeg(att[0])), kAngleDecimals);
      platforms.Add(geo::WrapDeg180(geo::RadToDeg(att[1])), kAngleDecimals);
      platforms.Add(geo::WrapDeg180(geo::RadToDeg(att[2])), kAngleDecimals).EndRow();
    }
  }
  biases.Write(folder.Path("truth/biases.csv"));
  targets.Write(folder.Path("truth/targets.csv"));
  platforms.Write(folder.Path("truth/platforms.csv"));
}

// scenario.json: the options, the platforms' biases and motion, the targets, the files, the summary.
io::Json RadarScenarioJson(const RadarSimulator& sim, const RadarTrialSummary& sum) {
  const RadarSimOptions& so = sim.options();
  io::Json j;
  j["generator"] = "rk-sim radar";
  j["seed_paper"] = "002 (Deng et al. 2024), section 4.1";
  j["scenario"] = so.scenario;
  j["seed"] = so.seed;
  j["options"] = RadarSimOptionsToJson(so);
  j["common_frame"] = "local ENU (x east, y north, z up, m) at the WGS-84 origin";
  io::Json radars;
  static const char* const kNames[6] = {"range_m", "az_deg", "el_deg", "yaw_deg", "pitch_deg", "roll_deg"};
  for (int r = 0; r < 2; ++r) {
    const RadarPlatformSpec& ps = sim.platforms()[r];
    io::Json rj;
    for (int i = 0; i < 6; ++i) rj["bias"][kNames[i]] = i == 0 ? ps.bias[i] : geo::RadToDeg(ps.bias[i]);
    rj["bias_rad"] = {ps.bias[1], ps.bias[2], ps.bias[3], ps.bias[4], ps.bias[5]};
    rj["sigma"] = {{"range_m", ps.sigma_range_m},
                   {"az_deg", geo::RadToDeg(ps.sigma_az_rad)},
                   {"el_deg", geo::RadToDeg(ps.sigma_el_rad)}};
    rj["position_enu_m"] = {{"at_0", {ps.p0_enu.x(), ps.p0_enu.y(), ps.p0_enu.z()}},
                            {"per_index", {ps.p_rate.x(), ps.p_rate.y(), ps.p_rate.z()}}};
    rj["attitude_rad"] = {{"at_0", {ps.att0.x(), ps.att0.y(), ps.att0.z()}},
                          {"per_index", {ps.att_rate.x(), ps.att_rate.y(), ps.att_rate.z()}}};
    radars[so.names[r]] = rj;
  }
  j["radars"] = radars;
  j["motion_model"] =
      "platform s(kappa) = at_0 + per_index*kappa, attitude (yaw, pitch, roll)(kappa) likewise, kappa = (t - t0)/dt "
      "(index_unit step) or t - t0 (second); target X(t) = X0 + V (t - t0)";
  io::Json tj = io::Json::array();
  for (std::size_t i = 0; i < sim.targets().size(); ++i) {
    const RadarTargetSpec& t = sim.targets()[i];
    tj.push_back({{"track_id", i + 1},
                  {"p0_enu_m", {t.p0_enu.x(), t.p0_enu.y(), t.p0_enu.z()}},
                  {"v_enu_mps", {t.v_enu.x(), t.v_enu.y(), t.v_enu.z()}}});
  }
  j["targets"] = tj;
  j["files"] = {{"plots", trial::kRadarPlotsFile},
                {"nav", trial::kRadarNavFile},
                {"truth_biases", "truth/biases.csv"},
                {"truth_targets", "truth/targets.csv"},
                {"truth_platforms", "truth/platforms.csv"}};
  j["summary"] = sum.ToJson();
  return j;
}

}  // namespace

RadarTrialSummary WriteRadarTrial(const RadarSimulator& sim, const RadarTrialWriteOptions& opt) {
  const RadarSimOptions& so = sim.options();
  TrialFolder folder(opt.out_dir, opt.force);
  folder.MakeSubfolder("truth");
  RadarTrialSummary sum;
  PlotsCsv(sim, &sum).Write(folder.Path(trial::kRadarPlotsFile));
  NavCsv(sim, &sum).Write(folder.Path(trial::kRadarNavFile));
  WriteTruthTables(sim, folder, &sum);
  io::WriteJson(folder.Path("scenario.json"), RadarScenarioJson(sim, sum));

  // Trial manifest (SPEC.md §6), so that rk-run processes the folder like a recorded trial; the station is the
  // origin of the common frame.
  trial::Manifest m;
  m.name = std::filesystem::path(opt.out_dir).lexically_normal().filename().string();
  if (m.name.empty()) m.name = std::filesystem::path(opt.out_dir).parent_path().filename().string();
  m.epoch_utc = opt.epoch_utc;
  m.Single().station = {{"lat_deg", so.origin_lat_deg}, {"lon_deg", so.origin_lon_deg}, {"h_m", so.origin_h_m}};
  m.radar = trial::RadarEntry{trial::kRadarPlotsFile, trial::kRadarNavFile};
  m.extra["sim"] = {{"generator", "rk-sim radar"},
                    {"scenario", "scenario.json"},
                    {"truth", {{"biases", "truth/biases.csv"}}}};
  trial::WriteManifest(folder.Path(trial::kManifestFile), m);
  folder.Commit();
  return sum;
}

}  // namespace rk::sim

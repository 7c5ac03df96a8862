// Two mobile radars observing common targets, with biases, noise, clutter and missed
// detections (rk-sim radar; seed 002, Deng et al. 2024, §4.1, scenarios 1–3).
//
// Common frame: local ENU (x east, y north, z up, m) with its origin at a stated WGS-84 point
// (default 25°N 110°E, h 0: near the paper's authors in Guilin; --origin). The paper's
// platform and target coordinates are in this frame; every geodetic conversion is geo/wgs84.h's
// (GeographicLib, WGS-84): common ENU → ECEF with the origin's ENU axes, platform geodetic
// position from ECEF.
// Time: scan k = 0 … N−1 at t_k = t0 + k·dt (dt = 5 s). The paper's expressions in k (platform
// positions s(k), attitudes v(k)) are evaluated at κ = t − t0 in seconds (--index-unit second,
// default: the paper gives their units as m, m/s, rad and rad/s, so 200 is a speed in m/s and
// 0.002 a rate in rad/s) or at κ = scan index (--index-unit step, the other reading),
// continuously in t for nav rows between scans. With the default, rk-register comes within about a
// point of the paper's accuracy figures (docs/benchmarks.md); the step reading carries 2–4 times
// less information. Targets are constant-velocity: X(t) = X0 + V (t − t0), velocities in m/s.
// Scenarios (rad, m):
//   radar a: σ_r 50, σ_θ = σ_φ = 0.0087; biases Δr 1200, Δθ 0.0105, Δφ 0.0035, Δϑ 0.0105,
//            Δϕ 0.0035, Δα 0.0035; s_a(κ) = [−10000, −20000 + 200κ, 40000].
//   radar b: σ as a; Δr 1000, Δθ 0.0087, Δφ 0.0047, Δϑ 0.0087, Δϕ 0.0047, Δα 0.0037;
//            s_b(κ) = [20000 + 10κ, 20000 + 8κ, 20000].
//   targets: [x, vx, y, vy, z, vz] = [10000,55,1000,150,50000,0], [9000,50,900,150,50000,0],
//            [1000,250,3000,−10,10000,0], [15000,−10,500,50,15000,0], [3000,300,3600,400,20000,0];
//            more targets (--targets > 5) are drawn at random (stream 1): position uniform in
//            the box of these five, horizontal speed uniform in [50, 400] m/s in a uniform
//            direction, vz = 0.
//   attitudes (yaw ϑ, pitch ϕ, roll α) of eq. 6:
//     scenario 1: a = [0.002κ, 0.01 + 0.002κ, 0.01 + 0.002κ], b = [0.002κ, 0.001κ, 0.001κ];
//     scenario 2: a = 1e−4·[8κ, 100 + 8κ, 100 + 8κ],        b = 1e−4·[8κ, 4κ, 4κ];
//     scenario 3: scenario 1 with Poisson clutter, mean 5 per radar per scan.
// Measurement of a target by radar i at time t (SPEC.md §3): d_enu = R_ecef_enuᵀ (X_ecef −
// s_ecef) at the platform, d_B = R_enu_Bᵀ d_enu with R_enu_B = Rz(−ϑ)·Rx(−ϕ)·Ry(−α) built from
// elementary rotations (deliberately not the registration module's eq. 6 code, so that tests
// can compare two independent implementations of SPEC.md §3), (r, θ, φ) from d_B (eq. 3
// inverted); measured = true + bias + N(0, σ²). Nav attitude = true + bias (+ optional noise).
// Each target is detected with probability p_D. Clutter: Poisson(λ) plots per radar per scan,
// uniform in (r, θ, φ) over the box spanned by the scan's true target measurements widened by
// clutter_margin_m in range and clutter_margin_rad in both angles (so clutter competes with
// the targets). Plots of a scan are shuffled (file order carries no association).
// Determinism: std::mt19937_64 streams seeded with seed_seq{seed, stream}: 1 extra targets,
// 2 noise of radar a, 3 noise of radar b, 4 detection, 5 clutter, 6 shuffle, 7 nav noise.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "geo/angles.h"
#include "io/json_util.h"
#include "io/options.h"

namespace rk::sim {

enum class RadarIndexUnit { kStep, kSecond };

struct RadarPlatformSpec {
  Eigen::Vector3d p0_enu = Eigen::Vector3d::Zero();      // s(0), common ENU (m)
  Eigen::Vector3d p_rate = Eigen::Vector3d::Zero();      // ds/dκ (m per κ unit)
  Eigen::Vector3d att0 = Eigen::Vector3d::Zero();        // (ϑ, ϕ, α)(0) (rad)
  Eigen::Vector3d att_rate = Eigen::Vector3d::Zero();    // d(ϑ, ϕ, α)/dκ (rad per κ unit)
  std::array<double, 6> bias{};                          // Δr (m), Δθ, Δφ, Δϑ, Δϕ, Δα (rad)
  double sigma_range_m = 50.0, sigma_az_rad = 0.0087, sigma_el_rad = 0.0087;
};

struct RadarTargetSpec {
  Eigen::Vector3d p0_enu = Eigen::Vector3d::Zero();  // m, common ENU at t0
  Eigen::Vector3d v_enu = Eigen::Vector3d::Zero();   // m/s
};

struct RadarSimOptions {
  int scenario = 1;                  // 1, 2 or 3
  int steps = 1000;                  // scans per radar, [1, 100000]
  double dt_s = 5.0;                 // scan interval (s), (0, 3600]
  double t0_s = 0.0;                 // time of scan 0 (s), >= 0
  int targets = 5;                   // [0, 100]; the first five are the paper's
  double clutter_rate = -1.0;        // mean clutter plots per radar per scan; < 0 = scenario default (3: 5, else 0)
  double detection_probability = 1.0;  // (0, 1]
  double origin_lat_deg = 25.0, origin_lon_deg = 110.0, origin_h_m = 0.0;
  double time_offset_b_s = 0.0;      // radar b's scans at t_k + offset, |offset| < dt/2
  double nav_rate_hz = 0.0;          // 0: nav rows at the plot times; > 0: a regular nav log at this rate
  double attitude_noise_deg = 0.0;   // 1-sigma noise of the nav attitude angles (not in the paper)
  RadarIndexUnit index_unit = RadarIndexUnit::kSecond;
  double clutter_margin_m = 20000.0;
  double clutter_margin_deg = 5.0;
  std::array<std::string, 2> names{"a", "b"};
  // Per radar: a 2-D radar, whose plots are written with an empty el_deg (SPEC.md §2.1; --2d). It is simulated
  // exactly as a 3-D one (same random streams, same true biases in truth/biases.csv, el bias included): only
  // the file leaves the elevation out.
  std::array<bool, 2> two_d{false, false};
  std::uint64_t seed = 1;

  // Every number and choice option; not in it: --clutter (negative = the scenario's default),
  // --origin, --names and --2d (composite values), registered by the app.
  static const io::OptionTable<RadarSimOptions>& Table();
  // Table().Check, then the clutter rate, the origin, radar b's offset and the names.
  bool Check(std::string* why) const;
  // The run report's "options": Table().ToJson plus the resolved clutter rate, the origin and the names.
  io::Json ToJson() const;
  double ClutterRate() const { return clutter_rate >= 0 ? clutter_rate : (scenario == 3 ? 5.0 : 0.0); }
  double attitude_noise_rad() const { return geo::DegToRad(attitude_noise_deg); }
  double clutter_margin_rad() const { return geo::DegToRad(clutter_margin_deg); }
};
io::Json RadarSimOptionsToJson(const RadarSimOptions& opt);

struct SimRadarPlot {
  double t_s = 0.0;
  int radar = 0;          // 0 = a, 1 = b
  double range_m = 0.0, az_rad = 0.0, el_rad = 0.0;  // measured; az in [0, 2π)
  int target = -1;        // 0-based target index, −1 = clutter
};

struct SimNavRow {
  double t_s = 0.0;
  int radar = 0;
  double lat_deg = 0.0, lon_deg = 0.0, h_m = 0.0;
  double yaw_rad = 0.0, pitch_rad = 0.0, roll_rad = 0.0;  // measured (true + bias + noise)
};

// True spherical measurement (r, θ, φ) of an ENU point from a platform at `platform_enu` with
// attitude (ϑ, ϕ, α), all in the common frame; exposed for tests.
Eigen::Vector3d TrueRadarMeasurement(const Eigen::Vector3d& target_enu, const Eigen::Vector3d& platform_enu,
                                     const Eigen::Vector3d& attitude, double origin_lat_deg,
                                     double origin_lon_deg, double origin_h_m);

class RadarSimulator {
 public:
  explicit RadarSimulator(RadarSimOptions opt);  // throws UsageError if Check fails

  const RadarSimOptions& options() const { return opt_; }
  const std::array<RadarPlatformSpec, 2>& platforms() const { return platforms_; }
  const std::vector<RadarTargetSpec>& targets() const { return targets_; }
  // κ at time t (scan index or seconds, per index_unit).
  double Kappa(double t_s) const;
  Eigen::Vector3d PlatformEnu(int radar, double t_s) const;
  Eigen::Vector3d PlatformAttitude(int radar, double t_s) const;  // true (ϑ, ϕ, α)
  Eigen::Vector3d TargetEnu(int target, double t_s) const;
  // Geodetic position (deg, deg, m) of a common-frame ENU point.
  Eigen::Vector3d Geodetic(const Eigen::Vector3d& enu) const;
  double ScanTime(int radar, int k) const;  // t_k (+ offset for radar b)

  const std::vector<SimRadarPlot>& plots() const { return plots_; }  // in time order
  const std::vector<SimNavRow>& nav() const { return nav_; }          // in time order
  std::int64_t clutter_plots() const { return clutter_plots_; }
  std::int64_t missed_detections() const { return missed_; }
  std::int64_t elevation_clamped() const { return el_clamped_; }

 private:
  void SimulateScans(std::normal_distribution<double>* gauss);  // plots_ and the counts, scan by scan
  void SimulateNav(std::normal_distribution<double>* gauss);    // nav_

  RadarSimOptions opt_;
  std::array<RadarPlatformSpec, 2> platforms_;
  std::vector<RadarTargetSpec> targets_;
  std::vector<SimRadarPlot> plots_;
  std::vector<SimNavRow> nav_;
  std::int64_t clutter_plots_ = 0, missed_ = 0, el_clamped_ = 0;
};

struct RadarTrialWriteOptions {
  std::string out_dir;
  bool force = false;
  std::string epoch_utc = "2026-01-01T00:00:00Z";  // trial epoch written to trial.json (t_s = 0)

  static const io::OptionTable<RadarTrialWriteOptions>& Table();  // --force (--out is registered by the app)
};

struct RadarTrialSummary {
  std::int64_t plots = 0, target_plots = 0, clutter_plots = 0, missed_detections = 0, nav_rows = 0;
  std::int64_t elevation_clamped = 0;
  double min_range_m = 0.0, max_range_m = 0.0;
  double max_abs_pitch_deg = 0.0;  // largest |true pitch| (eq. 6 angle; may exceed 90)
  io::Json ToJson() const;
};

// Writes plots.csv, nav.csv, truth/biases.csv, truth/targets.csv, truth/platforms.csv, scenario.json and
// trial.json (the SPEC.md §6 manifest with its radar block, for rk-run; docs/rk-sim.md) into a new folder,
// atomically (sim/trial_folder.h).
RadarTrialSummary WriteRadarTrial(const RadarSimulator& sim, const RadarTrialWriteOptions& opt);

}  // namespace rk::sim

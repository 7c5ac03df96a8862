// rk-locate with a pointing model (SPEC.md §3.1), the camera's time offset, the 1σ columns and WGS-84:
//   - camera::ApplyPointing (the equivalent §3 boresight and mount) is exact;
//   - the automatic-differentiation Jacobian of the located row equals a numerical one;
//   - a time offset moves the interpolation time and the output t_s;
//   - NEES of (az, el) over Monte Carlo beacon trials with a known pointing-model error, camera-calibration
//     error, pixel noise and encoder quantisation (one draw per dwell of a still turret);
//   - az/el error with the true pointing model equals the perfect station's; without it, degrees.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>
#include <random>

#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "geo/pointing.h"
#include "geo/wgs84.h"
#include "locate/locate.h"
#include "locate/locate_sigma.h"
#include "camera/station_view.h"
#include "test_cameras.h"

namespace rk::locate {
namespace {

using test_data::DistortedMisalignedCamera;

// Two rotation products that are equal in exact arithmetic agree to rounding.
constexpr double kExactTolerance_rad = 1e-12;
// Central differences with h = 1e-6 (angles, px, mm, m): truncation ~h², rounding ~1e-16/h.
constexpr double kJacobianRelTolerance = 1e-5;

geo::PointingTerms SomeTerms() {
  return {geo::DegToRad(123.4), geo::DegToRad(0.3), geo::DegToRad(-0.2), geo::DegToRad(0.15)};
}

TEST(StationView, EquivalentBoresightAndMountAreExact) {
  const camera::CameraModel cam = DistortedMisalignedCamera();
  const geo::PointingTerms terms = SomeTerms();
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> az(0.0, geo::kTwoPi), el(geo::DegToRad(-5), geo::DegToRad(85)),
      px(0.0, 2447.0), py(0.0, 2047.0);
  for (int i = 0; i < 200; ++i) {
    const geo::AzEl logged{az(rng), el(rng)};
    const Eigen::Vector2d p(px(rng), py(rng));
    const Eigen::Vector3d want = cam.RayEnu(p, logged.az_rad, logged.el_rad, terms);
    const camera::StationView v = camera::ApplyPointing(cam, logged, terms);
    const Eigen::Vector3d got = camera::CameraInView(cam, v).RayEnu(p, v.boresight.az_rad, v.boresight.el_rad);
    EXPECT_LT((got - want).norm(), kExactTolerance_rad) << i;
    // And back: ProjectEnu through the view finds the pixel again.
    const auto back = camera::CameraInView(cam, v).ProjectEnu(want, v.boresight.az_rad, v.boresight.el_rad);
    ASSERT_TRUE(back.has_value());
    EXPECT_LT((*back - p).norm(), 1e-6);
  }
}

TEST(StationView, ZeroTermsReturnTheLoggedAnglesAndTheCamera) {
  const camera::CameraModel cam = DistortedMisalignedCamera();
  const geo::AzEl logged{1.0, 0.5};
  const camera::StationView v = camera::ApplyPointing(cam, logged, geo::PointingTerms{});
  EXPECT_EQ(v.boresight.az_rad, logged.az_rad);
  EXPECT_EQ(v.boresight.el_rad, logged.el_rad);
  EXPECT_EQ(v.mount_yaw_rad, cam.mount_yaw_rad);
  EXPECT_EQ(v.mount_pitch_rad, cam.mount_pitch_rad);
  EXPECT_EQ(v.mount_roll_rad, cam.mount_roll_rad);
}

TEST(LocateSigma, AutodiffJacobianMatchesNumerical) {
  const camera::CameraModel cam = DistortedMisalignedCamera();
  const geo::PointingTerms terms = SomeTerms();
  SigmaPoint p;
  p.px = Eigen::Vector2d(1900.3, 300.7);  // far from the centre: distortion matters
  p.az_rad = geo::DegToRad(350.0);
  p.el_rad = geo::DegToRad(62.0);
  p.az_rate = 0.05;
  p.el_rate = -0.02;
  p.range_m = 1234.5;
  p.range_rate_mps = 40.0;
  const LocatedJacobian J = LocatedJacobianAt(cam, terms, p);
  const SigmaInputVector x0 = SigmaNominal(cam, terms, p);
  for (int i = 0; i < kSigmaInputs; ++i) {
    const double h = 1e-6;
    SigmaInputVector xp = x0, xm = x0;
    xp(i) += h;
    xm(i) -= h;
    Eigen::Matrix<double, kSigmaOutputs, 1> d = (LocatedFunction(cam, p, xp) - LocatedFunction(cam, p, xm)) / (2 * h);
    d(0) = geo::WrapPi(LocatedFunction(cam, p, xp)(0) - LocatedFunction(cam, p, xm)(0)) / (2 * h);
    for (int k = 0; k < kSigmaOutputs; ++k) {
      const double scale = std::max(1.0, std::abs(d(k)));
      EXPECT_NEAR(J(k, i), d(k), kJacobianRelTolerance * scale) << "output " << k << " input " << i;
    }
  }
  // y itself: the jet's value is rk-locate's line of sight.
  const Eigen::Vector3d ray = cam.RayEnu(p.px, p.az_rad, p.el_rad, terms);
  const Eigen::Matrix<double, kSigmaOutputs, 1> y = LocatedFunction(cam, p, x0);
  EXPECT_NEAR(y(3), p.range_m * ray.x(), 1e-9);
}

// A still turret logged at 50 Hz and a track at 20 Hz.
formats::TurretLog StillTurret(double az_deg, double el_deg, double t0, double t1) {
  formats::TurretLog log;
  log.source = "turret.csv";
  for (double t = t0; t <= t1 + 1e-9; t += 0.02) {
    log.t_s.push_back(t);
    log.az_rad.push_back(geo::DegToRad(az_deg));
    log.el_rad.push_back(geo::DegToRad(el_deg));
  }
  return log;
}

TEST(LocateTimeOffset, InterpolatesAtMidExposureAndWritesThatTime) {
  camera::CameraModel cam = camera::DefaultCamera();
  formats::TurretLog log;
  log.source = "turret.csv";
  for (int i = 0; i <= 100; ++i) {  // azimuth ramps at 1°/s
    log.t_s.push_back(0.02 * i);
    log.az_rad.push_back(geo::DegToRad(10.0 + 0.02 * i));
    log.el_rad.push_back(geo::DegToRad(5.0));
  }
  formats::Track track;
  track.rows.push_back({std::nullopt, 1.0, Eigen::Vector2d(1223.5, 1023.5), RowStatus::kOk, std::nullopt});
  cam.time_offset_s = 0.035;
  const LocateResult r = Locate(track, cam, log, nullptr, LocateOptions{});
  ASSERT_EQ(r.rows.size(), 1u);
  EXPECT_DOUBLE_EQ(r.rows[0].t_s, 1.035);
  EXPECT_NEAR(geo::RadToDeg(*r.rows[0].az_rad), 11.035, 1e-9);
}

TEST(LocateWgs84, StationGivesLatLonH) {
  const geo::Geodetic station{-33.9, 18.4, 120.0};
  const geo::LocalEnu enu(station);
  const Eigen::Vector3d p(1500.0, -700.0, 300.0);
  const geo::Geodetic g = enu.ToGeodetic(p);
  EXPECT_LT((enu.ToEnu(g) - p).norm(), 1e-6);
  // 700 m south ≈ 0.0063° of latitude; 300 m up plus the earth's curvature over 1.65 km (≈ 0.2 m).
  EXPECT_NEAR(g.lat_deg, -33.9 - 700.0 / 110900.0, 2e-4);
  EXPECT_NEAR(g.h_m, 120.0 + 300.0 + 0.21, 0.05);
  geo::Geodetic parsed;
  std::string why;
  EXPECT_TRUE(geo::ParseGeodetic("-33.9,18.4,120", &parsed, &why)) << why;
  EXPECT_DOUBLE_EQ(parsed.lat_deg, -33.9);
  EXPECT_FALSE(geo::ParseGeodetic("-33.9,18.4", &parsed, &why));
  EXPECT_FALSE(geo::ParseGeodetic("91,0,0", &parsed, &why));
  EXPECT_FALSE(geo::ParseGeodetic("1,2,x", &parsed, &why));
  EXPECT_FALSE(geo::ParseGeodetic("1,2,3,", &parsed, &why));
}

// ---- Monte Carlo: NEES and the error with and without the pointing model ----

struct McConfig {
  double sigma_px = 0.05;
  double step_deg = 0.003;                   // encoder step (the FLIR PTU of seed 001)
  std::array<double, 4> term_sigma_deg = {5.0 / 3600, 1.0 / 3600, 1.0 / 3600, 2.0 / 3600};
  std::array<double, 3> mount_sigma_deg = {3.0 / 3600, 3.0 / 3600, 10.0 / 3600};
  double focal_sigma_mm = 0.005;
  int frames = 20;
};

struct McRun {
  double nees_sum = 0.0;  // Σ over frames of (az, el) NEES
  int n = 0;
  double sse_az_arcsec2 = 0.0, sse_el_arcsec2 = 0.0;  // az error scaled by cos el (arc on the sky)
};

// One dwell: the turret holds still at encoder angles (A, E); the target crosses the field. The station's true
// pointing terms and mount differ from the files' by the files' σ (one draw per run); pixels get noise per frame;
// the logged angles are the encoder angles quantised (one draw per dwell).
McRun RunOnce(std::mt19937_64& rng, const McConfig& c, bool station_errors, bool use_pointing, bool calibrated) {
  std::normal_distribution<double> n01(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  camera::CameraModel truth_cam = DistortedMisalignedCamera();
  geo::PointingTerms truth_terms;
  if (station_errors) truth_terms = {geo::DegToRad(2.5), geo::DegToRad(0.3), geo::DegToRad(-0.2), geo::DegToRad(0.1)};
  // The files: the truth plus their own error of 1σ as stated (or the truth itself, σ = 0).
  camera::PointingModel file;
  camera::CameraModel file_cam = truth_cam;
  std::array<double, 4> t = {truth_terms.az_offset_rad, truth_terms.tilt_north_rad, truth_terms.tilt_east_rad,
                             truth_terms.el_axis_tilt_rad};
  if (calibrated) {
    for (int i = 0; i < 4; ++i) {
      const double s = geo::DegToRad(c.term_sigma_deg[i]);
      t[i] += s * n01(rng);
      file.sigma_rad[i] = s;
    }
    file_cam.mount_yaw_rad += geo::DegToRad(c.mount_sigma_deg[0]) * n01(rng);
    file_cam.mount_pitch_rad += geo::DegToRad(c.mount_sigma_deg[1]) * n01(rng);
    file_cam.mount_roll_rad += geo::DegToRad(c.mount_sigma_deg[2]) * n01(rng);
    file_cam.focal_length_mm += c.focal_sigma_mm * n01(rng);
    file_cam.calibration = {{"sigma",
                             {{"mount_deg",
                               {{"yaw", c.mount_sigma_deg[0]}, {"pitch", c.mount_sigma_deg[1]},
                                {"roll", c.mount_sigma_deg[2]}}},
                              {"focal_length_mm", c.focal_sigma_mm}}}};
  }
  file.SetTermsRad(t);
  const double A = geo::kTwoPi * u01(rng), E = geo::DegToRad(5.0 + 55.0 * u01(rng));
  const double q = geo::DegToRad(c.step_deg);
  const double A_log = q * std::round(A / q), E_log = q * std::round(E / q);
  const Eigen::Matrix3d R_enu_cam =
      geo::RotationEnuFromTurret(A, E, truth_terms) * truth_cam.RotationTurretFromCamera();
  formats::TurretLog log = StillTurret(geo::RadToDeg(A_log), geo::RadToDeg(E_log), 0.0, 1.2);
  formats::Track track;
  std::vector<Eigen::Vector3d> dirs;
  const Eigen::Vector2d start(400 + 1600 * u01(rng), 300 + 1400 * u01(rng)), vel(300 * n01(rng), 300 * n01(rng));
  for (int k = 0; k < c.frames; ++k) {
    const double t_s = 0.1 + 0.05 * k;
    const Eigen::Vector2d px_true = start + vel * (t_s - 0.5);
    const Eigen::Vector3d dir = R_enu_cam * truth_cam.NormalisedRay(px_true).normalized();
    dirs.push_back(dir);
    const Eigen::Vector2d noisy = px_true + c.sigma_px * Eigen::Vector2d(n01(rng), n01(rng));
    track.rows.push_back({k, t_s, noisy, RowStatus::kOk, std::nullopt});
  }
  LocateOptions o;
  o.sigma_px = c.sigma_px;
  o.encoder_step_deg = c.step_deg;
  if (use_pointing) o.pointing = file;
  const LocateResult r = Locate(track, file_cam, log, nullptr, o);
  McRun out;
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    const LocatedRow& row = r.rows[k];
    if (!row.az_rad || !row.cov) continue;
    const geo::AzEl truth = geo::AzElFromEnu(dirs[k]);
    const Eigen::Vector2d e(geo::WrapPi(*row.az_rad - truth.az_rad), *row.el_rad - truth.el_rad);
    const Eigen::Matrix2d P = row.cov->topLeftCorner<2, 2>();
    out.nees_sum += e.dot(P.ldlt().solve(e));
    out.sse_az_arcsec2 += std::pow(e(0) * std::cos(truth.el_rad) * geo::kArcsecPerRad, 2);
    out.sse_el_arcsec2 += std::pow(e(1) * geo::kArcsecPerRad, 2);
    ++out.n;
  }
  return out;
}

struct McSummary {
  double mean_nees = 0.0;  // per degree of freedom (expect 1)
  double rms_az_arcsec = 0.0, rms_el_arcsec = 0.0;
};

McSummary MonteCarlo(std::uint64_t seed, int runs, bool station_errors, bool use_pointing, bool calibrated) {
  std::mt19937_64 rng(seed);
  const McConfig c;
  double nees_run_means = 0.0, sse_az = 0.0, sse_el = 0.0;
  int n = 0;
  for (int i = 0; i < runs; ++i) {
    const McRun run = RunOnce(rng, c, station_errors, use_pointing, calibrated);
    if (run.n == 0) continue;
    nees_run_means += run.nees_sum / run.n;
    sse_az += run.sse_az_arcsec2;
    sse_el += run.sse_el_arcsec2;
    n += run.n;
  }
  McSummary s;
  s.mean_nees = nees_run_means / runs / 2.0;
  s.rms_az_arcsec = std::sqrt(sse_az / n);
  s.rms_el_arcsec = std::sqrt(sse_el / n);
  return s;
}

// 200 runs. Within a run the frames share the pointing, mount, focal and encoder errors, so a run's mean NEES
// varies at most like one χ²₂ draw (variance 4, or 1 per degree of freedom); the mean over 200 independent
// runs then has a standard deviation ≤ 1/√200 = 0.071 per degree of freedom. Band ±3 of those: [0.79, 1.21].
constexpr int kRuns = 200;
constexpr double kNeesLow = 0.79, kNeesHigh = 1.21;

TEST(LocateNees, AzElConsistentWithCalibratedStation) {
  const McSummary s = MonteCarlo(20261126, kRuns, true, true, true);
  std::cout << "NEES (az, el) per dof, calibrated station: " << s.mean_nees << "; RMS az " << s.rms_az_arcsec
            << "\" el " << s.rms_el_arcsec << "\"\n";
  RecordProperty("nees_per_dof", std::to_string(s.mean_nees));
  EXPECT_GT(s.mean_nees, kNeesLow);
  EXPECT_LT(s.mean_nees, kNeesHigh);
}

TEST(LocateNees, AzElConsistentWithPerfectStationAndFiles) {
  // No calibration error: pixel noise and encoder quantisation only.
  const McSummary s = MonteCarlo(7, kRuns, true, true, false);
  std::cout << "NEES (az, el) per dof, exact pointing model: " << s.mean_nees << "\n";
  EXPECT_GT(s.mean_nees, kNeesLow);
  EXPECT_LT(s.mean_nees, kNeesHigh);
}

TEST(LocatePointing, TruthMatchesPerfectStationWithoutItDegreesOff) {
  // Same seed: the same dwells, pixels and noise; only the station differs.
  const McSummary perfect = MonteCarlo(99, 100, false, false, false);
  const McSummary truth = MonteCarlo(99, 100, true, true, false);
  const McSummary none = MonteCarlo(99, 100, true, false, false);
  std::cout << "az/el RMS (arcsec): perfect station " << perfect.rms_az_arcsec << " / " << perfect.rms_el_arcsec
            << "; with --pointing truth " << truth.rms_az_arcsec << " / " << truth.rms_el_arcsec
            << "; without --pointing " << none.rms_az_arcsec << " / " << none.rms_el_arcsec << "\n";
  // Issue target: ≤ 1.1 × the perfect station's.
  EXPECT_LE(truth.rms_az_arcsec, 1.1 * perfect.rms_az_arcsec);
  EXPECT_LE(truth.rms_el_arcsec, 1.1 * perfect.rms_el_arcsec);
  EXPECT_GT(std::hypot(none.rms_az_arcsec, none.rms_el_arcsec), 3600.0);  // > 1°
}

}  // namespace
}  // namespace rk::locate

// The per-row solver (lib/intersect/solver.h): analytic Jacobians against numerical ones, exactness on
// noise-free lines over 20 km baselines (the ECEF treatment: a flat earth errs by metres), azimuth across
// north, outlier rejection, degenerate geometry.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <GeographicLib/LocalCartesian.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "geo/angles.h"
#include "intersect/solver.h"
#include "intersect/station_frames.h"
#include "rk_test/matchers.h"

namespace rk::intersect {
namespace {

using geo::Geodetic;

// Numerical derivative step (m) and its tolerance: central differences err by ~h² f''' ≈ 1e-12 relative.
constexpr double kStepM = 1e-3;
constexpr double kJacobianTolerance = 1e-7;  // relative to the row's norm
// Noise-free intersection: GeographicLib's round trip is ~1e-9 m; allow 1 mm over 30 km.
constexpr double kExactM = 1e-3;

const Geodetic kOrigin{47.0, 8.0, 400.0};

// Station geodetic position from origin ENU (independent of MakeStationFrame).
Geodetic AtEnu(double e, double n, double u) {
  GeographicLib::LocalCartesian lc(kOrigin.lat_deg, kOrigin.lon_deg, kOrigin.h_m);
  Geodetic g;
  lc.Reverse(e, n, u, g.lat_deg, g.lon_deg, g.h_m);
  return g;
}

// True az/el/range of p (origin ENU) from a station, through WGS-84 and the station's own LocalCartesian.
LineObservation Truth(int index, const Geodetic& st, const Eigen::Vector3d& p, double sigma_rad) {
  GeographicLib::LocalCartesian lo(kOrigin.lat_deg, kOrigin.lon_deg, kOrigin.h_m);
  double lat, lon, h;
  lo.Reverse(p(0), p(1), p(2), lat, lon, h);
  GeographicLib::LocalCartesian ls(st.lat_deg, st.lon_deg, st.h_m);
  Eigen::Vector3d d;
  ls.Forward(lat, lon, h, d(0), d(1), d(2));
  LineObservation o;
  o.station = index;
  o.az_rad = geo::WrapTwoPi(std::atan2(d(0), d(1)));
  o.el_rad = std::atan2(d(2), std::hypot(d(0), d(1)));
  o.sigma_el_rad = sigma_rad;
  o.sigma_az_rad = sigma_rad / std::cos(o.el_rad);
  o.range_m = d.norm();
  o.sigma_range_m = 1.0;
  return o;
}

struct Layout {
  std::vector<Geodetic> geo;
  std::vector<StationFrame> frames;
};

// Three stations 10–20 km apart at different heights.
Layout ThreeStations() {
  Layout s;
  s.geo = {AtEnu(0, 0, 0), AtEnu(20000, 0, 350), AtEnu(9000, 15000, 900)};
  for (const Geodetic& g : s.geo) s.frames.push_back(MakeStationFrame(kOrigin, g));
  return s;
}

TEST(IntersectSolver, JacobianMatchesNumerical) {
  const Layout s = ThreeStations();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-20000.0, 20000.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d p(u(rng), u(rng), 2000.0 + std::abs(u(rng)) / 2.0);
    for (const StationFrame& f : s.frames) {
      const Prediction pr = Predict(f, p);
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d dp = Eigen::Vector3d::Zero();
        dp(k) = kStepM;
        const Prediction a = Predict(f, p + dp), b = Predict(f, p - dp);
        const Eigen::Vector3d num(geo::WrapPi(a.az - b.az) / (2 * kStepM), (a.el - b.el) / (2 * kStepM),
                                  (a.range - b.range) / (2 * kStepM));
        for (int r = 0; r < 3; ++r) {
          EXPECT_NEAR(pr.J(r, k), num(r), kJacobianTolerance * pr.J.row(r).norm()) << "row " << r << " col " << k;
        }
      }
    }
  }
}

TEST(IntersectSolver, NoiseFreeIsExactOver20kmAndFlatEarthIsNot) {
  const Layout s = ThreeStations();
  std::vector<StationFrame> flat = s.frames;  // a flat earth: every station's ENU parallel to the origin's
  for (StationFrame& f : flat) {
    f.M.setIdentity();
    f.c = -f.a;
  }
  double worst_flat = 0.0;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(10000, 6000, 3000), Eigen::Vector3d(-5000, 25000, 12000),
                                   Eigen::Vector3d(30000, 10000, 800)}) {
    std::vector<LineObservation> obs;
    for (int i = 0; i < 3; ++i) obs.push_back(Truth(i, s.geo[i], p, 1e-5));
    const RowResult r = SolveRow(s.frames, obs.data(), 3, SolverOptions{});
    ASSERT_EQ(r.solution.status, SolveStatus::kOk);
    EXPECT_THAT(r.solution.p, test::EnuNear(p, kExactM)) << p.transpose();
    EXPECT_LT(r.rms_residual_arcsec, 1e-3);
    const Solution f = SolveMasked(flat, obs.data(), 3, 7);
    worst_flat = std::max(worst_flat, (f.p - p).norm());
  }
  std::printf("flat-earth treatment, 20 km baseline: largest error %.2f m (exact form < %.0e m)\n", worst_flat, kExactM);
  EXPECT_GT(worst_flat, 1.0) << "a flat-earth treatment should err by metres at 20 km";
}

TEST(IntersectSolver, AzimuthAcrossNorth) {
  const Layout s = ThreeStations();
  // Target passing north of station 0 from west to east: station 0's azimuth goes 350° → 10°.
  for (double e = -2000.0; e <= 2000.0; e += 250.0) {
    const Eigen::Vector3d p(e, 12000.0, 2500.0);
    std::vector<LineObservation> obs;
    for (int i = 0; i < 3; ++i) obs.push_back(Truth(i, s.geo[i], p, 1e-5));
    const RowResult r = SolveRow(s.frames, obs.data(), 3, SolverOptions{});
    ASSERT_EQ(r.solution.status, SolveStatus::kOk);
    EXPECT_THAT(r.solution.p, test::EnuNear(p, kExactM));
  }
}

// Stations at very different heights (a valley station 350 m below the origin, a mountain station 2600 m above
// it, 15 km out): each sees the target with its own vertical, some below their horizon (negative elevation
// from the mountain); noise-free lines still meet exactly.
TEST(IntersectSolver, StationsAtVeryDifferentHeights) {
  Layout s;
  s.geo = {AtEnu(0, 0, 0), AtEnu(15000, 2000, 2600), AtEnu(4000, 12000, -350)};
  for (const Geodetic& g : s.geo) s.frames.push_back(MakeStationFrame(kOrigin, g));
  int below_horizon = 0;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(8000, 6000, 300), Eigen::Vector3d(12000, 3000, 1500),
                                  Eigen::Vector3d(2000, 9000, 6000), Eigen::Vector3d(-5000, 20000, 100)}) {
    std::vector<LineObservation> obs;
    for (int i = 0; i < 3; ++i) obs.push_back(Truth(i, s.geo[i], p, 1e-5));
    below_horizon += obs[1].el_rad < 0 ? 1 : 0;
    const RowResult r = SolveRow(s.frames, obs.data(), 3, SolverOptions{});
    ASSERT_EQ(r.solution.status, SolveStatus::kOk);
    EXPECT_THAT(r.solution.p, test::EnuNear(p, kExactM)) << p.transpose();
    // Two stations alone (the valley and the mountain) too.
    const Solution two = SolveMasked(s.frames, obs.data(), 3, 0b110);
    ASSERT_EQ(two.status, SolveStatus::kOk);
    EXPECT_THAT(two.p, test::EnuNear(p, kExactM)) << p.transpose();
  }
  EXPECT_GE(below_horizon, 2);  // the case is exercised
}

TEST(IntersectSolver, OutlierStationIsRejected) {
  Layout s = ThreeStations();
  s.geo.push_back(AtEnu(-6000, 12000, 150));
  s.frames.push_back(MakeStationFrame(kOrigin, s.geo.back()));
  const double sigma = 5.0 / geo::kArcsecPerRad;
  const Eigen::Vector3d p(8000, 9000, 4000);
  std::vector<LineObservation> obs;
  for (int i = 0; i < 4; ++i) obs.push_back(Truth(i, s.geo[i], p, sigma));
  obs[2].az_rad += 200.0 * obs[2].sigma_az_rad;  // 200 σ off in azimuth
  const RowResult r = SolveRow(s.frames, obs.data(), 4, SolverOptions{});
  ASSERT_EQ(r.solution.status, SolveStatus::kOk);
  EXPECT_EQ(r.rejected, std::uint64_t{1} << 2);
  EXPECT_EQ(r.used, std::uint64_t{0b1011});
  EXPECT_THAT(r.solution.p, test::EnuNear(p, kExactM));
  // Two stations cannot decide: nothing is rejected.
  const RowResult two = SolveRow(s.frames, obs.data() + 1, 2, SolverOptions{});
  EXPECT_EQ(two.rejected, 0u);
}

TEST(IntersectSolver, OneLineWithRangeAndTooFew) {
  const Layout s = ThreeStations();
  const Eigen::Vector3d p(5000, 7000, 3000);
  LineObservation o = Truth(0, s.geo[0], p, 1e-5);
  o.has_range = false;
  EXPECT_EQ(SolveMasked(s.frames, &o, 1, 1).status, SolveStatus::kTooFew);
  o.has_range = true;
  const Solution sol = SolveMasked(s.frames, &o, 1, 1);
  ASSERT_EQ(sol.status, SolveStatus::kOk);
  EXPECT_THAT(sol.p, test::EnuNear(p, kExactM));
  EXPECT_NEAR(std::sqrt(sol.P(0, 0) + sol.P(1, 1) + sol.P(2, 2)) > 0.0, 1.0, 0.0);
}

TEST(IntersectSolver, TargetOnTheBaselineIsSingular) {
  const Layout s = ThreeStations();
  // A point on the line through stations 0 and 1 (beyond station 1): both lines coincide.
  const Eigen::Vector3d p = s.frames[1].a + 2.0 * (s.frames[1].a - s.frames[0].a);
  std::vector<LineObservation> obs = {Truth(0, s.geo[0], p, 1e-5), Truth(1, s.geo[1], p, 1e-5)};
  EXPECT_NE(SolveMasked(s.frames, obs.data(), 2, 3).status, SolveStatus::kOk);
}

// Issue 28 item 6: rk-locate's corr_az_el reaches the solver. The whitened residuals' Jacobian is the numerical
// one (∂z/∂p = −NormalisedJacobian), and with correlated angle errors the covariance is honest only when the
// correlation is used: NEES over Monte Carlo runs in its band with ρ, out of it without.
TEST(IntersectSolver, CorrelatedAnglesJacobianMatchesNumerical) {
  const Layout s = ThreeStations();
  const Eigen::Vector3d p0(7000, 8000, 3000);
  const double sigma = 5.0 / geo::kArcsecPerRad;
  for (const double rho : {-0.9, 0.0, 0.6}) {
    for (int i = 0; i < 3; ++i) {
      LineObservation o = Truth(i, s.geo[i], p0 + Eigen::Vector3d(30, -20, 10), sigma);
      o.has_range = true;
      o.corr_az_el = rho;
      const Eigen::Matrix3d Jn = NormalisedJacobian(o, Predict(s.frames[i], p0));
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d dp = Eigen::Vector3d::Zero();
        dp(k) = kStepM;
        const Eigen::Vector3d num = (NormalisedResiduals(o, Predict(s.frames[i], p0 + dp)) -
                                     NormalisedResiduals(o, Predict(s.frames[i], p0 - dp))) / (2 * kStepM);
        for (int r = 0; r < 3; ++r) {
          EXPECT_NEAR(-Jn(r, k), num(r), kJacobianTolerance * Jn.row(r).norm()) << "rho " << rho << " row " << r;
        }
      }
    }
  }
}

// Eigenvalues of P^{-1/2} S P^{-1/2}: 1, 1, 1 when the sample covariance S of the errors is what P claims.
Eigen::Vector3d CovarianceRatio(const Eigen::Matrix3d& P, const Eigen::Matrix3d& S) {
  const Eigen::Matrix3d L = P.llt().matrixL();
  const Eigen::Matrix3d W = L.triangularView<Eigen::Lower>().solve(
      L.triangularView<Eigen::Lower>().solve(S).transpose());
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(0.5 * (W + W.transpose())).eigenvalues();
}

TEST(IntersectSolver, CorrelatedResidualsWrapAcrossNorth) {
  // A target due north of station 0 (predicted azimuth 0) measured at 359.9994°: the azimuth residual is
  // −2 µrad, not 2π, and the whitened elevation residual carries −ρ of it.
  const Layout s = ThreeStations();
  const Prediction pr = Predict(s.frames[0], s.frames[0].a + Eigen::Vector3d(0.0, 10000.0, 2000.0));
  const double sigma = 5.0 / geo::kArcsecPerRad, rho = 0.5;
  LineObservation o;
  o.az_rad = geo::WrapTwoPi(pr.az - 1e-5);
  o.el_rad = pr.el + 2e-5;
  o.sigma_az_rad = o.sigma_el_rad = sigma;
  o.corr_az_el = rho;
  const Eigen::Vector3d z = NormalisedResiduals(o, pr);
  EXPECT_NEAR(z(0), -1e-5 / sigma, 1e-6);
  EXPECT_NEAR(z(1), (2e-5 / sigma + rho * 1e-5 / sigma) / std::sqrt(1.0 - rho * rho), 1e-6);
}

TEST(IntersectSolver, CorrelatedAngleErrorsCovarianceHonestOnlyWithTheCorrelation) {
  // Two stations' lines of sight only (no range): the az/el correlation shapes the 3-D error ellipsoid.
  const Layout s = ThreeStations();
  const Eigen::Vector3d p(7000, 8000, 3000);
  const double sigma = 10.0 / geo::kArcsecPerRad, rho = 0.85;
  constexpr int kRuns = 4000;
  // A sample covariance of kRuns 3-D errors, whitened by the true one, has eigenvalues within
  // (1 ± sqrt(3 / kRuns))² ≈ [0.946, 1.056] (Marchenko–Pastur edges) plus their fluctuation: ±0.1 is wide.
  constexpr double kRatioTol = 0.1;
  std::mt19937_64 rng(28);
  std::normal_distribution<double> n01;
  Eigen::Matrix3d S_with = Eigen::Matrix3d::Zero(), S_without = Eigen::Matrix3d::Zero(), P_with, P_without;
  double nees_with = 0.0;
  for (int run = 0; run < kRuns; ++run) {
    std::vector<LineObservation> obs;
    for (int i = 0; i < 2; ++i) {
      LineObservation o = Truth(i, s.geo[i], p, sigma);
      o.has_range = false;
      const double a = n01(rng), b = n01(rng);
      o.az_rad += o.sigma_az_rad * a;
      o.el_rad += o.sigma_el_rad * (rho * a + std::sqrt(1.0 - rho * rho) * b);
      o.corr_az_el = rho;
      obs.push_back(o);
    }
    const Solution with = SolveMasked(s.frames, obs.data(), 2, 3);
    for (LineObservation& o : obs) o.corr_az_el = 0.0;
    const Solution without = SolveMasked(s.frames, obs.data(), 2, 3);
    ASSERT_EQ(with.status, SolveStatus::kOk);
    ASSERT_EQ(without.status, SolveStatus::kOk);
    const Eigen::Vector3d e1 = with.p - p, e0 = without.p - p;
    S_with += e1 * e1.transpose() / kRuns;
    S_without += e0 * e0.transpose() / kRuns;
    nees_with += e1.dot(with.P.ldlt().solve(e1)) / kRuns;
    P_with = with.P;  // the geometry is fixed: P hardly moves with the noise
    P_without = without.P;
  }
  const Eigen::Vector3d r_with = CovarianceRatio(P_with, S_with), r_without = CovarianceRatio(P_without, S_without);
  std::printf("mean NEES with rho %.3f; covariance ratio eigenvalues with %.3f %.3f %.3f, without %.3f %.3f %.3f\n",
              nees_with, r_with(0), r_with(1), r_with(2), r_without(0), r_without(1), r_without(2));
  EXPECT_NEAR(nees_with, 3.0, 3.0 * kRatioTol);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r_with(k), 1.0, kRatioTol) << r_with.transpose();
  // Without the correlation P claims an ellipsoid the errors do not have (this checks the test has power).
  EXPECT_GT((r_without.array() - 1.0).abs().maxCoeff(), 3.0 * kRatioTol) << r_without.transpose();
}

}  // namespace
}  // namespace rk::intersect

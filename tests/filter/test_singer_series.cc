// Singer-model filter/smoother over a Series (filter/singer_series.h) against simulated truth.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "filter/series.h"
#include "filter/singer_series.h"
#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "track/singer.h"
#include "test_series_util.h"

namespace rk::filter {
namespace {

// NEES consistency on data drawn from the Singer model itself.
TEST(SingerSeries, ConsistentOnSingerProcessAndSmootherBeatsFilter) {
  constexpr int kRuns = 60, kSteps = 300, kBurnIn = 40;
  constexpr double kT = 0.1, kTau = 2.0, kSigmaM = 1.0, kSigmaZ = 0.05;
  // Mean NEES of a 3-state estimate over 60 × 260 correlated samples: expected 3; the band
  // allows for the time correlation (effective samples ≈ runs × steps / 10).
  constexpr double kNeesLow = 2.6, kNeesHigh = 3.4;
  const double a = 1.0 / kTau, q = 2.0 * a * kSigmaM * kSigmaM;
  const Eigen::Matrix3d Phi = track::SingerTransition(kT, a);
  const Eigen::Matrix3d Lq = track::SingerProcessNoise(kT, a, q).llt().matrixL();
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n01(0.0, 1.0);
  double nees_f = 0.0, nees_s = 0.0, se_f = 0.0, se_s = 0.0, sv_f = 0.0, sv_s = 0.0;
  std::size_t count = 0;
  SingerSeriesOptions opt;
  opt.maneuver_time_s = kTau;
  opt.accel_sigma = {kSigmaM};
  opt.meas_sigma = {kSigmaZ};
  for (int run = 0; run < kRuns; ++run) {
    std::vector<Eigen::Vector3d> truth(kSteps);
    std::vector<double> t(kSteps), z(kSteps);
    Eigen::Vector3d x(0.0, 0.0, kSigmaM * n01(rng));
    for (int k = 0; k < kSteps; ++k) {
      if (k > 0) x = Phi * x + Lq * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
      truth[k] = x;
      t[k] = k * kT;
      z[k] = x(0) + kSigmaZ * n01(rng);
    }
    const Series s = MakeSeries("x_m", t, z);
    SingerSeriesOptions fo = opt;
    fo.smooth = false;
    const SingerSeriesResult rf = RunSingerSeries(s, fo);
    const SingerSeriesResult rs = RunSingerSeries(s, opt);
    for (int k = kBurnIn; k < kSteps; ++k) {
      Eigen::Vector3d xf, xs;
      Eigen::Matrix3d Pf, Ps;
      ASSERT_TRUE(rf.At(0, static_cast<std::size_t>(k), &xf, &Pf));
      ASSERT_TRUE(rs.At(0, static_cast<std::size_t>(k), &xs, &Ps));
      const Eigen::Vector3d ef = xf - truth[k], es = xs - truth[k];
      nees_f += ef.dot(Pf.ldlt().solve(ef));
      nees_s += es.dot(Ps.ldlt().solve(es));
      se_f += ef(0) * ef(0);
      se_s += es(0) * es(0);
      sv_f += ef(1) * ef(1);
      sv_s += es(1) * es(1);
      ++count;
    }
    EXPECT_NEAR(rf.stats[0].nis_mean, 1.0, 0.35) << "run " << run;
  }
  nees_f /= static_cast<double>(count);
  nees_s /= static_cast<double>(count);
  std::printf("NEES filter %.3f smoother %.3f; position RMS filter %.4f smoother %.4f\n", nees_f, nees_s,
              std::sqrt(se_f / static_cast<double>(count)), std::sqrt(se_s / static_cast<double>(count)));
  EXPECT_GT(nees_f, kNeesLow);
  EXPECT_LT(nees_f, kNeesHigh);
  EXPECT_GT(nees_s, kNeesLow);
  EXPECT_LT(nees_s, kNeesHigh);
  // The smoother uses the future samples too: strictly smaller errors.
  EXPECT_LT(se_s, 0.8 * se_f);
  EXPECT_LT(sv_s, 0.8 * sv_f);
}

// Rate and acceleration of known motions: a parabola and a sinusoid, 20 Hz, 1 mm noise.
TEST(SingerSeries, DerivativesOfKnownMotion) {
  constexpr double kNoiseM = 1e-3;
  // Smoothed derivative errors from 1 mm noise at 20 Hz (Singer σ_m chosen by likelihood):
  // a few mm/s in rate and a few cm/s² in acceleration away from the ends.
  constexpr double kRateTolMps = 0.015, kAccelTolMps2 = 0.12;
  constexpr double kEdgeS = 1.0;  // the ends have one-sided data: not checked
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, kNoiseM);
  struct Motion {
    std::function<double(double)> p, v, acc;
  };
  const std::vector<Motion> motions = {
      {[](double t) { return 5.0 + 2.0 * t + 0.15 * t * t; }, [](double t) { return 2.0 + 0.3 * t; },
       [](double) { return 0.3; }},
      {[](double t) { return 2.0 * std::sin(1.0 * t); }, [](double t) { return 2.0 * std::cos(t); },
       [](double t) { return -2.0 * std::sin(t); }},
  };
  for (std::size_t m = 0; m < motions.size(); ++m) {
    std::vector<double> t, z;
    for (int k = 0; k <= 200; ++k) {
      t.push_back(0.05 * k);
      z.push_back(motions[m].p(t.back()) + noise(rng));
    }
    const Series s = MakeSeries("x_m", t, z);
    const SingerSeriesResult r = RunSingerSeries(s, SingerSeriesOptions{});
    EXPECT_TRUE(r.stats[0].meas_sigma_estimated);
    EXPECT_NEAR(r.stats[0].meas_sigma, kNoiseM, 0.3 * kNoiseM);
    double max_rate = 0.0, max_acc = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (t[k] < kEdgeS || t[k] > t.back() - kEdgeS) continue;
      Eigen::Vector3d x;
      Eigen::Matrix3d P;
      ASSERT_TRUE(r.At(0, k, &x, &P));
      max_rate = std::max(max_rate, std::abs(x(1) - motions[m].v(t[k])));
      max_acc = std::max(max_acc, std::abs(x(2) - motions[m].acc(t[k])));
    }
    std::printf("motion %zu: max rate error %.4f m/s, max accel error %.4f m/s^2, sigma_z %.5f\n", m, max_rate,
                max_acc, r.stats[0].meas_sigma);
    EXPECT_LT(max_rate, kRateTolMps) << "motion " << m;
    EXPECT_LT(max_acc, kAccelTolMps2) << "motion " << m;
  }
}

// Angles across 0/360 and ±180: the state stays continuous, the rate is right.
TEST(SingerSeries, AngleWrap) {
  constexpr double kRateDegS = 20.0;
  constexpr double kAngleTolDeg = 0.01;  // 0.001° noise, smoothed
  constexpr double kRateTolDegS = 0.05;
  for (double start : {355.0, 175.0}) {
    std::string csv = start > 300 ? "t_s,az_deg\n" : "t_s,yaw_deg\n";
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 0.001);
    std::vector<double> truth;
    for (int k = 0; k <= 100; ++k) {
      const double t = 0.02 * k;
      const double deg = start + kRateDegS * t;
      truth.push_back(deg);
      const double written = start > 300 ? geo::WrapDeg360(deg + noise(rng)) : geo::WrapDeg180(deg + noise(rng));
      csv += std::to_string(t) + "," + std::to_string(written) + "\n";
    }
    const io::CsvTable table = io::CsvTable::Parse(csv, "wrap.csv");
    const Series s = ReadSeries(table, {table.header()[1]}, 3);
    SingerSeriesOptions opt;
    opt.meas_sigma = {geo::DegToRad(0.001)};
    const SingerSeriesResult r = RunSingerSeries(s, opt);
    for (std::size_t k = 0; k < truth.size(); ++k) {
      Eigen::Vector3d x;
      Eigen::Matrix3d P;
      ASSERT_TRUE(r.At(0, k, &x, &P));
      EXPECT_LT(std::abs(geo::WrapDeg180(geo::RadToDeg(x(0)) - truth[k])), kAngleTolDeg) << start << " " << k;
      if (k > 10 && k + 10 < truth.size()) {
        EXPECT_NEAR(geo::RadToDeg(x(1)), kRateDegS, kRateTolDegS) << start << " " << k;
      }
    }
    EXPECT_NEAR(r.stats[0].nis_mean, 1.0, 0.5);
  }
  std::vector<double> az = {geo::DegToRad(350.0), geo::DegToRad(10.0)};
  EXPECT_TRUE(AngleColumnIs360("az_deg", az));
  EXPECT_FALSE(AngleColumnIs360("el_deg", {geo::DegToRad(-5.0), geo::DegToRad(30.0)}));
  EXPECT_TRUE(AngleColumnIs360("bearing_deg", {geo::DegToRad(350.0), geo::DegToRad(10.0)}));
}

TEST(SingerSeries, MissingValuesArePredictedRows) {
  std::vector<double> t, z;
  const double nan = std::nan("");
  for (int k = 0; k < 40; ++k) {
    t.push_back(0.1 * k);
    z.push_back((k >= 10 && k < 15) || k < 2 ? nan : 1.0 + 0.5 * t.back());
  }
  const Series s = MakeSeries("x_m", t, z);
  SingerSeriesOptions opt;
  opt.meas_sigma = {1e-3};
  const SingerSeriesResult r = RunSingerSeries(s, opt);
  EXPECT_EQ(r.status[0], SingerRowStatus::kLost);  // before the first value: no estimate
  EXPECT_EQ(r.status[12], SingerRowStatus::kPredicted);
  EXPECT_EQ(r.status[20], SingerRowStatus::kOk);
  EXPECT_EQ(r.rows_lost, 2u);
  EXPECT_EQ(r.rows_predicted, 5u);
  EXPECT_EQ(r.stats[0].missing, 5u);
  Eigen::Vector3d x;
  Eigen::Matrix3d P;
  EXPECT_FALSE(r.At(0, 1, &x, &P));
  ASSERT_TRUE(r.At(0, 12, &x, &P));
  constexpr double kGapTolM = 0.01;  // straight line bridged by the smoother
  EXPECT_NEAR(x(0), 1.0 + 0.5 * 1.2, kGapTolM);
}

TEST(SingerSeries, NoiseEstimate) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<double> v;
  for (int k = 0; k < 2000; ++k) v.push_back(std::sin(0.01 * k) * 3.0 + noise(rng));
  constexpr double kRelTol = 0.08;  // MAD estimator on ~2000 samples
  EXPECT_NEAR(EstimateNoiseSigma(v, false), 0.02, kRelTol * 0.02);
  EXPECT_TRUE(std::isnan(EstimateNoiseSigma({1.0, 2.0, 3.0}, false)));
}

TEST(SingerSeries, OptionsAndNames) {
  SingerSeriesOptions o;
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  o.maneuver_time_s = 0.0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--maneuver-time must be > 0 s");
  o = SingerSeriesOptions{};
  o.meas_sigma = {0.0};
  EXPECT_FALSE(o.Check(&why));
  o = SingerSeriesOptions{};
  o.accel_sigma = {1.0, 2.0};
  const Series s = MakeSeries("x_m", {0.0, 1.0, 2.0, 3.0}, {0.0, 1.0, 2.0, 3.0});
  EXPECT_THROW(RunSingerSeries(s, o), Error);
  const Series u = MakeSeries("x_kg", {0.0, 1.0, 2.0, 3.0}, {0.0, 1.0, 2.0, 3.0});
  EXPECT_THROW(RunSingerSeries(u, SingerSeriesOptions{}), Error);  // no default for the unit
  EXPECT_EQ(DerivedColumnName("range_m", 1), "range_rate_m_s");
  EXPECT_EQ(DerivedColumnName("range_m", 2), "range_accel_m_s2");
  EXPECT_EQ(DerivedColumnName("yaw_deg", 1), "yaw_rate_deg_s");
  EXPECT_EQ(DerivedColumnName("az_deg", 0, true), "az_sigma_deg");
  EXPECT_EQ(DerivedColumnName("range_m", 1, true), "range_rate_sigma_m_s");
  EXPECT_EQ(DerivedColumnName("range_m", 2, true), "range_accel_sigma_m_s2");
}

TEST(SingerSeries, MaskByStatus) {
  const io::CsvTable t = io::CsvTable::Parse(
      "t_s,range_m,status\n0,1.0,0\n0.2,1.1,7\n0.4,1.2,\n0.6,1.3,0\n0.8,1.4,ok\n", "range.csv");
  Series s = ReadSeries(t, {"range_m"}, 3);
  EXPECT_EQ(MaskByStatus(t, &s, 3), 1u);
  EXPECT_TRUE(std::isnan(s.values(1, 0)));
  EXPECT_EQ(s.values(2, 0), 1.2);
  const io::CsvTable bad = io::CsvTable::Parse("t_s,range_m,status\n0,1,0\n1,1,0\n2,1,weird\n3,1,0\n", "bad.csv");
  Series sb = ReadSeries(bad, {"range_m"}, 3);
  try {
    MaskByStatus(bad, &sb, 3);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("bad.csv:4:"), std::string::npos) << e.what();
  }
  const io::CsvTable few = io::CsvTable::Parse("t_s,range_m,status\n0,1,0\n1,1,3\n2,1,3\n3,1,0\n", "few.csv");
  Series sf = ReadSeries(few, {"range_m"}, 3);
  EXPECT_THROW(MaskByStatus(few, &sf, 3), Error);
}

}  // namespace
}  // namespace rk::filter

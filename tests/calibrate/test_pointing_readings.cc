// rk-calibrate pointing's turret-reading error model (pointing_observations.h "Shared errors") on a
// hand-made quantised turret log: a dwell, a cosine S-curve slew of 1° in azimuth over 1 s, a second dwell;
// and the log accessors it uses (TimeSeriesInterpolator::Bracket, track::BoresightSource::SampleWeight and
// mean_sample_interval_s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "calibrate/pointing_observations.h"
#include "geo/angles.h"
#include "track/boresight.h"

namespace rk::calibrate {
namespace {

constexpr double kStepDeg = 0.003;           // encoder quantum
constexpr double kLogRateHz = 50.0;          // turret log rate
constexpr double kSlewStartS = 3.0, kSlewS = 1.0, kSlewDeg = 1.0, kEndS = 6.0;
constexpr double kAz0Deg = 10.0004, kElDeg = 5.0;
constexpr double kSigmaTol = 1e-12;          // σ are formulas of the step: rounding only
constexpr double kWeightTol = 1e-9;          // sample times k / 50: rounding only
// Mid-slew rate (≈ 1.57°/s) over ±50 ms of the log: quantisation adds at most one step per 0.1 s (0.03°/s,
// 2 %) and the S-curve's curvature (rate²/jerk) under 1 %.
constexpr double kRateRelTol = 0.05;

double CommandedAzDeg(double t) {
  const double s = std::clamp((t - kSlewStartS) / kSlewS, 0.0, 1.0);
  return kAz0Deg + kSlewDeg * 0.5 * (1.0 - std::cos(geo::kPi * s));
}

double Quantise(double deg) { return std::round(deg / kStepDeg) * kStepDeg; }

track::BoresightSource HandMadeLog() {
  formats::TurretLog log;
  log.source = "turret.csv";
  for (int k = 0; k <= static_cast<int>(kEndS * kLogRateHz); ++k) {
    const double t = k / kLogRateHz;
    log.t_s.push_back(t);
    log.az_rad.push_back(geo::DegToRad(Quantise(CommandedAzDeg(t))));
    log.el_rad.push_back(geo::DegToRad(Quantise(kElDeg)));
  }
  return track::BoresightSource::FromLog(log, track::InterpMethod::kLinear, 1.0);
}

PointingObservations ObservationsAt(const track::BoresightSource& turret, const std::vector<double>& times) {
  ImagePoints pts;
  pts.source = "points.csv";
  for (std::size_t i = 0; i < times.size(); ++i) {
    ImagePoint p;
    p.t_s = times[i];
    p.id = "L1";
    p.line = i + 2;
    p.id_column = 1;
    pts.rows.push_back(p);
  }
  TargetCatalogue cat;
  target::Landmark l;
  l.id = "L1";
  l.p_enu = {200.0, 1000.0, 80.0};
  cat.landmarks.push_back(l);
  return BuildObservations(pts, cat, turret, geo::DegToRad(kStepDeg), 0.05, 0.0);
}

TEST(PointingReadings, LogAccessorsGiveTheSampleIntervalAndWeight) {
  const track::BoresightSource turret = HandMadeLog();
  EXPECT_NEAR(turret.mean_sample_interval_s(), 1.0 / kLogRateHz, kWeightTol);
  EXPECT_NEAR(turret.SampleWeight(3.51), 0.5, kWeightTol);
  EXPECT_NEAR(turret.SampleWeight(1.005), 0.25, kWeightTol);
  EXPECT_TRUE(std::isnan(turret.SampleWeight(kEndS + 1.0)));
  EXPECT_TRUE(std::isnan(track::BoresightSource::Fixed(0, 0).mean_sample_interval_s()));
}

TEST(PointingReadings, DwellSlewAndCreepGetTheirOwnErrors) {
  const track::BoresightSource turret = HandMadeLog();
  // 1.0, 1.5: first dwell; 3.51: mid-slew (about 10 steps per log interval), halfway between samples;
  // 3.97: the slew's slow end (about 1 step per interval); 4.01: the log already reads the second dwell's
  // value but the turret crept into that cell 20 ms before; 4.5, 5.0: second dwell.
  const PointingObservations o = ObservationsAt(turret, {1.0, 1.5, 3.51, 3.97, 4.01, 4.5, 5.0});
  ASSERT_EQ(o.obs.size(), 7u);
  const double sq = geo::DegToRad(kStepDeg) / std::sqrt(12.0);
  auto cluster = [&](int i) { return o.obs[static_cast<std::size_t>(i)].cluster; };
  auto sigma = [&](int i) { return o.cluster_sigma_rad[static_cast<std::size_t>(cluster(i))]; };
  EXPECT_EQ(cluster(0), cluster(1));  // one reading for the dwell
  EXPECT_NEAR(sigma(0).x(), sq, kSigmaTol);
  // Fast azimuth: two independent samples averaged at w = 0.5; still elevation: one reading.
  EXPECT_NEAR(sigma(2).x(), sq * std::sqrt(0.5), kSigmaTol);
  EXPECT_NEAR(sigma(2).y(), sq, kSigmaTol);
  // Slow azimuth: correlated samples, the full σ.
  EXPECT_NEAR(sigma(3).x(), sq, kSigmaTol);
  // Creep: its own reading, not the second dwell's; the dwell's interior shares one.
  EXPECT_NE(cluster(4), cluster(5));
  EXPECT_NEAR(sigma(4).x(), sq, kSigmaTol);
  EXPECT_EQ(cluster(5), cluster(6));
  EXPECT_EQ(o.dwells, 2u);
  // The rate through which τ acts is the turret's over ±50 ms, not the log's one-step slope.
  const double true_rate = geo::DegToRad(CommandedAzDeg(3.52) - CommandedAzDeg(3.50)) / 0.02;
  EXPECT_NEAR(o.obs[2].az_rate_rps, true_rate, kRateRelTol * true_rate);
}

}  // namespace
}  // namespace rk::calibrate

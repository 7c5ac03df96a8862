// The checkpointed smoother (filter::SingerSmoother) against the run kept whole in memory (RunSingerSeries):
// the same numbers exactly, bit for bit (EXPECT_EQ on doubles), at every row and at times between rows —
// the blocks recompute the same arithmetic in the same order from the same inputs, so no tolerance is due.
// Block seams are exercised by forcing small blocks (1, 2, 3 rows, N − 1, N, N + 1) on irregular sampling
// with missing rows, a column that starts late, an azimuth across 0/360, with and without smoothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "filter/resample.h"
#include "filter/series.h"
#include "filter/singer_series.h"
#include "geo/angles.h"

namespace rk::filter {
namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

// n rows, irregular times (0.05 s ± 40 %); az_deg sweeping across 0/360 with noise and holes; range_m that
// starts at row n/4 (+1) and has holes of its own.
Series MakeTwoColumns(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(0.6, 1.4);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Series s;
  s.source = "test";
  s.columns = {"az_deg", "range_m"};
  s.is_angle = {true, false};
  s.values.resize(static_cast<Eigen::Index>(n), 2);
  double t = 10.0;
  for (std::size_t r = 0; r < n; ++r) {
    t += 0.05 * jitter(rng);
    s.t_s.push_back(t);
    const double az_deg = 350.0 + 8.0 * (t - 10.0) + 0.01 * noise(rng);  // crosses 360 after ~1.25 s
    const bool az_missing = r == 0 || u01(rng) < 0.15;
    s.values(static_cast<Eigen::Index>(r), 0) = az_missing ? kNoValue : geo::DegToRad(geo::WrapDeg360(az_deg));
    const bool range_missing = r < n / 4 + 1 || u01(rng) < 0.2;
    s.values(static_cast<Eigen::Index>(r), 1) =
        range_missing ? kNoValue : 1000.0 + 30.0 * t + 2.0 * std::sin(t) + 0.05 * noise(rng);
  }
  return s;
}

// Every coefficient equal (no tolerance).
bool Bitwise(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a == b; }
bool Bitwise(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return a == b; }

// Every figure, every row's estimate and status, and estimates at times around every row (before the
// first, between rows, on rows, after the last) equal those of RunSingerSeries exactly.
void ExpectSameAsFullRun(const Series& s, const SingerSeriesOptions& opt, std::size_t block_rows) {
  SCOPED_TRACE("rows " + std::to_string(s.rows()) + ", block " + std::to_string(block_rows) +
               (opt.smooth ? ", smoothed" : ", filter only"));
  const SingerSeriesResult full = RunSingerSeries(s, opt);
  const SingerSmoother sm(s, opt, block_rows);
  const SingerSeriesSummary& sum = sm.summary();
  EXPECT_EQ(sum.smoothed, full.smoothed);
  EXPECT_EQ(sum.rows, full.rows);
  EXPECT_EQ(sum.rows_ok, full.rows_ok);
  EXPECT_EQ(sum.rows_predicted, full.rows_predicted);
  EXPECT_EQ(sum.rows_lost, full.rows_lost);
  EXPECT_EQ(sum.ToJson(s, 2.0).dump(), full.ToJson(s, 2.0).dump());  // σ_z, σ_m, NIS, counts
  const std::size_t nc = s.columns.size();
  // Target times: 0.3 s before the first row, then between and on rows, then after the last.
  std::vector<double> targets = {s.t_s.front() - 0.3};
  for (std::size_t r = 0; r < s.rows(); ++r) {
    targets.push_back(s.t_s[r]);
    if (r + 1 < s.rows()) targets.push_back(0.7 * s.t_s[r] + 0.3 * s.t_s[r + 1]);
  }
  targets.push_back(s.t_s.back() + 0.2);
  std::vector<std::size_t> next_target(nc, 0);
  std::size_t next_row = 0;
  sm.ForEachBlock([&](const SingerBlock& block) {
    ASSERT_EQ(block.begin(), next_row);  // blocks in time order, each row once
    ASSERT_GT(block.end(), block.begin());
    ASSERT_LE(block.end() - block.begin(), block_rows);
    for (std::size_t r = block.begin(); r < block.end(); ++r) {
      EXPECT_EQ(sm.RowStatus(r), full.status[r]) << "row " << r;
      for (std::size_t c = 0; c < nc; ++c) {
        Eigen::Vector3d x, xf;
        Eigen::Matrix3d P, Pf;
        const bool have = block.At(c, r, &x, &P);
        ASSERT_EQ(have, full.At(c, r, &xf, &Pf)) << "row " << r << " column " << c;
        if (!have) continue;
        EXPECT_TRUE(Bitwise(x, xf)) << "row " << r << " column " << c << "\n" << x - xf;
        EXPECT_TRUE(Bitwise(P, Pf)) << "row " << r << " column " << c << "\n" << P - Pf;
      }
    }
    next_row = block.end();
    for (std::size_t c = 0; c < nc; ++c) {
      if (full.stats[c].updates == 0) continue;
      for (; next_target[c] < targets.size() && sm.EvaluationRow(c, targets[next_target[c]]) < block.end();
           ++next_target[c]) {
        const double t = targets[next_target[c]];
        Eigen::Vector3d x, xf;
        Eigen::Matrix3d P, Pf;
        sm.Evaluate(block, c, t, &x, &P);
        EvaluateSinger(full, s, c, t, &xf, &Pf);
        EXPECT_TRUE(Bitwise(x, xf)) << "t " << t << " column " << c;
        EXPECT_TRUE(Bitwise(P, Pf)) << "t " << t << " column " << c;
      }
    }
  });
  EXPECT_EQ(next_row, s.rows());
  for (std::size_t c = 0; c < nc; ++c) {
    if (full.stats[c].updates > 0) {
      EXPECT_EQ(next_target[c], targets.size()) << "column " << c;
    }
  }
}

TEST(SingerSmoother, EqualsFullRunAcrossBlockSeams) {
  const Series s = MakeTwoColumns(40, 1);
  for (const bool smooth : {true, false}) {
    SingerSeriesOptions opt;  // σ_z estimated, σ_m by maximum likelihood
    opt.smooth = smooth;
    for (const std::size_t k : {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{7}, std::size_t{39},
                                std::size_t{40}, std::size_t{41}, kSingerBlockRows}) {
      ExpectSameAsFullRun(s, opt, k);
    }
  }
}

TEST(SingerSmoother, EqualsFullRunForSeriesOfBlockLength) {
  // N = 1, 2, k − 1, k, k + 1, 2k + 1 rows with blocks of k = 8; σ_m given, σ_z given (one row has no
  // estimate to take a σ_z from).
  constexpr std::size_t kBlock = 8;
  for (const std::size_t n : {std::size_t{1}, std::size_t{2}, kBlock - 1, kBlock, kBlock + 1, 2 * kBlock + 1}) {
    Series s = MakeTwoColumns(n, 2);
    s.values(0, 0) = geo::DegToRad(359.9);  // every column needs a first value somewhere
    s.values(static_cast<Eigen::Index>(n - 1), 1) = 1234.5;
    for (const bool smooth : {true, false}) {
      SingerSeriesOptions opt;
      opt.smooth = smooth;
      opt.meas_sigma = {geo::DegToRad(0.01), 0.05};
      opt.accel_sigma = {geo::DegToRad(5.0), 0.5};
      ExpectSameAsFullRun(s, opt, kBlock);
      ExpectSameAsFullRun(s, opt, 1);
    }
  }
}

TEST(SingerSmoother, EqualsFullRunWithColumnThatNeverStarts) {
  Series s = MakeTwoColumns(30, 3);
  for (Eigen::Index r = 0; r < s.values.rows(); ++r) s.values(r, 1) = kNoValue;
  ExpectSameAsFullRun(s, SingerSeriesOptions{}, 4);
}

// Resample's kalman method walks the blocks (default size) with its target times: the same values and 1σ
// as EvaluateSinger on the whole run, across several blocks, with gaps and extrapolation.
TEST(SingerSmoother, ResampleKalmanEqualsFullRun) {
  const std::size_t n = 2 * kSingerBlockRows + 123;
  const Series s = MakeTwoColumns(n, 4);
  ResampleOptions o;
  o.margin_s = 0.5;
  std::vector<double> targets;
  for (double t = s.t_s.front() - 1.0; t < s.t_s.back() + 1.0; t += 0.137) targets.push_back(t);
  const ResampleResult r = Resample(s, targets, o);
  const SingerSeriesResult full = RunSingerSeries(s, o.singer);
  EXPECT_EQ(r.singer.ToJson(s, 2.0).dump(), full.ToJson(s, 2.0).dump());
  std::size_t evaluated = 0;
  for (std::size_t c = 0; c < s.columns.size(); ++c) {
    for (std::size_t i = 0; i < targets.size(); ++i) {
      if (std::isnan(r.values[c][i])) continue;
      Eigen::Vector3d x;
      Eigen::Matrix3d P;
      EvaluateSinger(full, s, c, targets[i], &x, &P);
      EXPECT_EQ(r.values[c][i], x(0)) << "column " << c << " t " << targets[i];
      EXPECT_EQ(r.sigmas[c][i], std::sqrt(std::max(P(0, 0), 0.0))) << "column " << c << " t " << targets[i];
      ++evaluated;
    }
  }
  EXPECT_GT(evaluated, targets.size());  // most targets of both columns have a value
  EXPECT_GT(r.rows_gap + r.rows_outside, 0u);
  EXPECT_GT(r.rows_extrapolated, 0u);
}

}  // namespace
}  // namespace rk::filter

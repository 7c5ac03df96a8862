// rk-analyze compare: statistics against hand-computed values, angle wrap,
// time window, reference interpolation, skip reasons, bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/compare.h"
#include "analysis/stats.h"
#include "io/csv.h"
#include "io/error.h"

namespace rk::analysis {
namespace {

constexpr double kTol = 1e-12;  // hand-computed values, double precision

TEST(ErrorStats, HandComputed) {
  // e = {1, -2, 3, 4}: mean 1.5; Σ(e-mean)² = 0.25+12.25+2.25+6.25 = 21 → std = sqrt(21/3) = sqrt(7);
  // rms = sqrt(30/4); |e| sorted {1,2,3,4}: h = 3·0.95 = 2.85 → 3 + 0.85·(4−3) = 3.85.
  const auto s = ComputeErrorStats({1.0, -2.0, 3.0, 4.0});
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->n, 4u);
  EXPECT_NEAR(s->max, 4.0, kTol);
  EXPECT_NEAR(s->min, -2.0, kTol);
  EXPECT_NEAR(s->mean, 1.5, kTol);
  EXPECT_NEAR(s->std, std::sqrt(7.0), kTol);
  EXPECT_NEAR(s->rms, std::sqrt(7.5), kTol);
  EXPECT_NEAR(s->p95_abs, 3.85, kTol);
}

TEST(ErrorStats, EdgeCases) {
  EXPECT_FALSE(ComputeErrorStats({}).has_value());
  const auto one = ComputeErrorStats({-2.5});
  ASSERT_TRUE(one.has_value());
  EXPECT_TRUE(std::isnan(one->std));
  EXPECT_NEAR(one->p95_abs, 2.5, kTol);
  EXPECT_NEAR(Percentile({5, 1, 3}, 0.5), 3.0, kTol);
  EXPECT_NEAR(Percentile({1, 2}, 0.25), 1.25, kTol);
}

io::CsvTable Csv(const std::string& text, const std::string& name) { return io::CsvTable::Parse(text, name); }

TEST(Compare, LinearReferenceInterpolationAndWrap) {
  // Reference: az crosses north (359.9 → 0.1 between t = 0 and 1), range linear.
  const auto ref = Csv("t_s,az_deg,range_m\n0,359.9,100\n1,0.1,102\n2,0.3,104\n", "ref.csv");
  // At t=0.5 the reference is 0 (= 360) and 101 m; at t=1.5: 0.2° and 103 m.
  const auto est = Csv("t_s,az_deg,range_m\n0.5,359.99,101.5\n1.5,0.25,102.9\n", "est.csv");
  CompareOptions opt;
  opt.columns = {"az_deg", "range_m"};
  const CompareResult r = Compare(est, ref, opt);
  ASSERT_EQ(r.columns.size(), 2u);
  const ColumnComparison& az = r.columns[0];
  EXPECT_TRUE(az.angle);
  EXPECT_EQ(az.unit, "deg");
  ASSERT_TRUE(az.errors[0] && az.errors[1]);
  EXPECT_NEAR(*az.errors[0], -0.01, 1e-9);
  EXPECT_NEAR(*az.errors[1], 0.05, 1e-9);
  EXPECT_NEAR(az.stats->mean, 0.02, 1e-9);
  const ColumnComparison& range = r.columns[1];
  EXPECT_FALSE(range.angle);
  EXPECT_EQ(range.unit, "m");
  EXPECT_NEAR(*range.errors[0], 0.5, 1e-9);
  EXPECT_NEAR(*range.errors[1], -0.1, 1e-9);

  opt.arcsec = true;
  const CompareResult as = Compare(est, ref, opt);
  EXPECT_EQ(as.columns[0].unit, "arcsec");
  EXPECT_NEAR(as.columns[0].stats->max, 0.05 * 3600.0, 1e-6);
  EXPECT_EQ(as.columns[1].unit, "m");                 // only angles change unit
  EXPECT_NEAR(*as.columns[0].errors[1], 0.05, 1e-9);  // series stays in degrees
}

TEST(Compare, WrapOfErrorsAcross180) {
  const auto ref = Csv("t_s,yaw_deg\n0,179.5\n1,179.5\n", "ref.csv");
  const auto est = Csv("t_s,yaw_deg\n0.5,-179.5\n", "est.csv");
  CompareOptions opt;
  opt.columns = {"yaw_deg"};
  EXPECT_NEAR(*Compare(est, ref, opt).columns[0].errors[0], 1.0, 1e-9);
}

TEST(Compare, CubicReferenceInterpolation) {
  // Reference v = t³ sampled at integers; linear would give 3.5 at t = 1.5, cubic exactly 3.375.
  const auto ref = Csv("t_s,x_m\n0,0\n1,1\n2,8\n3,27\n", "ref.csv");
  const auto est = Csv("t_s,x_m\n1.5,3.375\n", "est.csv");
  CompareOptions opt;
  opt.columns = {"x_m"};
  EXPECT_NEAR(*Compare(est, ref, opt).columns[0].errors[0], 3.375 - 4.5, 1e-12);
  opt.interp = track::InterpMethod::kCubic;
  EXPECT_NEAR(*Compare(est, ref, opt).columns[0].errors[0], 0.0, 1e-12);
}

TEST(Compare, SkipReasonsAndTimeWindow) {
  // Reference: empty value at t=2 breaks (1, 3); span [0, 4].
  const auto ref = Csv("t_s,x_m\n0,0\n1,1\n2,\n3,3\n4,4\n", "ref.csv");
  const auto est =
      Csv("t_s,x_m\n"
          "-1,0\n"     // reference outside
          "0.5,0.6\n"  // ok: error 0.1
          "1.5,1\n"    // reference gap
          "2.5,\n"     // estimate empty
          "3.5,3.3\n"  // ok: error -0.2
          "4.5,4\n"    // reference outside
          "# comment row\n"
          "5,5\n",
          "est.csv");
  CompareOptions opt;
  opt.columns = {"x_m"};
  const ColumnComparison c = Compare(est, ref, opt).columns[0];
  EXPECT_EQ(c.stats->n, 2u);
  EXPECT_EQ(c.skipped_reference_outside, 3u);
  EXPECT_EQ(c.skipped_reference_gap, 1u);
  EXPECT_EQ(c.skipped_estimate_empty, 1u);
  EXPECT_NEAR(c.stats->mean, -0.05, 1e-12);
  EXPECT_NEAR(c.stats->max, 0.1, 1e-12);
  EXPECT_NEAR(c.stats->min, -0.2, 1e-12);

  opt.after_s = 1.0;
  opt.before_s = 4.0;
  const ColumnComparison w = Compare(est, ref, opt).columns[0];
  EXPECT_EQ(w.stats->n, 1u);
  EXPECT_EQ(w.skipped_time_window, 4u);  // -1, 0.5, 4.5, 5
  EXPECT_NEAR(w.stats->mean, -0.2, 1e-12);

  opt.after_s = 10.0;
  opt.before_s.reset();
  const CompareResult none = Compare(est, ref, opt);
  EXPECT_FALSE(none.columns[0].stats.has_value());
  const io::Json j = ColumnsToJson(none);
  EXPECT_EQ(j["x_m"]["n"], 0);
  EXPECT_TRUE(j["x_m"]["rms"].is_null());
}

TEST(Compare, ErrorsCsvHasEveryEstimateRow) {
  const auto ref = Csv("t_s,x_m\n0,0\n1,1\n", "ref.csv");
  const auto est = Csv("t_s,x_m\n0.5,0.75\n2,2\n", "est.csv");
  CompareOptions opt;
  opt.columns = {"x_m"};
  const std::string csv = ErrorsCsv(Compare(est, ref, opt)).str();
  EXPECT_EQ(csv, "t_s,err_x_m\n0.500000000,0.250000000\n2.000000000,\n");
}

TEST(Compare, BadInput) {
  const auto ref = Csv("t_s,x_m\n0,0\n1,1\n", "ref.csv");
  const auto est = Csv("t_s,x_m\n0.5,0.75\n", "est.csv");
  CompareOptions opt;
  opt.columns = {"y_m"};
  try {
    Compare(est, ref, opt);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("est.csv:1"), std::string::npos) << e.what();
  }
  opt.columns = {"x_m"};
  const auto back = Csv("t_s,x_m\n1,0\n0,1\n", "ref.csv");
  EXPECT_THROW(Compare(est, back, opt), Error);
  const auto text = Csv("t_s,x_m\n0.5,abc\n", "est.csv");
  EXPECT_THROW(Compare(text, ref, opt), Error);
  opt.columns = {};
  EXPECT_THROW(Compare(est, ref, opt), Error);
}

}  // namespace
}  // namespace rk::analysis

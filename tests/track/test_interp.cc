// Time-series interpolation: polynomial exactness, angle wrap, gaps, no
// extrapolation, bad times.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "geo/angles.h"
#include "track/interp.h"

namespace rk::track {
namespace {

// Exactness tests evaluate polynomials of size ~10 in double precision.
constexpr double kExactTolerance = 1e-11;

std::vector<double> UnevenTimes() { return {0.0, 0.13, 0.31, 0.42, 0.60, 0.77, 0.95, 1.10, 1.32, 1.40}; }

std::vector<std::optional<double>> Eval(const std::vector<double>& t, double (*f)(double)) {
  std::vector<std::optional<double>> v;
  for (double x : t) v.push_back(f(x));
  return v;
}

double Line(double t) { return 3.0 - 2.5 * t; }
double Quadratic(double t) { return 1.0 + 0.5 * t - 4.0 * t * t; }
double Cubic(double t) { return -2.0 + t - 3.0 * t * t + 5.0 * t * t * t; }

void ExpectReproduces(InterpMethod method, double (*f)(double), int window = 3) {
  const auto t = UnevenTimes();
  InterpOptions opt;
  opt.method = method;
  opt.window = window;
  const TimeSeriesInterpolator interp(t, Eval(t, f), opt);
  for (double q = 0.0; q <= 1.40; q += 0.0137) {  // includes the first and last intervals
    const InterpValue v = interp.At(q);
    ASSERT_TRUE(v.ok()) << q;
    EXPECT_NEAR(v.value, f(q), kExactTolerance) << InterpMethodName(method) << " t=" << q;
  }
  EXPECT_NEAR(interp.At(1.40).value, f(1.40), kExactTolerance);
}

TEST(Interp, LinearReproducesLines) { ExpectReproduces(InterpMethod::kLinear, Line); }
TEST(Interp, CubicReproducesCubics) {
  ExpectReproduces(InterpMethod::kCubic, Line);
  ExpectReproduces(InterpMethod::kCubic, Quadratic);
  ExpectReproduces(InterpMethod::kCubic, Cubic);
}
TEST(Interp, LocalQuadraticReproducesQuadratics) {
  ExpectReproduces(InterpMethod::kLocalQuadratic, Quadratic, 2);
  ExpectReproduces(InterpMethod::kLocalQuadratic, Quadratic, 4);
}
TEST(Interp, LocalCubicReproducesCubics) {
  ExpectReproduces(InterpMethod::kLocalCubic, Cubic, 3);
  ExpectReproduces(InterpMethod::kLocalCubic, Cubic, 5);
}

TEST(Interp, LinearIsNotExactOnCurves) {  // the exactness tests above can fail
  const auto t = UnevenTimes();
  const TimeSeriesInterpolator interp(t, Eval(t, Quadratic), InterpOptions{});
  EXPECT_GT(std::abs(interp.At(0.2).value - Quadratic(0.2)), 1e-3);
}

TEST(Interp, CubicPassesThroughSamples) {
  const std::vector<double> t = {0, 1, 2, 3, 4, 5};
  const std::vector<std::optional<double>> v = {0.3, -1.0, 2.0, 0.5, 0.7, 4.0};
  InterpOptions opt;
  opt.method = InterpMethod::kCubic;
  const TimeSeriesInterpolator interp(t, v, opt);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(interp.At(t[i]).value, *v[i], kExactTolerance);
}

TEST(Interp, AngleWrapThroughNorth) {
  const std::vector<double> t = {0, 1, 2, 3, 4};
  std::vector<std::optional<double>> az;
  for (double deg : {359.8, 359.9, 0.0, 0.1, 0.2}) az.push_back(geo::DegToRad(deg));
  for (InterpMethod m : {InterpMethod::kLinear, InterpMethod::kCubic}) {
    InterpOptions opt;
    opt.method = m;
    opt.angle = true;
    const TimeSeriesInterpolator interp(t, az, opt);
    EXPECT_NEAR(geo::RadToDeg(geo::WrapTwoPi(interp.At(1.5).value)), 359.95, 1e-9) << InterpMethodName(m);
    EXPECT_NEAR(geo::RadToDeg(geo::WrapTwoPi(interp.At(2.5).value)), 0.05, 1e-9) << InterpMethodName(m);
    // Without unwrapping the same data would interpolate through 180°.
    opt.angle = false;
    const TimeSeriesInterpolator raw(t, az, opt);
    EXPECT_GT(std::abs(geo::RadToDeg(raw.At(1.5).value) - 359.95), 100.0);
  }
}

TEST(Interp, AngleWrapThroughPlusMinus180) {
  const std::vector<double> t = {0, 1, 2, 3};
  std::vector<std::optional<double>> a;
  for (double deg : {179.8, 179.9, -180.0, -179.9}) a.push_back(geo::DegToRad(deg));
  InterpOptions opt;
  opt.method = InterpMethod::kCubic;
  opt.angle = true;
  const TimeSeriesInterpolator interp(t, a, opt);
  EXPECT_NEAR(geo::RadToDeg(geo::WrapPi(interp.At(1.5).value)), 179.95, 1e-9);
  EXPECT_NEAR(geo::RadToDeg(geo::WrapPi(interp.At(2.5).value)), -179.95, 1e-9);
}

TEST(Interp, GapLimitAndUnusableSamples) {
  // 5 Hz log; a 0.6 s hole between 0.4 and 1.0; a device error at 1.4.
  const std::vector<double> t = {0.0, 0.2, 0.4, 1.0, 1.2, 1.4, 1.6, 1.8};
  const std::vector<std::optional<double>> v = {1, 2, 3, 6, 7, std::nullopt, 9, 10};
  InterpOptions opt;
  opt.max_gap_s = 0.5;
  const TimeSeriesInterpolator interp(t, v, opt);
  EXPECT_EQ(interp.usable_samples(), 7u);
  EXPECT_EQ(interp.segments(), 3u);
  EXPECT_TRUE(interp.At(0.3).ok());
  EXPECT_NEAR(interp.At(0.3).value, 2.5, kExactTolerance);
  EXPECT_EQ(interp.At(0.7).status, InterpStatus::kGap);
  EXPECT_TRUE(interp.At(1.0).ok());  // the sample itself
  EXPECT_NEAR(interp.At(1.1).value, 6.5, kExactTolerance);
  EXPECT_EQ(interp.At(1.3).status, InterpStatus::kUnusable);
  EXPECT_EQ(interp.At(1.5).status, InterpStatus::kUnusable);
  EXPECT_NEAR(interp.At(1.7).value, 9.5, kExactTolerance);
  // Cubic never reaches across a gap either: values near the hole come from one side only.
  opt.method = InterpMethod::kCubic;
  const TimeSeriesInterpolator cubic(t, v, opt);
  EXPECT_NEAR(cubic.At(0.3).value, 2.5, kExactTolerance);  // 0,0.2,0.4 are collinear
  EXPECT_NEAR(cubic.At(1.1).value, 6.5, kExactTolerance);  // segment {1.0, 1.2}: linear
  // A larger limit bridges the hole but not the device error.
  opt.max_gap_s = 1.0;
  const TimeSeriesInterpolator wide(t, v, opt);
  EXPECT_TRUE(wide.At(0.7).ok());
  EXPECT_EQ(wide.At(1.3).status, InterpStatus::kUnusable);
}

TEST(Interp, NoExtrapolation) {
  const std::vector<double> t = {1.0, 2.0, 3.0};
  const std::vector<std::optional<double>> v = {1, 2, 3};
  for (InterpMethod m : {InterpMethod::kLinear, InterpMethod::kCubic, InterpMethod::kLocalQuadratic,
                         InterpMethod::kLocalCubic}) {
    InterpOptions opt;
    opt.method = m;
    const TimeSeriesInterpolator interp(t, v, opt);
    EXPECT_EQ(interp.At(0.999).status, InterpStatus::kOutside);
    EXPECT_EQ(interp.At(3.001).status, InterpStatus::kOutside);
    EXPECT_TRUE(interp.At(1.0).ok());
    EXPECT_TRUE(interp.At(3.0).ok());
    EXPECT_NEAR(interp.At(3.0).value, 3.0, kExactTolerance);
  }
  const TimeSeriesInterpolator empty(std::vector<double>{}, std::vector<std::optional<double>>{}, InterpOptions{});
  EXPECT_EQ(empty.At(0.0).status, InterpStatus::kOutside);
}

TEST(Interp, IsolatedSampleAnswersOnlyItsOwnTime) {
  const std::vector<double> t = {0.0, 1.0, 2.0};
  const std::vector<std::optional<double>> v = {std::nullopt, 5.0, std::nullopt};
  const TimeSeriesInterpolator interp(t, v, InterpOptions{});
  EXPECT_TRUE(interp.At(1.0).ok());
  EXPECT_EQ(interp.At(1.0).value, 5.0);
  EXPECT_FALSE(interp.At(1.01).ok());
}

TEST(Interp, RejectsNonIncreasingTimes) {
  const std::vector<std::optional<double>> v = {1, 2, 3};
  EXPECT_THROW(TimeSeriesInterpolator({0.0, 1.0, 1.0}, v, InterpOptions{}), std::invalid_argument);
  EXPECT_THROW(TimeSeriesInterpolator({0.0, 2.0, 1.0}, v, InterpOptions{}), std::invalid_argument);
  EXPECT_THROW(TimeSeriesInterpolator({0.0, NAN, 2.0}, v, InterpOptions{}), std::invalid_argument);
  EXPECT_THROW(TimeSeriesInterpolator({0.0, 1.0}, v, InterpOptions{}), std::invalid_argument);
  InterpOptions bad;
  bad.max_gap_s = 0.0;
  EXPECT_THROW(TimeSeriesInterpolator({0.0, 1.0, 2.0}, v, bad), std::invalid_argument);
}

TEST(Interp, MergeDuplicateTimes) {
  std::vector<double> t = {0.0, 1.0, 1.0, 2.0, 2.0};
  std::vector<std::optional<double>> v = {1.0, 2.0, 4.0, std::nullopt, std::nullopt};
  EXPECT_EQ(MergeDuplicateTimes(&t, &v), 2u);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(*v[1], 3.0);
  EXPECT_FALSE(v[2].has_value());
}

TEST(Interp, MergeDuplicateTimesOfSeveralColumnsInPlace) {
  std::vector<double> t = {0.0, 1.0, 1.0, 2.0, 2.0, 2.0, 3.0};
  std::vector<double> a = {1.0, 2.0, 4.0, NAN, NAN, NAN, 7.0};
  std::vector<double> b = {5.0, NAN, 6.0, 1.0, 2.0, 6.0, NAN};
  EXPECT_EQ(MergeDuplicateTimes(&t, {&a, &b}), 3u);
  EXPECT_EQ(t, (std::vector<double>{0.0, 1.0, 2.0, 3.0}));
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(a[1], 3.0);
  EXPECT_TRUE(std::isnan(a[2]));  // no usable value at t = 2
  EXPECT_EQ(a[3], 7.0);
  EXPECT_EQ(b[1], 6.0);           // the one usable value at t = 1
  EXPECT_EQ(b[2], 3.0);
  EXPECT_TRUE(std::isnan(b[3]));
  std::vector<double> short_col = {1.0};
  EXPECT_THROW(MergeDuplicateTimes(&t, {&short_col}), std::invalid_argument);
}

// The NaN form (a long log's columns taken over) answers exactly as the optional form, for every method,
// status and query, across an unusable sample, a gap, an isolated sample and a wrap through north.
TEST(Interp, NanFormAnswersAsOptionalForm) {
  std::vector<double> t;
  std::vector<std::optional<double>> v;
  for (int i = 0; i < 60; ++i) {
    const double ti = 0.1 * i + (i > 30 ? 0.7 : 0.0) + 0.003 * std::sin(i);  // a 0.8 s hole after sample 30
    t.push_back(ti);
    v.push_back(geo::WrapTwoPi(6.2 + 0.05 * i));  // through 0/2π
  }
  v[12] = std::nullopt;
  v[44] = std::nullopt;
  v[46] = std::nullopt;  // sample 45 is isolated
  std::vector<double> nan_v;
  for (const auto& x : v) nan_v.push_back(x ? *x : NAN);
  for (InterpMethod m : {InterpMethod::kLinear, InterpMethod::kCubic, InterpMethod::kLocalQuadratic,
                         InterpMethod::kLocalCubic}) {
    for (bool angle : {false, true}) {
      InterpOptions opt;
      opt.method = m;
      opt.angle = angle;
      opt.max_gap_s = 0.5;
      const TimeSeriesInterpolator a(t, v, opt);
      const TimeSeriesInterpolator b(std::make_shared<const std::vector<double>>(t), nan_v, opt);
      EXPECT_EQ(a.usable_samples(), b.usable_samples());
      EXPECT_EQ(a.segments(), b.segments());
      ASSERT_EQ(a.segments(), 5u);  // 0-11, 13-30, 31-43 (the hole), 45 alone, 47-59
      for (double q = -0.05; q < 7.0; q += 0.00731) {
        const InterpValue x = a.At(q), y = b.At(q);
        ASSERT_EQ(x.status, y.status) << q;
        if (x.ok()) {
          EXPECT_EQ(x.value, y.value) << InterpMethodName(m) << " t=" << q;
        }
      }
      for (double q : t) {
        EXPECT_EQ(a.At(q).status, b.At(q).status) << q;
        EXPECT_EQ(a.At(q).value, b.At(q).value) << q;
      }
    }
  }
}

TEST(Interp, AxesOfOneLogShareTheirTimes) {
  const auto times = std::make_shared<const std::vector<double>>(std::vector<double>{0.0, 1.0, 2.0, 3.0});
  const TimeSeriesInterpolator az(times, {0.1, 0.2, 0.3, 0.4}, InterpOptions{});
  const TimeSeriesInterpolator el(times, {1.0, 2.0, 3.0, 4.0}, InterpOptions{});
  EXPECT_EQ(times.use_count(), 3);  // no copy of the times while every value is usable
  const TimeSeriesInterpolator holed(times, {1.0, NAN, 3.0, 4.0}, InterpOptions{});
  EXPECT_EQ(times.use_count(), 3);  // an axis with an empty sample keeps its own usable times
  EXPECT_EQ(holed.usable_samples(), 3u);
  EXPECT_EQ(holed.At(0.5).status, InterpStatus::kUnusable);
  EXPECT_EQ(holed.At(2.5).value, 3.5);
}

// Memory on a long log (issue 27 item 16): an axis holds 8 bytes a sample of values beside the times (8 a
// sample, shared between the axes); segments cost nothing per sample. The old interpolator held 28 a sample.
constexpr double kMaxBytesPerSampleWithTimes = 16.1;
TEST(Interp, HoldsSixteenBytesASampleWithItsTimes) {
  constexpr std::size_t kSamples = 100000;
  std::vector<double> t(kSamples), v(kSamples);
  for (std::size_t i = 0; i < kSamples; ++i) {
    t[i] = 1e-3 * static_cast<double>(i);
    v[i] = std::sin(1e-3 * static_cast<double>(i));
  }
  v[500] = NAN;  // two segments: the bytes do not depend on how many
  const auto times = std::make_shared<const std::vector<double>>(std::move(t));
  InterpOptions opt;
  opt.method = InterpMethod::kCubic;
  const TimeSeriesInterpolator full(times, std::vector<double>(times->size(), 1.0), opt);
  const TimeSeriesInterpolator holed(times, v, opt);
  EXPECT_LE(static_cast<double>(full.HeldBytes()) / kSamples, kMaxBytesPerSampleWithTimes);
  EXPECT_LE(static_cast<double>(holed.HeldBytes()) / kSamples, kMaxBytesPerSampleWithTimes);
  EXPECT_EQ(holed.segments(), 2u);
}

TEST(Interp, ParseMethodNames) {
  InterpMethod m;
  for (const char* name : {"linear", "cubic", "local-quadratic", "local-cubic"}) {
    ASSERT_TRUE(ParseInterpMethod(name, &m));
    EXPECT_EQ(InterpMethodName(m), name);
  }
  EXPECT_FALSE(ParseInterpMethod("spline", &m));
}

}  // namespace
}  // namespace rk::track

// Tests of the synthetic pose tracks (sim/posetrack.h): turntable truth and noise,
// mid-time grid, head profile (yaw crossing north, changing accelerations, exact
// derivatives), dropout, determinism, option checks, and the written files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "sim/posetrack.h"
#include "rk_test/temp_dir.h"

namespace rk::sim {
namespace {

constexpr double kTimeTol_s = 1e-12;        // grid times are t0 + k/fps: round-off only
constexpr double kRateTol_rad_s = 1e-12;    // turntable rate is the closed-form slope: round-off only
// Sample std of N Gaussian draws has relative std ≈ 1/sqrt(2N); N = 6 × 181 × 40 runs
// ≈ 43 000 → 0.34 %; 2 % is ~6 sigma.
constexpr double kNoiseStdRelTol = 0.02;
constexpr double kNoiseMeanTolSigmas = 0.05;  // mean of ~43 000 draws: std 0.005 sigma; 10x margin
// Central differences of the closed form with h = 1e-4 s: O(h²·f³) truncation (< 1e-6
// rad/s at 2 Hz, 40°) plus round-off ~1e-16/h.
constexpr double kDerivTol = 1e-5;
constexpr double kFileTol = 1e-8;  // files carry 9 decimals

template <typename F>
void ExpectUsageError(F f) {
  try {
    f();
    ADD_FAILURE() << "no error thrown";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage) << e.what();
  }
}

TEST(PoseTrack, TurntableTruthIsExactlySeed000Experiment) {
  const PoseTrackSimulator sim(DefaultPoseTrackOptions(PoseScenario::kTurntable));
  ASSERT_EQ(sim.sample_count(), 181u);  // 0–9 s at 20 fps, both ends
  ASSERT_EQ(sim.mid_times().size(), 180u);
  EXPECT_NEAR(sim.sample_times().front(), 0.0, kTimeTol_s);
  EXPECT_NEAR(sim.sample_times().back(), 9.0, kTimeTol_s);
  const PoseTruth p0 = sim.TruthAt(0.0);
  for (double t : sim.sample_times()) {
    const PoseTruth p = sim.TruthAt(t);
    EXPECT_NEAR(p.rate[kPoseYaw], geo::DegToRad(10.0), kRateTol_rad_s);
    EXPECT_NEAR(p.value[kPoseYaw] - p0.value[kPoseYaw], geo::DegToRad(10.0) * t, 1e-12);
    EXPECT_EQ(p.accel[kPoseYaw], 0.0);
    for (int c = 0; c < kPoseDof; ++c) {
      if (c == kPoseYaw) continue;
      EXPECT_EQ(p.value[c], p0.value[c]) << "component " << c << " must stay constant";
      EXPECT_EQ(p.rate[c], 0.0);
    }
  }
}

TEST(PoseTrack, MidTimesAreExactMidpoints) {
  for (PoseScenario s : {PoseScenario::kTurntable, PoseScenario::kHead}) {
    PoseTrackOptions o = DefaultPoseTrackOptions(s);
    o.fps = 30;
    o.t0_s = 12.5;
    const PoseTrackSimulator sim(o);
    const auto& ts = sim.sample_times();
    const auto& tm = sim.mid_times();
    ASSERT_EQ(tm.size() + 1, ts.size());
    for (std::size_t k = 0; k < tm.size(); ++k) {
      EXPECT_NEAR(tm[k], 0.5 * (ts[k] + ts[k + 1]), kTimeTol_s);
      EXPECT_NEAR(ts[k + 1] - ts[k], 1.0 / 30.0, kTimeTol_s);
    }
  }
}

TEST(PoseTrack, NoiseStdAndMeanMatchTheOptions) {
  PoseTrackOptions o = DefaultPoseTrackOptions(PoseScenario::kTurntable);
  o.noise_deg = 0.0724;
  o.noise_position_m = 0.002;
  double s1[2] = {0, 0}, s2[2] = {0, 0};
  double n[2] = {0, 0};
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    o.seed = seed;
    const PoseTrackSimulator sim(o);
    for (const PoseMeasurement& m : sim.measurements()) {
      const PoseTruth t = sim.TruthAt(m.t_s);
      for (int c = 0; c < kPoseDof; ++c) {
        const int g = PoseIsAngle(c) ? 1 : 0;
        const double e = (m.value[c] - t.value[c]) / (g ? o.noise_angle_rad() : o.noise_position_m);
        s1[g] += e;
        s2[g] += e * e;
        n[g] += 1;
      }
    }
  }
  for (int g = 0; g < 2; ++g) {
    const double mean = s1[g] / n[g];
    const double sd = std::sqrt((s2[g] - n[g] * mean * mean) / (n[g] - 1));
    EXPECT_NEAR(sd, 1.0, kNoiseStdRelTol) << (g ? "angles" : "position");
    EXPECT_NEAR(mean, 0.0, kNoiseMeanTolSigmas) << (g ? "angles" : "position");
  }
}

TEST(PoseTrack, ZeroNoiseMeasuresTheTruth) {
  PoseTrackOptions o = DefaultPoseTrackOptions(PoseScenario::kHead);
  o.noise_deg = 0;
  o.noise_position_m = 0;
  const PoseTrackSimulator sim(o);
  for (const PoseMeasurement& m : sim.measurements()) {
    EXPECT_EQ((m.value - sim.TruthAt(m.t_s).value).cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(PoseTrack, HeadYawCrossesNorthAndIsContinuousAfterUnwrapping) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    PoseTrackOptions o = DefaultPoseTrackOptions(PoseScenario::kHead);
    o.seed = seed;
    const PoseTrackSimulator sim(o);
    // Yaw as written (wrapped to [0, 2π)) over the merged sample/mid grid.
    std::vector<double> wrapped;
    for (std::size_t k = 0; k < sim.sample_count(); ++k) {
      wrapped.push_back(geo::WrapTwoPi(sim.TruthAt(sim.sample_times()[k]).value[kPoseYaw]));
      if (k < sim.mid_times().size()) wrapped.push_back(geo::WrapTwoPi(sim.TruthAt(sim.mid_times()[k]).value[kPoseYaw]));
    }
    int crossings = 0;
    double unwrapped = wrapped[0], max_step = 0;
    for (std::size_t i = 1; i < wrapped.size(); ++i) {
      if (std::abs(wrapped[i] - wrapped[i - 1]) > geo::kPi) ++crossings;
      const double step = geo::AngleDiff(wrapped[i], wrapped[i - 1]);
      unwrapped += step;
      max_step = std::max(max_step, std::abs(step));
    }
    EXPECT_GE(crossings, 1) << "seed " << seed;
    // Continuity: at 40 samples/s the unwrapped steps stay small (peak rate < ~600°/s → < 15°).
    EXPECT_LT(max_step, geo::DegToRad(20.0)) << "seed " << seed;
    // Unwrapping the written values gives back the continuous truth (up to whole turns).
    const double last = sim.TruthAt(sim.sample_times().back()).value[kPoseYaw];
    const double first = sim.TruthAt(sim.sample_times().front()).value[kPoseYaw];
    EXPECT_NEAR(unwrapped - wrapped[0], last - first, 1e-9) << "seed " << seed;
  }
}

TEST(PoseTrack, HeadAmplitudesAndAccelerationsVary) {
  PoseTrackOptions o = DefaultPoseTrackOptions(PoseScenario::kHead);
  o.seed = 3;
  const PoseTrackSimulator sim(o);
  for (int c = 0; c < kPoseDof; ++c) {
    double amp = 0, lo = INFINITY, hi = -INFINITY, alo = INFINITY, ahi = -INFINITY;
    for (const PoseSine& s : sim.motion()[c].sines) {
      EXPECT_GE(s.freq_hz, 0.1);
      EXPECT_LE(s.freq_hz, 2.0);
      amp += s.amplitude;
    }
    if (PoseIsAngle(c)) {
      EXPECT_GE(amp, geo::DegToRad(10.0) - 1e-12);
      EXPECT_LE(amp, geo::DegToRad(40.0) + 1e-12);
    } else {
      EXPECT_GE(amp, 0.1 - 1e-12);
      EXPECT_LE(amp, 0.3 + 1e-12);
    }
    for (double t : sim.sample_times()) {
      const PoseTruth p = sim.TruthAt(t);
      lo = std::min(lo, p.value[c]);
      hi = std::max(hi, p.value[c]);
      alo = std::min(alo, p.accel[c]);
      ahi = std::max(ahi, p.accel[c]);
      EXPECT_LE(std::abs(p.value[c] - sim.motion()[c].centre), amp + 1e-12);
    }
    // Motion is a real maneuver: values move by a good part of the amplitude, and the
    // acceleration takes both signs (it is not constant).
    EXPECT_GT(hi - lo, 0.2 * amp) << "component " << c;
    EXPECT_LT(alo, 0.0) << "component " << c;
    EXPECT_GT(ahi, 0.0) << "component " << c;
  }
}

TEST(PoseTrack, DerivativesAreExact) {
  PoseTrackOptions o = DefaultPoseTrackOptions(PoseScenario::kHead);
  o.seed = 5;
  const PoseTrackSimulator sim(o);
  constexpr double h = 1e-4;
  for (double t = 0.3; t < 20; t += 1.7) {
    const PoseTruth p = sim.TruthAt(t), a = sim.TruthAt(t - h), b = sim.TruthAt(t + h);
    for (int c = 0; c < kPoseDof; ++c) {
      EXPECT_NEAR(p.rate[c], (b.value[c] - a.value[c]) / (2 * h), kDerivTol);
      EXPECT_NEAR(p.accel[c], (b.rate[c] - a.rate[c]) / (2 * h), kDerivTol * 10);
    }
  }
}

TEST(PoseTrack, DeterministicPerSeed) {
  for (PoseScenario s : {PoseScenario::kTurntable, PoseScenario::kHead}) {
    PoseTrackOptions o = DefaultPoseTrackOptions(s);
    o.seed = 11;
    const PoseTrackSimulator a(o), b(o);
    o.seed = 12;
    const PoseTrackSimulator c(o);
    bool differs = false;
    for (std::size_t k = 0; k < a.sample_count(); ++k) {
      EXPECT_EQ(a.measurements()[k].value, b.measurements()[k].value);
      EXPECT_EQ(a.TruthAt(a.sample_times()[k]).value, b.TruthAt(b.sample_times()[k]).value);
      if (a.measurements()[k].value != c.measurements()[k].value) differs = true;
    }
    EXPECT_TRUE(differs) << "the seed has no effect";
  }
}

TEST(PoseTrack, DropoutLeavesNoiseUnchanged) {
  PoseTrackOptions o = DefaultPoseTrackOptions(PoseScenario::kHead);
  o.seed = 4;
  const PoseTrackSimulator full(o);
  o.dropout = 0.2;
  o.dropout_value = 0.1;
  const PoseTrackSimulator holed(o);
  std::size_t rows = 0, values = 0;
  for (std::size_t k = 0; k < full.sample_count(); ++k) {
    const PoseMeasurement& m = holed.measurements()[k];
    if (m.row_missing) {
      ++rows;
      EXPECT_TRUE(m.value.array().isNaN().all());
      continue;
    }
    for (int c = 0; c < kPoseDof; ++c) {
      if (std::isnan(m.value[c])) {
        ++values;
      } else {
        EXPECT_EQ(m.value[c], full.measurements()[k].value[c]);
      }
    }
  }
  // 401 rows: expected 80 missing rows (binomial std 8) and ~193 missing values.
  EXPECT_GT(rows, 40u);
  EXPECT_LT(rows, 120u);
  EXPECT_GT(values, 100u);
}

TEST(PoseTrack, CheckRejectsBadOptions) {
  const PoseTrackOptions good = DefaultPoseTrackOptions(PoseScenario::kTurntable);
  std::string why;
  ASSERT_TRUE(good.Check(&why)) << why;
  auto bad = [&](auto mutate, const std::string& word) {
    PoseTrackOptions o = good;
    mutate(o);
    std::string w;
    EXPECT_FALSE(o.Check(&w));
    EXPECT_NE(w.find(word), std::string::npos) << w;
    ExpectUsageError([&] { PoseTrackSimulator sim(o); });
  };
  bad([](PoseTrackOptions& o) { o.duration_s = 0; }, "duration");
  bad([](PoseTrackOptions& o) { o.duration_s = NAN; }, "duration");
  bad([](PoseTrackOptions& o) { o.fps = -1; }, "fps");
  bad([](PoseTrackOptions& o) { o.duration_s = 0.05; }, "fewer than 3");
  bad([](PoseTrackOptions& o) { o.t0_s = -1; }, "t0");
  bad([](PoseTrackOptions& o) { o.noise_deg = -1e-3; }, "--noise-deg must be in [0, 10] deg");
  bad([](PoseTrackOptions& o) { o.noise_position_m = INFINITY; }, "--noise-m must be in [0, 1] m");
  bad([](PoseTrackOptions& o) { o.rate_rad_s = NAN; }, "rate");
  bad([](PoseTrackOptions& o) { o.yaw0_rad = geo::kTwoPi; }, "initial yaw");
  bad([](PoseTrackOptions& o) { o.dropout = 1.0; }, "dropout");
  bad([](PoseTrackOptions& o) { o.dropout_value = -0.1; }, "dropout-value");
  PoseScenario s;
  EXPECT_FALSE(ParsePoseScenario("spin", &s));
  EXPECT_TRUE(ParsePoseScenario("head", &s));
  EXPECT_EQ(s, PoseScenario::kHead);
}

TEST(PoseTrack, WrittenFilesAgreeWithTheSimulator) {
  namespace fs = std::filesystem;
  const rk::test::TempDir tmp("posetrack");
  const fs::path dir = fs::path(tmp.path()) / "trial";
  fs::remove_all(dir);
  PoseTrackOptions o = DefaultPoseTrackOptions(PoseScenario::kHead);
  o.duration_s = 3;
  o.dropout = 0.1;
  const PoseTrackSimulator sim(o);
  PoseTrackWriteOptions w;
  w.out_dir = dir.string();
  const PoseTrackSummary sum = WritePoseTrack(sim, w);
  EXPECT_EQ(sum.samples, 61);
  EXPECT_EQ(sum.mid_times, 60);
  ExpectUsageError([&] { WritePoseTrack(sim, w); });  // not empty, no force
  w.force = true;
  EXPECT_NO_THROW(WritePoseTrack(sim, w));

  const io::CsvTable truth = io::CsvTable::Read((dir / "truth.csv").string());
  ASSERT_EQ(truth.rows(), 121u);
  truth.RequireIncreasing(truth.RequireColumn("t_s"));
  const int kind = truth.RequireColumn("kind"), yaw = truth.RequireColumn("yaw_deg");
  const int yaw_rate = truth.RequireColumn("yaw_rate_deg_s"), t = truth.RequireColumn("t_s");
  for (std::size_t r = 0; r < truth.rows(); ++r) {
    EXPECT_EQ(truth.Cell(r, kind), r % 2 == 0 ? "sample" : "mid");
    const PoseTruth p = sim.TruthAt(truth.Double(r, t));
    const double y = truth.Double(r, yaw);
    EXPECT_GE(y, 0.0);
    EXPECT_LT(y, 360.0);
    EXPECT_NEAR(geo::WrapDeg180(y - geo::RadToDeg(p.value[kPoseYaw])), 0.0, kFileTol);
    EXPECT_NEAR(truth.Double(r, yaw_rate), geo::RadToDeg(p.rate[kPoseYaw]), kFileTol);
  }
  const io::CsvTable meas = io::CsvTable::Read((dir / "measurements.csv").string());
  ASSERT_EQ(meas.rows(), 61u);
  std::int64_t empty_rows = 0;
  for (std::size_t r = 0; r < meas.rows(); ++r) {
    if (meas.IsEmpty(r, meas.RequireColumn("x_m"))) ++empty_rows;
  }
  EXPECT_EQ(empty_rows, sum.missing_rows);
  EXPECT_EQ(io::CsvTable::Read((dir / "truth_mid.csv").string()).rows(), 60u);
  EXPECT_EQ(io::CsvTable::Read((dir / "truth_sample.csv").string()).rows(), 61u);
  EXPECT_TRUE(fs::exists(dir / "scenario.json"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rk::sim

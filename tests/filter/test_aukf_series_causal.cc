// rk-smooth aukf, issue "predictions use the future": with the default causal noise fit, every `estimate`
// and `prediction` node depends on no later sample (truncating the series at any row leaves every earlier
// node unchanged), the 1σ of the predictions is consistent with simulated truth (NEES in its χ² band),
// and the smoothed rows come from the whole-file fit.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "filter/aukf_series.h"
#include "geo/angles.h"

namespace rk::filter {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kCausalTol = 1e-9;  // the tolerance (radians, metres; the values are recomputed bit-exactly)
constexpr double kFrameS = 0.05;     // 20 Hz

// Yaw through ±180° (sum of two sines) and a position column whose first three values are missing, with one
// missing position value and one empty row; sample times jitter by ±5 %.
Series Track(unsigned seed, int rows) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  Series s;
  s.source = "track";
  s.columns = {"yaw_deg", "x_m"};
  s.is_angle = {true, false};
  s.values.resize(rows, 2);
  double t = 0;
  for (int k = 0; k < rows; ++k) {
    s.t_s.push_back(t);
    const double yaw = geo::DegToRad(175.0 + 20.0 * std::sin(1.3 * t) + 5.0 * std::sin(4.1 * t + 1.0));
    s.values(k, 0) = geo::WrapPi(yaw + geo::DegToRad(0.05) * g(rng));
    s.values(k, 1) = 2.0 + 0.4 * t + 0.1 * std::sin(2.2 * t) + 0.001 * g(rng);
    t += kFrameS * (1.0 + jitter(rng));
  }
  for (int k : {0, 1, 2, 40}) s.values(k, 1) = kNaN;
  s.values(60, 0) = s.values(60, 1) = kNaN;
  return s;
}

Series Head(const Series& s, int rows) {
  Series h = s;
  h.t_s.resize(static_cast<std::size_t>(rows));
  h.values.conservativeResize(rows, Eigen::NoChange);
  return h;
}

bool Same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= kCausalTol; }

// Largest difference of the forward nodes of `cut` from those of `full` (infinity when a flag differs).
double MaxForwardDifference(const AukfResult& full, const AukfResult& cut) {
  double worst = 0;
  for (std::size_t j = 0; j < cut.t_s.size(); ++j) {
    if (cut.t_s[j] != full.t_s[j] || cut.is_mid[j] != full.is_mid[j] || cut.status[j] != full.status[j]) {
      return HUGE_VAL;
    }
    for (int c = 0; c < cut.m; ++c) {
      if (cut.HasValue(j, c) != full.HasValue(j, c) || cut.HasSigma(j, c) != full.HasSigma(j, c)) return HUGE_VAL;
    }
    const Eigen::Index jc = static_cast<Eigen::Index>(j);
    for (int i = 0; i < cut.n; ++i) {
      if (!cut.HasValue(j, i / 3)) continue;
      for (const auto* M : {&cut.x_filter, &cut.sd_filter}) {
        const Eigen::MatrixXd& F = M == &cut.x_filter ? full.x_filter : full.sd_filter;
        const double a = (*M)(i, jc), b = F(i, jc);
        if (!Same(a, b)) worst = std::max(worst, std::isfinite(a - b) ? std::abs(a - b) : HUGE_VAL);
      }
    }
  }
  return worst;
}

// Every truncation point: rows 7 … N−1 of the series (7 = the fewest that give x_m the 4 consecutive values
// a noise estimate needs; shorter heads are rejected as data errors).
double WorstOverTruncations(const Series& s, const AukfOptions& opt) {
  const AukfResult full = RunAukf(s, opt);
  double worst = 0;
  for (int rows = 7; rows < static_cast<int>(s.rows()); ++rows) {
    const AukfResult cut = RunAukf(Head(s, rows), opt);
    EXPECT_EQ(cut.t_s.size(), static_cast<std::size_t>(2 * rows - 1));
    worst = std::max(worst, MaxForwardDifference(full, cut));
  }
  return worst;
}

constexpr int kTrackRows = 100;  // covers the dense refits (8…31 rows), 32 and 64, and a restart at each

TEST(AukfCausal, TruncationLeavesEveryEarlierPredictionAndEstimateUnchanged) {
  const Series s = Track(21, kTrackRows);
  AukfOptions opt;  // CLI defaults: σ and q estimated (ml), causal fit, no adaptation
  opt.smooth = true;  // the smoothed rows may use everything; they must not disturb the forward nodes
  EXPECT_LE(WorstOverTruncations(s, opt), kCausalTol);
  AukfOptions moments;
  moments.noise_estimator = NoiseEstimator::kDifferences;
  EXPECT_LE(WorstOverTruncations(s, moments), kCausalTol);
  AukfOptions qr;  // the paper's adaptation on top of the causal fit, refits without restarts after 16 rows
  qr.adapt.mode = AdaptMode::kQR;
  qr.adapt.window = 10;
  qr.causal.restart_until = 16;
  EXPECT_LE(WorstOverTruncations(s, qr), kCausalTol);
}

TEST(AukfCausal, WholeFileFitIsNotCausal) {
  // The check above can fail: the old whole-file fit changes earlier nodes when later rows go.
  const Series s = Track(21, kTrackRows);
  AukfOptions file;
  file.noise_fit = NoiseFit::kFile;
  EXPECT_GT(WorstOverTruncations(s, file), 1e3 * kCausalTol);
}

TEST(AukfCausal, NoiseKnownFromTheFirstFitAndValuesFromTheFirstSample) {
  const Series s = Track(22, kTrackRows);
  AukfOptions opt;
  const AukfResult r = RunAukf(s, opt);
  const std::size_t first_fit = static_cast<std::size_t>(opt.causal.first_fit);
  ASSERT_FALSE(r.noise_refits.empty());
  EXPECT_EQ(r.noise_refits.front().rows, first_fit);
  for (std::size_t j = 0; j < r.t_s.size(); ++j) {
    // yaw: a value from row 0, its 1σ from the node of row first_fit − 1 (the first fit's last row).
    EXPECT_TRUE(r.HasValue(j, 0));
    EXPECT_EQ(r.HasSigma(j, 0), r.sample_row(j) + 1 >= first_fit) << j;
    EXPECT_EQ(r.HasValue(j, 1), r.sample_row(j) >= 3) << j;  // x_m starts at row 3
  }
  AukfOptions given;  // noise given: known from the start, no refits
  given.meas_sigma = {geo::DegToRad(0.05), 0.001};
  given.q = {1.0, 1.0};
  const AukfResult g = RunAukf(s, given);
  EXPECT_TRUE(g.noise_refits.empty());
  EXPECT_TRUE(g.HasSigma(0, 0));
  EXPECT_FALSE(g.HasSigma(0, 1));  // x_m has no value before row 3
}

TEST(AukfCausal, SmoothedRowsComeFromTheWholeFileFit) {
  const Series s = Track(23, kTrackRows);
  AukfOptions opt;
  opt.smooth = true;
  const AukfResult r = RunAukf(s, opt);
  AukfOptions file = opt;
  file.noise_fit = NoiseFit::kFile;
  const AukfResult f = RunAukf(s, file);
  EXPECT_EQ((r.x_smooth - f.x_smooth).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((r.sd_smooth - f.sd_smooth).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(r.smooth_meas_sigma, f.meas_sigma);
  AukfOptions causal_smooth = opt;  // the alternative: smooth the causal pass itself (per-interval q)
  causal_smooth.smooth_noise_fit = NoiseFit::kCausal;
  const AukfResult c = RunAukf(s, causal_smooth);
  EXPECT_EQ((c.x_filter - r.x_filter).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE(c.smooth_meas_sigma.empty());
  for (std::size_t j = 0; j + 1 < c.t_s.size(); ++j) {  // the last node: smoothed = filtered
    if (c.t_s[j] < 1.0) continue;
    for (int col = 0; col < 2; ++col) {
      EXPECT_LT(c.sd_smooth(3 * col, static_cast<Eigen::Index>(j)), c.sd_filter(3 * col, static_cast<Eigen::Index>(j)));
    }
  }
}

// White-jerk truth (the filter's own model) per column, generated at half steps; noise σ and q estimated
// by the default causal fit. NEES of the two measured components at the mid-time predictions (and the
// estimates) from the output 1σ (the covariance is block diagonal per column without adaptation).
TEST(AukfCausal, PredictionSigmaConsistentOnWhiteJerkTruth) {
  constexpr int kRuns = 100, kRows = 201;
  constexpr double kAfterS = 1.0;  // after the first fits (8…20 rows) and the diffuse start
  constexpr double kSigmaPos = 0.001, kSigmaAngDeg = 0.05;
  const double q_pos = 0.05, q_ang = std::pow(geo::DegToRad(30.0), 2);  // m²/s⁵, rad²/s⁵
  std::mt19937 rng(31);
  std::normal_distribution<double> g;
  const double h = kFrameS / 2;
  Eigen::Matrix3d Phi;
  Phi << 1, h, h * h / 2, 0, 1, h, 0, 0, 1;
  const Eigen::Matrix3d L[2] = {WhiteJerkQ(h, q_ang).llt().matrixL(), WhiteJerkQ(h, q_pos).llt().matrixL()};
  std::vector<std::vector<double>> per_node(2 * kRows - 1);
  std::size_t diverged = 0;
  for (int run = 0; run < kRuns; ++run) {
    Series s;
    s.source = "white jerk";
    s.columns = {"yaw_deg", "x_m"};
    s.is_angle = {true, false};
    s.values.resize(kRows, 2);
    Eigen::Vector3d x[2] = {Eigen::Vector3d(geo::DegToRad(30.0) * g(rng), geo::DegToRad(30.0) * g(rng), 0.0),
                            Eigen::Vector3d(0.2 * g(rng), 0.3 * g(rng), 0.0)};
    std::vector<Eigen::Vector2d> truth;
    for (int j = 0; j < 2 * kRows - 1; ++j) {
      truth.emplace_back(x[0](0), x[1](0));
      if (j % 2 == 0) {
        const int k = j / 2;
        s.t_s.push_back(k * kFrameS);
        s.values(k, 0) = geo::WrapPi(x[0](0) + geo::DegToRad(kSigmaAngDeg) * g(rng));
        s.values(k, 1) = x[1](0) + kSigmaPos * g(rng);
      }
      for (int c = 0; c < 2; ++c) x[c] = Phi * x[c] + L[c] * Eigen::Vector3d(g(rng), g(rng), g(rng));
    }
    const AukfResult r = RunAukf(s, AukfOptions{});
    for (std::size_t j = 0; j < r.t_s.size(); ++j) {
      const Eigen::Index jc = static_cast<Eigen::Index>(j);
      const double e0 = geo::WrapPi(r.x_filter(0, jc) - truth[j](0)), e1 = r.x_filter(3, jc) - truth[j](1);
      const double v = std::pow(e0 / r.sd_filter(0, jc), 2) + std::pow(e1 / r.sd_filter(3, jc), 2);
      per_node[j].push_back(v);
      if (r.t_s[j] >= kAfterS && !(v < 100.0)) ++diverged;  // an error beyond 10σ
    }
  }
  std::printf("ANEES (both kinds) by time:");  // how the fit settles as the data grow
  for (double a : {0.0, 0.5, 1.0, 2.0, 3.0, 5.0, 7.5}) {
    const double b = a < 2.0 ? a + 0.5 * (a < 1.0 ? 1.0 : 2.0) : a + 2.5;
    double sm = 0, ct = 0;
    for (std::size_t j = 0; j < per_node.size(); ++j) {
      if (j * h < a || j * h >= b) continue;
      for (double v : per_node[j]) {
        if (std::isfinite(v)) {
          sm += v;
          ct += 1;
        }
      }
    }
    std::printf(" [%.1f, %.1f) s %.2f;", a, b, ct > 0 ? sm / ct : 0.0);
  }
  std::printf("\n");
  // ANEES over runs and nodes after kAfterS, and the fraction of nodes whose ANEES over the runs is in the
  // two-sided 95 % band of χ²(2·kRuns)/kRuns.
  auto band = [](double dof, double z) {
    const double a = 2.0 / (9.0 * dof);
    return dof * std::pow(1.0 - a + z * std::sqrt(a), 3);
  };
  const double lo = band(2.0 * kRuns, -1.959964) / kRuns, hi = band(2.0 * kRuns, 1.959964) / kRuns;
  double sum[2] = {0, 0}, count[2] = {0, 0}, inside[2] = {0, 0};
  for (std::size_t j = 0; j < per_node.size(); ++j) {
    if (j * h < kAfterS) continue;
    double a = 0;
    for (double v : per_node[j]) a += v / kRuns;
    const int mid = static_cast<int>(j % 2);
    sum[mid] += a;
    count[mid] += 1;
    inside[mid] += (a >= lo && a <= hi) ? 1 : 0;
  }
  std::printf("white jerk, causal noise fit (%d runs): ANEES estimate %.3f (%.1f %% of nodes in [%.2f, %.2f]), "
              "prediction %.3f (%.1f %%); %zu errors > 10 sigma\n",
              kRuns, sum[0] / count[0], 100 * inside[0] / count[0], lo, hi, sum[1] / count[1],
              100 * inside[1] / count[1], diverged);
  // The noise is estimated from the data so far (16 rows at first): the prediction's 1σ is held to its band
  // (measured: ANEES 2.08, 93 % of nodes in band); the estimate's 1σ is measured ≈ 7 % small (ANEES 2.28, 72 %
  // of nodes in band: σ̂ from the first rows scatters, and an under-estimate shows at the sample times first),
  // held to within 20 % of 2. The whole-file fit gives 2.13 / 2.11 on the same runs (not causal).
  constexpr double kAneesLo = 1.8, kPredictionAneesHi = 2.2, kEstimateAneesHi = 2.4;
  constexpr double kMinFractionInside = 0.8;  // prediction nodes; nominal 95 %
  EXPECT_EQ(diverged, 0u);
  EXPECT_GT(sum[1] / count[1], kAneesLo);
  EXPECT_LT(sum[1] / count[1], kPredictionAneesHi);
  EXPECT_GE(inside[1] / count[1], kMinFractionInside);
  EXPECT_GT(sum[0] / count[0], kAneesLo);
  EXPECT_LT(sum[0] / count[0], kEstimateAneesHi);
}

}  // namespace
}  // namespace rk::filter

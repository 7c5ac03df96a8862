// rk-smooth aukf on simulated truth: seed 000 Table 1 (turntable 10°/s, 20 fps, 0–9 s, noise 0.0724°),
// the offline smoother, and filter consistency (NEES) on a manoeuvring 6-DOF profile.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "filter/aukf_series.h"
#include "filter/ukf.h"
#include "geo/angles.h"
#include "io/error.h"

namespace rk::filter {
namespace {

// Seed 000 §4.2 experiment.
constexpr double kTurntableRateDegS = 10.0;
constexpr double kFrameRateHz = 20.0;
constexpr double kDurationS = 9.0;
constexpr double kTurntableNoiseDeg = 0.0724;
constexpr double kConvergedAfterS = 1.0;  // statistics "after convergence": the paper's Fig. 3 settles within ~1 s
constexpr int kTurntableRuns = 10;        // Monte Carlo seeds (the ratios below are their mean)
// Targets (issue 3): prediction std ≤ 1.02 × measurement std (paper 0.0736/0.0724 = 1.017);
// smoother std ≤ 0.6 × measurement std at sample and mid-times.
constexpr double kPredictionRatioMax = 1.02;
constexpr double kSmoothedRatioMax = 0.6;

struct Stats {
  double n = 0, sum = 0, sum2 = 0;
  void Add(double e) {
    n += 1;
    sum += e;
    sum2 += e * e;
  }
  double Std() const { return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n))); }
};

Series Turntable(unsigned seed, std::vector<double>* noise_deg) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, kTurntableNoiseDeg);
  Series s;
  s.source = "turntable";
  s.columns = {"yaw_deg"};
  s.is_angle = {true};
  const int N = static_cast<int>(std::lround(kDurationS * kFrameRateHz)) + 1;
  s.values.resize(N, 1);
  noise_deg->clear();
  for (int k = 0; k < N; ++k) {
    const double t = k / kFrameRateHz;
    const double e = g(rng);
    noise_deg->push_back(e);
    s.t_s.push_back(t);
    s.values(k, 0) = geo::DegToRad(kTurntableRateDegS * t + e);
  }
  return s;
}

struct TurntableRatios {
  double prediction = 0, estimate = 0, smoothed_sample = 0, smoothed_mid = 0;
};

TurntableRatios RunTurntable(const AukfOptions& opt) {
  TurntableRatios mean;
  for (int run = 0; run < kTurntableRuns; ++run) {
    std::vector<double> noise;
    const Series s = Turntable(static_cast<unsigned>(1000 + run), &noise);
    const AukfResult r = RunAukf(s, opt);
    Stats meas, pred, est, sm_s, sm_m;
    for (std::size_t k = 0; k < noise.size(); ++k) {
      if (s.t_s[k] >= kConvergedAfterS) meas.Add(noise[k]);
    }
    for (std::size_t j = 0; j < r.t_s.size(); ++j) {
      if (r.t_s[j] < kConvergedAfterS) continue;
      auto err = [&](const Eigen::MatrixXd& X) {
        return geo::RadToDeg(geo::AngleDiff(X(0, static_cast<Eigen::Index>(j)),
                                            geo::DegToRad(kTurntableRateDegS * r.t_s[j])));
      };
      (r.is_mid[j] ? pred : est).Add(err(r.x_filter));
      if (opt.smooth) (r.is_mid[j] ? sm_m : sm_s).Add(err(r.x_smooth));
    }
    mean.prediction += pred.Std() / meas.Std() / kTurntableRuns;
    mean.estimate += est.Std() / meas.Std() / kTurntableRuns;
    if (opt.smooth) {
      mean.smoothed_sample += sm_s.Std() / meas.Std() / kTurntableRuns;
      mean.smoothed_mid += sm_m.Std() / meas.Std() / kTurntableRuns;
    }
  }
  return mean;
}

TEST(Aukf, TurntableTable1DefaultOptions) {
  AukfOptions opt;  // defaults of the CLI: adapt none (auto), noise estimated from the data
  opt.adapt.mode = AdaptMode::kNone;
  opt.smooth = true;
  const TurntableRatios r = RunTurntable(opt);
  std::printf("turntable default: prediction %.3f estimate %.3f smoothed sample %.3f mid %.3f (x measurement std)\n",
              r.prediction, r.estimate, r.smoothed_sample, r.smoothed_mid);
  EXPECT_LE(r.prediction, kPredictionRatioMax);
  EXPECT_LE(r.smoothed_sample, kSmoothedRatioMax);
  EXPECT_LE(r.smoothed_mid, kSmoothedRatioMax);
}

TEST(Aukf, TurntableTable1PaperAdaptation) {
  // The paper adapts Q and R; its own finding is errors at the measurement level (std ratio ≈ 1).
  AukfOptions opt;
  opt.adapt.mode = AdaptMode::kQR;
  opt.meas_sigma = {geo::DegToRad(kTurntableNoiseDeg)};
  opt.smooth = true;
  const TurntableRatios r = RunTurntable(opt);
  std::printf("turntable qr: prediction %.3f estimate %.3f smoothed sample %.3f mid %.3f (x measurement std)\n",
              r.prediction, r.estimate, r.smoothed_sample, r.smoothed_mid);
  EXPECT_LE(r.prediction, kPredictionRatioMax);
  EXPECT_LE(r.estimate, kPredictionRatioMax);
}

// Manoeuvring 6-DOF profiles, 20 Hz, 10 s: e, n, u (m) and yaw, pitch, roll (radians inside).
constexpr int kNeesRuns = 100;       // Monte Carlo runs (the figure)
constexpr double kNeesAfterS = 1.0;  // after the initial transient (initialisation reuses z₁)
constexpr double kPosNoiseM = 0.001;
constexpr double kAngNoiseDeg = 0.05;
const std::vector<std::string> kPoseColumns = {"e_m", "n_m", "u_m", "yaw_deg", "pitch_deg", "roll_deg"};

Series PoseSeries(const std::vector<double>& t, const std::vector<Eigen::VectorXd>& truth, std::mt19937* rng) {
  std::normal_distribution<double> g;
  Series s;
  s.source = "manoeuvre";
  s.columns = kPoseColumns;
  s.is_angle = {false, false, false, true, true, true};
  s.values.resize(static_cast<Eigen::Index>(t.size()), 6);
  for (std::size_t k = 0; k < t.size(); ++k) {
    s.t_s.push_back(t[k]);
    for (int c = 0; c < 6; ++c) {
      const double sd = c >= 3 ? geo::DegToRad(kAngNoiseDeg) : kPosNoiseM;
      double v = truth[2 * k](3 * c) + sd * g(*rng);
      if (c >= 3) v = geo::WrapPi(v);
      s.values(static_cast<Eigen::Index>(k), c) = v;
    }
  }
  return s;
}

struct NeesSummary {
  double anees = 0, lo = 0, hi = 0, fraction_inside = 0;
  std::size_t diverged = 0;
};

// Truth per node (2k = sample k, 2k+1 = mid-time), 18 states. NEES per node over runs.
NeesSummary Nees(const std::vector<std::vector<double>>& nees_by_node, int n) {
  const int R = static_cast<int>(nees_by_node.front().size());
  const double dof = static_cast<double>(R) * n;
  // Mean NEES over R runs × R is χ²(R·n): 95 % two-sided band (Wilson–Hilferty quantiles).
  auto q = [&](double z) {
    const double a = 2.0 / (9.0 * dof);
    return dof * std::pow(1.0 - a + z * std::sqrt(a), 3) / R;
  };
  NeesSummary out;
  out.lo = q(-1.959964);
  out.hi = q(1.959964);
  int inside = 0;
  for (const auto& v : nees_by_node) {
    double a = 0;
    for (double x : v) {
      a += x / R;
      if (!std::isfinite(x) || x > 1e4) ++out.diverged;
    }
    out.anees += a / static_cast<double>(nees_by_node.size());
    if (a >= out.lo && a <= out.hi) ++inside;
  }
  out.fraction_inside = static_cast<double>(inside) / static_cast<double>(nees_by_node.size());
  return out;
}

// NEES of the six measured components (p of each column) only: the outputs a user reads with their 1σ.
double NodePositionNees(const AukfResult& r, std::size_t node, const Eigen::VectorXd& truth) {
  const ukf::StateMat P = r.FilterCovariance(node);
  Eigen::Matrix<double, 6, 1> e;
  Eigen::Matrix<double, 6, 6> Pp;
  for (int a = 0; a < 6; ++a) {
    e(a) = r.x_filter(3 * a, static_cast<Eigen::Index>(node)) - truth(3 * a);
    if (a >= 3) e(a) = geo::WrapPi(e(a));
    for (int b = 0; b < 6; ++b) Pp(a, b) = P(3 * a, 3 * b);
  }
  return e.dot(Pp.ldlt().solve(e));
}

double NodeNees(const AukfResult& r, std::size_t node, const Eigen::VectorXd& truth) {
  Eigen::VectorXd e = r.x_filter.col(static_cast<Eigen::Index>(node)) - truth;
  for (int c = 3; c < 6; ++c) e(3 * c) = geo::WrapPi(e(3 * c));
  return e.dot(r.FilterCovariance(node).ldlt().solve(e));
}

// Truth drawn from the filter's own model (white jerk of intensity q: accelerations that change
// randomly), generated at half steps with Φ(T/2), Q(T/2) (exact, since Q composes over sub-steps).
// A correct filter is consistent here at sample and mid-times: ANEES within its χ² band.
TEST(Aukf, ManoeuvringWhiteJerkNeesWithinChiSquareBand) {
  std::mt19937 rng(77);
  std::normal_distribution<double> g;
  const double T = 1.0 / kFrameRateHz;
  const int N = static_cast<int>(std::lround(10.0 * kFrameRateHz)) + 1, n = 18;
  const double q_pos = 0.05, q_ang = std::pow(geo::DegToRad(30.0), 2);  // m²/s⁵, rad²/s⁵
  std::vector<double> t;
  for (int k = 0; k < N; ++k) t.push_back(k * T);
  std::vector<std::vector<double>> nees(static_cast<std::size_t>(2 * N - 1));
  for (int run = 0; run < kNeesRuns; ++run) {
    std::vector<Eigen::VectorXd> truth;
    Eigen::VectorXd x(n);
    for (int c = 0; c < 6; ++c) {
      const bool ang = c >= 3;
      x.segment<3>(3 * c) << (ang ? geo::DegToRad(20.0) : 0.2) * g(rng), (ang ? geo::DegToRad(30.0) : 0.3) * g(rng),
          (ang ? geo::DegToRad(50.0) : 0.5) * g(rng);
    }
    const double h = T / 2;
    Eigen::Matrix3d Phi;
    Phi << 1, h, h * h / 2, 0, 1, h, 0, 0, 1;
    const Eigen::Matrix3d Lp = WhiteJerkQ(h, q_pos).llt().matrixL(), La = WhiteJerkQ(h, q_ang).llt().matrixL();
    for (int j = 0; j < 2 * N - 1; ++j) {
      truth.push_back(x);
      for (int c = 0; c < 6; ++c) {
        const Eigen::Vector3d w(g(rng), g(rng), g(rng));
        x.segment<3>(3 * c) = Phi * x.segment<3>(3 * c) + (c >= 3 ? La : Lp) * w;
      }
    }
    const Series s = PoseSeries(t, truth, &rng);
    AukfOptions opt;
    opt.adapt.mode = AdaptMode::kNone;
    opt.keep_covariance = true;
    opt.meas_sigma = {kPosNoiseM, kPosNoiseM, kPosNoiseM, geo::DegToRad(kAngNoiseDeg), geo::DegToRad(kAngNoiseDeg),
                      geo::DegToRad(kAngNoiseDeg)};
    opt.q = {q_pos, q_pos, q_pos, q_ang, q_ang, q_ang};
    const AukfResult r = RunAukf(s, opt);
    for (std::size_t j = 0; j < r.t_s.size(); ++j) {
      Eigen::VectorXd tr = truth[j];
      nees[j].push_back(NodeNees(r, j, tr));
    }
  }
  std::vector<std::vector<double>> sample_nodes, mid_nodes;
  for (std::size_t j = 0; j < nees.size(); ++j) {
    if (j * T / 2 < kNeesAfterS) continue;
    ((j % 2) ? mid_nodes : sample_nodes).push_back(nees[j]);
  }
  const NeesSummary ss = Nees(sample_nodes, n), sm = Nees(mid_nodes, n);
  std::printf("white-jerk NEES (%d runs): estimate mean %.2f, %.1f %% of steps in [%.2f, %.2f]; prediction mean %.2f, "
              "%.1f %% in band; %zu divergent\n",
              kNeesRuns, ss.anees, 100 * ss.fraction_inside, ss.lo, ss.hi, sm.anees, 100 * sm.fraction_inside,
              ss.diverged + sm.diverged);
  constexpr double kMinFractionInside = 0.85;  // nominal 95 %; per-step ANEES of neighbouring steps correlate
  EXPECT_EQ(ss.diverged + sm.diverged, 0u);
  for (const NeesSummary* x : {&ss, &sm}) {
    EXPECT_GE(x->anees, x->lo);
    EXPECT_LE(x->anees, x->hi);
    EXPECT_GE(x->fraction_inside, kMinFractionInside);
  }
}

// Deterministic manoeuvre (sums of sinusoids, random phases) with the CLI defaults (noise estimated from
// the data): no divergence, estimates better than the measurement, predictions within a stated bound.
TEST(Aukf, ManoeuvringSinusoidsDefaultsDoNotDiverge) {
  std::mt19937 rng(78);
  std::uniform_real_distribution<double> uphase(0.0, geo::kTwoPi);
  const double T = 1.0 / kFrameRateHz;
  const int N = static_cast<int>(std::lround(10.0 * kFrameRateHz)) + 1, n = 18;
  constexpr int kRuns = 20;
  std::vector<double> t;
  for (int k = 0; k < N; ++k) t.push_back(k * T);
  std::vector<std::vector<double>> nees(static_cast<std::size_t>(2 * N - 1)), nees_p(nees.size());
  double err2_est[6] = {}, err2_pred[6] = {}, cnt_est = 0, cnt_pred = 0;
  for (int run = 0; run < kRuns; ++run) {
    double amp[6][3], om[6][3], ph[6][3];
    for (int c = 0; c < 6; ++c) {
      for (int i = 0; i < 3; ++i) {
        amp[c][i] = (c >= 3 ? geo::DegToRad(20.0) : 0.15) / (i + 1);
        om[c][i] = 0.8 * (i + 1) + 0.1 * c;
        ph[c][i] = uphase(rng);
      }
    }
    std::vector<Eigen::VectorXd> truth;
    for (int j = 0; j < 2 * N - 1; ++j) {
      const double tt = j * T / 2;
      Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
      for (int c = 0; c < 6; ++c) {
        for (int i = 0; i < 3; ++i) {
          x(3 * c) += amp[c][i] * std::sin(om[c][i] * tt + ph[c][i]);
          x(3 * c + 1) += amp[c][i] * om[c][i] * std::cos(om[c][i] * tt + ph[c][i]);
          x(3 * c + 2) -= amp[c][i] * om[c][i] * om[c][i] * std::sin(om[c][i] * tt + ph[c][i]);
        }
      }
      truth.push_back(x);
    }
    const Series s = PoseSeries(t, truth, &rng);
    AukfOptions opt;
    opt.adapt.mode = AdaptMode::kNone;
    opt.keep_covariance = true;
    const AukfResult r = RunAukf(s, opt);
    for (std::size_t j = 0; j < r.t_s.size(); ++j) {
      nees[j].push_back(NodeNees(r, j, truth[j]));
      nees_p[j].push_back(NodePositionNees(r, j, truth[j]));
      if (r.t_s[j] < kNeesAfterS) continue;
      for (int c = 0; c < 6; ++c) {
        double e = r.x_filter(3 * c, static_cast<Eigen::Index>(j)) - truth[j](3 * c);
        if (c >= 3) e = geo::WrapPi(e);
        ((j % 2) ? err2_pred : err2_est)[c] += e * e;
      }
      ((j % 2) ? cnt_pred : cnt_est) += 1;
    }
  }
  std::vector<std::vector<double>> after, after_p;
  for (std::size_t j = 0; j < nees.size(); ++j) {
    if (j * T / 2 < kNeesAfterS) continue;
    after.push_back(nees[j]);
    after_p.push_back(nees_p[j]);
  }
  const NeesSummary su = Nees(after, n), sp = Nees(after_p, 6);
  std::printf("sinusoid manoeuvre (defaults, %d runs): 18-state NEES mean %.2f (band for this count [%.2f, %.2f]); "
              "measured-component NEES mean %.2f, %.1f %% of nodes in [%.2f, %.2f]; RMS error / measurement σ, "
              "estimate|prediction:",
              kRuns, su.anees, su.lo, su.hi, sp.anees, 100 * sp.fraction_inside, sp.lo, sp.hi);
  EXPECT_EQ(su.diverged, 0u);
  // The six values a user reads, with their 1σ, are consistent although the motion (sums of sines) is not the
  // filter's white-jerk model: σ from high-order differences and q by maximum likelihood (noise_ml.h).
  // Measured: mean 6.14, 96 % of nodes in band (20 runs; neighbouring nodes correlate). The rates and
  // accelerations are conservative (18-state mean ≈ 13 < 18): the white-jerk q over-covers a smooth jerk.
  constexpr double kPositionNeesLo = 5.0, kPositionNeesHi = 7.2;  // ±20 % of 6 around the mean
  constexpr double kMinFractionInside = 0.85;  // nominal 95 %
  EXPECT_GT(sp.anees, kPositionNeesLo);
  EXPECT_LT(sp.anees, kPositionNeesHi);
  EXPECT_GT(sp.fraction_inside, kMinFractionInside);
  for (int c = 0; c < 6; ++c) {
    const double sd = c >= 3 ? geo::DegToRad(kAngNoiseDeg) : kPosNoiseM;
    const double re = std::sqrt(err2_est[c] / cnt_est) / sd, rp = std::sqrt(err2_pred[c] / cnt_pred) / sd;
    std::printf(" %s %.2f|%.2f", kPoseColumns[static_cast<std::size_t>(c)].c_str(), re, rp);
    // Estimates must beat the raw measurement. Mid-time predictions carry half a frame of manoeuvre
    // extrapolation with the (conservative) data-estimated q: measured 1.1–1.45 × σ; bound 1.6.
    constexpr double kMaxEstimateRatio = 1.0, kMaxPredictionRatio = 1.6;
    EXPECT_LT(re, kMaxEstimateRatio);
    EXPECT_LT(rp, kMaxPredictionRatio);
  }
  std::printf("\n");
}

TEST(Aukf, MissingRowsArePredictedAndBadOptionsRejected) {
  std::vector<double> noise;
  Series s = Turntable(5, &noise);
  s.values(50, 0) = std::numeric_limits<double>::quiet_NaN();
  AukfOptions opt;
  const AukfResult r = RunAukf(s, opt);
  EXPECT_EQ(r.skipped_updates, 1u);
  EXPECT_EQ(r.status[100], AukfStatus::kPredicted);
  EXPECT_TRUE(std::isfinite(r.x_filter(0, 100)));
  AukfOptions bad;
  bad.lead = 1.0;
  std::string why;
  EXPECT_FALSE(bad.Check(&why));
  EXPECT_THROW(RunAukf(s, bad), rk::Error);
  bad = AukfOptions();
  bad.meas_sigma = {0.1, 0.2};  // two values for one column
  EXPECT_THROW(RunAukf(s, bad), rk::Error);
}

TEST(Aukf, AngleWrapThroughNorth) {
  // Yaw crossing ±180° (and written in [0, 360)): the filter must follow through the wrap.
  std::mt19937 rng(9);
  std::normal_distribution<double> g(0.0, geo::DegToRad(0.05));
  Series s;
  s.source = "wrap";
  s.columns = {"yaw_deg"};
  s.is_angle = {true};
  const int N = 200;
  s.values.resize(N, 1);
  for (int k = 0; k < N; ++k) {
    const double t = k * 0.05;
    s.t_s.push_back(t);
    s.values(k, 0) = geo::WrapPi(geo::DegToRad(170.0 + 5.0 * t) + g(rng));
  }
  AukfOptions opt;
  opt.smooth = true;
  const AukfResult r = RunAukf(s, opt);
  double worst = 0;
  for (std::size_t j = 20; j < r.t_s.size(); ++j) {
    const double truth = geo::DegToRad(170.0 + 5.0 * r.t_s[j]);
    worst = std::max(worst, std::abs(geo::AngleDiff(r.x_filter(0, static_cast<Eigen::Index>(j)), truth)));
    worst = std::max(worst, std::abs(geo::AngleDiff(r.x_smooth(0, static_cast<Eigen::Index>(j)), truth)));
  }
  constexpr double kWrapToleranceDeg = 0.3;  // ~6σ of the filtered error; a wrap bug errs by ~360°
  EXPECT_LT(geo::RadToDeg(worst), kWrapToleranceDeg);
}

}  // namespace
}  // namespace rk::filter

// The golden test: on the linear constant-acceleration model without adaptation the AUKF cycle equals the
// linear Kalman filter, state and covariance, at both half steps.
namespace rk::filter {
namespace {

using ukf::StateMat;

constexpr double kGoldenTolerance = 1e-9;  // relative; the two filters differ only by rounding

// Linear Kalman filter on the same model (Φ, white-jerk Q, partial H), started from the AUKF's node 0; for the
// per-column-block unscented transform (the default without adaptation) and the joint 9-state one.
void GoldenEqualsLinearKalmanFilter(bool joint_transform) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.03, 0.07);
  Series s;
  s.source = "golden";
  s.columns = {"x_m", "y_m", "z_m"};
  s.is_angle = {false, false, false};
  const int N = 120, m = 3, n = 9;
  s.values.resize(N, m);
  double t = 0;
  for (int k = 0; k < N; ++k) {
    s.t_s.push_back(t);
    for (int c = 0; c < m; ++c) s.values(k, c) = std::sin(0.7 * t + c) * (c + 1) + 0.01 * g(rng);
    t += u(rng);  // irregular sampling
  }
  s.values(40, 1) = std::numeric_limits<double>::quiet_NaN();  // partial update
  for (int c = 0; c < m; ++c) s.values(70, c) = std::numeric_limits<double>::quiet_NaN();  // no update
  AukfOptions opt;
  opt.adapt.mode = AdaptMode::kNone;
  opt.meas_sigma = {0.01, 0.02, 0.015};
  opt.q = {3.0, 1.0, 0.5};
  opt.lead = 0.4;
  opt.kappa = 2.0;
  opt.keep_covariance = true;
  opt.joint_transform = joint_transform;
  const AukfResult r = RunAukf(s, opt);
  ASSERT_EQ(r.t_s.size(), static_cast<std::size_t>(2 * N - 1));
  EXPECT_EQ(r.partial_updates, 1u);
  EXPECT_EQ(r.skipped_updates, 1u);
  EXPECT_EQ(r.status[140], AukfStatus::kPredicted);

  Eigen::VectorXd x = r.x_filter.col(0);
  Eigen::MatrixXd P = r.FilterCovariance(0);
  auto predict = [&](double tau) {
    Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(n, n), Q = Eigen::MatrixXd::Zero(n, n);
    for (int c = 0; c < m; ++c) {
      Phi.block<3, 3>(3 * c, 3 * c) << 1, tau, tau * tau / 2, 0, 1, tau, 0, 0, 1;
      Q.block<3, 3>(3 * c, 3 * c) = WhiteJerkQ(tau, opt.q[static_cast<std::size_t>(c)]);
    }
    x = Phi * x;
    P = Phi * P * Phi.transpose() + Q;
  };
  auto expect_near = [&](std::size_t node) {
    const Eigen::VectorXd xu = r.x_filter.col(static_cast<Eigen::Index>(node));
    const Eigen::MatrixXd Pu = r.FilterCovariance(node);
    for (int i = 0; i < n; ++i) {
      ASSERT_NEAR(xu(i), x(i), kGoldenTolerance * std::max(1.0, std::abs(x(i)))) << "node " << node << " x" << i;
      for (int j = 0; j < n; ++j) {
        ASSERT_NEAR(Pu(i, j), P(i, j), kGoldenTolerance * std::max(1.0, std::abs(P(i, j))))
            << "node " << node << " P" << i << j;
      }
    }
  };
  for (int k = 1; k < N; ++k) {
    const double tau = s.t_s[static_cast<std::size_t>(k)] - s.t_s[static_cast<std::size_t>(k - 1)];
    predict(opt.lead * tau);
    expect_near(static_cast<std::size_t>(2 * k - 1));
    predict(tau - opt.lead * tau);
    std::vector<int> a;
    for (int c = 0; c < m; ++c)
      if (std::isfinite(s.values(k, c))) a.push_back(c);
    if (!a.empty()) {
      const int ma = static_cast<int>(a.size());
      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(ma, n), R = Eigen::MatrixXd::Zero(ma, ma);
      Eigen::VectorXd z(ma);
      for (int i = 0; i < ma; ++i) {
        H(i, 3 * a[static_cast<std::size_t>(i)]) = 1;
        R(i, i) = std::pow(opt.meas_sigma[static_cast<std::size_t>(a[static_cast<std::size_t>(i)])], 2);
        z(i) = s.values(k, a[static_cast<std::size_t>(i)]);
      }
      const Eigen::MatrixXd S = H * P * H.transpose() + R;
      const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
      x += K * (z - H * x);
      P = (Eigen::MatrixXd::Identity(n, n) - K * H) * P;
      P = 0.5 * (P + P.transpose()).eval();
    }
    expect_near(static_cast<std::size_t>(2 * k));
  }
  EXPECT_EQ(r.p_repairs, 0u);
}

TEST(Aukf, GoldenEqualsLinearKalmanFilterAtBothHalfSteps) {
  {
    SCOPED_TRACE("per-column blocks");
    GoldenEqualsLinearKalmanFilter(false);
  }
  {
    SCOPED_TRACE("joint transform");
    GoldenEqualsLinearKalmanFilter(true);
  }
}

// The per-column-block transform and the joint one give the same filter and smoother, with angles through
// ±180°, a partial and an empty row, irregular sampling.
TEST(Aukf, BlockTransformEqualsJointTransform) {
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  Series s;
  s.source = "blocks";
  s.columns = {"yaw_deg", "x_m"};
  s.is_angle = {true, false};
  const int N = 150;
  s.values.resize(N, 2);
  double t = 0;
  for (int k = 0; k < N; ++k) {
    s.t_s.push_back(t);
    s.values(k, 0) = geo::WrapPi(3.0 + 0.4 * t + 0.3 * std::sin(2 * t) + 0.002 * g(rng));  // crosses ±π
    s.values(k, 1) = std::cos(t) + 0.01 * g(rng);
    t += 0.04 + 0.02 * (k % 3);
  }
  s.values(50, 1) = std::numeric_limits<double>::quiet_NaN();
  s.values(90, 0) = s.values(90, 1) = std::numeric_limits<double>::quiet_NaN();
  AukfOptions opt;
  opt.smooth = true;
  opt.keep_covariance = true;
  const AukfResult a = RunAukf(s, opt);
  opt.joint_transform = true;
  const AukfResult b = RunAukf(s, opt);
  ASSERT_EQ(a.t_s.size(), b.t_s.size());
  constexpr double kSameTolerance = 1e-9;  // rounding only
  for (std::size_t j = 0; j < a.t_s.size(); ++j) {
    const Eigen::Index jc = static_cast<Eigen::Index>(j);
    for (int i = 0; i < 6; ++i) {
      const double sc = std::max(1.0, std::abs(b.x_filter(i, jc)));
      EXPECT_NEAR(i == 0 ? geo::AngleDiff(a.x_filter(i, jc), b.x_filter(i, jc)) : a.x_filter(i, jc) - b.x_filter(i, jc),
                  0.0, kSameTolerance * sc);
      EXPECT_NEAR(i == 0 ? geo::AngleDiff(a.x_smooth(i, jc), b.x_smooth(i, jc)) : a.x_smooth(i, jc) - b.x_smooth(i, jc),
                  0.0, kSameTolerance * std::max(1.0, std::abs(b.x_smooth(i, jc))));
      EXPECT_NEAR(a.sd_smooth(i, jc), b.sd_smooth(i, jc), kSameTolerance * std::max(1.0, b.sd_smooth(i, jc)));
    }
    const ukf::StateMat Pa = a.FilterCovariance(j), Pb = b.FilterCovariance(j);
    EXPECT_LT((Pa - Pb).norm(), kSameTolerance * std::max(1.0, Pb.norm())) << "node " << j;
  }
}

}  // namespace
}  // namespace rk::filter

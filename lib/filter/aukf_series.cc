#include "filter/aukf_series.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "filter/aukf_internal.h"
#include "filter/singer_series.h"  // output naming and angle range shared by the rk-smooth subcommands
#include "geo/angles.h"
#include "io/error.h"

// The AUKF in stages (aukf_internal.h): this file holds the options, the input checks and RunAukf; the noise,
// the forward filter and the smoother are in aukf_noise.cc, aukf_forward.cc and aukf_smoother.cc.
namespace rk::filter {

using ukf::MeasMat;
using ukf::MeasVec;
using ukf::SigmaMat;
using ukf::StateMat;
using ukf::StateVec;

const io::OptionTable<AukfOptions>& AukfOptions::Table() {
  using O = AukfOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--lead", &O::lead, "", io::Bounds::Open(0.0, 1.0),
                "Fraction of each interval at which the prediction is output, in (0, 1)")
          .Flag("--smooth", &O::smooth, "Add 'smoothed' rows (unscented RTS) at sample and mid-times")
          .Sub(&O::adapt, AdaptiveNoiseOptions::Table())
          .Choice("--noise-estimate", &O::noise_estimator,
                  {NoiseEstimator::kMaxLikelihood, NoiseEstimator::kDifferences}, NoiseEstimatorName,
                  "How --meas-sigma/--q not given are estimated per column: ml (sigma from high-order differences, "
                  "q by maximum likelihood of the innovations) or moments (third differences at lags 1-8 only)")
          .Choice("--noise-fit", &O::noise_fit, {NoiseFit::kCausal, NoiseFit::kFile}, NoiseFitName,
                  "Data the fitted noise of the estimate/prediction rows may use: causal (the rows up to each "
                  "time, refitted as the file goes: no row depends on a later sample) or file (the whole file, "
                  "the old default: earlier rows then depend on later samples)")
          .Choice("--smooth-noise-fit", &O::smooth_noise_fit, {NoiseFit::kCausal, NoiseFit::kFile}, NoiseFitName,
                  "Noise fit behind the 'smoothed' rows: file (an extra forward pass with the whole-file fit) or "
                  "causal (smooth the causal pass)")
          // n + kappa > 0 for every n >= 1 columns' 3n states.
          .Real("--kappa", &O::kappa, "", io::Bounds{.lo = -1.0, .lo_open = true, .finite = true},
                "Sigma-point parameter kappa: W0 = kappa/(n+kappa)");
  return table;
}

const io::OptionTable<AukfOutputOptions>& AukfOutputOptions::Table() {
  static const io::OptionTable<AukfOutputOptions> table =
      io::OptionTable<AukfOutputOptions>()
          .Flag("--derivatives", &AukfOutputOptions::derivatives,
                "Add <base>_rate_<unit>_s and <base>_accel_<unit>_s2 columns (e.g. yaw_rate_deg_s)")
          .Flag("--sigmas", &AukfOutputOptions::sigmas,
                "Add <base>_sigma_<unit> columns (1-sigma of each value, file units)");
  return table;
}

bool AukfOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  for (double s : meas_sigma) {
    if (!(s > 0.0 && std::isfinite(s))) {
      *why = "--meas-sigma values must be > 0";
      return false;
    }
  }
  for (double v : q) {
    if (!(v >= 0.0 && std::isfinite(v))) {
      *why = "--q values must be >= 0";
      return false;
    }
  }
  if (meas_sigma.size() > static_cast<std::size_t>(ukf::kMaxColumns) ||
      q.size() > static_cast<std::size_t>(ukf::kMaxColumns)) {
    *why = "--meas-sigma/--q: at most 12 values";
    return false;
  }
  return adapt.Check(why) && causal.Check(why);
}

std::string NoiseEstimatorName(NoiseEstimator e) { return e == NoiseEstimator::kMaxLikelihood ? "ml" : "moments"; }

Eigen::Matrix3d WhiteJerkQ(double t, double q) {
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
  Eigen::Matrix3d Q;
  Q << t5 / 20, t4 / 8, t3 / 6, t4 / 8, t3 / 3, t2 / 2, t3 / 6, t2 / 2, t;
  return q * Q;
}

ukf::StateMat AukfResult::FilterCovariance(std::size_t node) const {
  const std::size_t packed = static_cast<std::size_t>(n * (n + 1) / 2);
  RK_CHECK((node + 1) * packed <= cov_filter.size(), "covariance not kept");
  StateMat P(n, n);
  const double* p = cov_filter.data() + node * packed;
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      P(i, j) = *p;
      P(j, i) = *p;
      ++p;
    }
  }
  return P;
}

namespace {

// The options and the series fit together: usage errors (exit 2) and data errors (exit 3).
void CheckAukfInput(const Series& series, const AukfOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  const int m = static_cast<int>(series.columns.size());
  if (m < 1 || m > ukf::kMaxColumns) throw UsageError("--columns: 1 to 12 columns, got " + std::to_string(m));
  if (options.meas_sigma.size() > 1 && options.meas_sigma.size() != static_cast<std::size_t>(m)) {
    throw UsageError("--meas-sigma: give one value or one per column (" + std::to_string(m) + ")");
  }
  if (options.q.size() > 1 && options.q.size() != static_cast<std::size_t>(m)) {
    throw UsageError("--q: give one value or one per column (" + std::to_string(m) + ")");
  }
  const std::size_t N = series.rows();
  if (N < 3) throw TooFewSamplesError(series.source, "needs at least 3 samples, has " + std::to_string(N));
  if (!(m * 3 + options.kappa > 0)) throw UsageError("--kappa: n + kappa must be > 0");
}

// Every column has at least 2 values.
void CheckColumnValues(const Series& series) {
  const Eigen::MatrixXd& Z = series.values;
  for (int c = 0; c < static_cast<int>(series.columns.size()); ++c) {
    std::size_t values = 0;
    for (std::size_t k = 0; k < series.rows(); ++k) values += std::isfinite(Z(static_cast<Eigen::Index>(k), c)) ? 1 : 0;
    if (values < 2) {
      throw DataError(series.source, 0, 0, "column '" + series.columns[static_cast<std::size_t>(c)] + "' has fewer than 2 values");
    }
  }
}

// The model of the series' columns (white jerk per column, angle rows wrapped).
void InitModel(const Series& series, const AukfOptions& options, aukf_detail::Model* model) {
  const int m = static_cast<int>(series.columns.size());
  const int n = 3 * m;
  model->m = m;
  model->n = n;
  model->kappa = options.kappa;
  model->w = ukf::MakeWeights(n, options.kappa);
  model->is_angle = series.is_angle;
  model->block_diagonal = options.adapt.mode == AdaptMode::kNone && !options.joint_transform;
  model->scale.resize(n);
  for (int c = 0; c < m; ++c) {
    if (series.is_angle[static_cast<std::size_t>(c)]) model->angles.Add(3 * c);
  }
}

}  // namespace

AukfResult RunAukf(const Series& series, const AukfOptions& options) {
  CheckAukfInput(series, options);
  const int m = static_cast<int>(series.columns.size());
  const int n = 3 * m;
  const std::size_t N = series.rows();

  AukfResult res;
  res.m = m;
  res.n = n;
  res.samples = N;
  res.interval_s = aukf_detail::MedianInterval(series.t_s, N);
  CheckColumnValues(series);

  res.meas_sigma_estimated = options.meas_sigma.empty();
  res.q_estimated = options.q.empty();
  const bool estimated = res.meas_sigma_estimated || res.q_estimated;
  const bool causal = estimated && options.noise_fit == NoiseFit::kCausal;
  aukf_detail::NoiseFitOut noise;
  aukf_detail::NoiseInUse use = aukf_detail::InitialNoise(series, options, res, causal, &noise);
  res.noise_known_row.assign(static_cast<std::size_t>(m), causal ? N : 0);

  aukf_detail::Model model;
  InitModel(series, options, &model);

  const std::size_t J = 2 * N - 1;
  const bool smooth_here = options.smooth && (!estimated || options.smooth_noise_fit == options.noise_fit);
  const bool keep_cov = options.keep_covariance || smooth_here;
  const std::size_t packed = static_cast<std::size_t>(n * (n + 1) / 2);
  if (keep_cov) res.cov_filter.reserve(J * packed);
  aukf_detail::IntervalNoise intervals;
  intervals.store_q = smooth_here && AdaptsQ(options.adapt.mode);
  intervals.store_model_q = smooth_here && causal;
  res.t_s.reserve(J);
  res.x_filter.resize(n, static_cast<Eigen::Index>(J));
  res.sd_filter.resize(n, static_cast<Eigen::Index>(J));

  aukf_detail::RunForward(series, options, causal, keep_cov, &model, &noise, &use, &intervals, &res);

  if (options.smooth && !smooth_here) {
    // Smoothed rows from a forward pass with the other noise fit (they may use every sample).
    AukfOptions o = options;
    o.noise_fit = options.smooth_noise_fit;
    o.keep_covariance = false;
    AukfResult r = RunAukf(series, o);
    res.x_smooth = std::move(r.x_smooth);
    res.sd_smooth = std::move(r.sd_smooth);
    res.smooth_meas_sigma = r.meas_sigma;
    res.smooth_q = r.q;
    res.p_repairs += r.p_repairs;
    return res;
  }
  if (smooth_here) aukf_detail::RtsSmooth(options, intervals, &model, &res);
  return res;
}

}  // namespace rk::filter


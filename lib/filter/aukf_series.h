// Adaptive unscented Kalman filter with fixed-lead prediction over a time series — seed 000
// (Sun & Zhang 2015, "Pose prediction method for moving helmet based on Kalman filtering",
// eqs. 1–20, with the errata of docs/seed-notes.md), plus an unscented Rauch–Tung–Striebel smoother
// (S. Särkkä, "Unscented Rauch–Tung–Striebel smoother", IEEE TAC 53(3), 2008).
//
// Model, per value column c (m columns, n = 3m states):
//   state x_c = [p, p', p'']ᵀ (constant acceleration, eq. 1), Φ(τ) = blockdiag [[1, τ, τ²/2], [0, 1, τ], [0, 0, 1]],
//   process noise: white jerk of intensity q_c (unit²/s⁵):
//     Q_c(τ) = q_c [[τ⁵/20, τ⁴/8, τ³/6], [τ⁴/8, τ³/3, τ²/2], [τ³/6, τ²/2, τ]],
//   which composes exactly over sub-steps: Φ(b) Q(a) Φ(b)ᵀ + Q(b) = Q(a + b), so splitting an interval
//   into two half steps each with its own Q(·) gives the same one-step covariance.
//   measurement z = H x + v, H picks p of every column (eq. 2), v ~ N(0, R).
// Cycle for each interval t_{k−1} → t_k, τ_k = t_k − t_{k−1} (irregular sampling allowed):
//   1. sigma points of (x_{k−1}, P_{k−1}) (eqs. 3–4), propagate by Φ(ℓτ_k) (ℓ = lead, default ½):
//      X̂ = Σ W ΦX,  P = Σ W (ΦX − X̂)(ΦX − X̂)ᵀ + Q(ℓτ_k)          (eqs. 5–6)
//      → the `prediction` output at t_{k−1} + ℓτ_k.
//   2. new sigma points at the mid-time (eqs. 7–8), propagate by Φ((1−ℓ)τ_k) with Q((1−ℓ)τ_k) (eqs. 9–10).
//   3. update with the measured components a of Z_k (partial H when some are missing; none → no update):
//      P_y = H P_{k|k−½} Hᵀ + R,  P_xy = P_{k|k−½} Hᵀ,  K = P_xy P_y⁻¹,
//      X_k = X_{k|k−½} + K (Z_k − Ŷ),  P_k = P_{k|k−½} − K P_y Kᵀ          (eqs. 11–16)
//      (the extracted eqs. 12–13 take P_y and P_xy from the propagated sigma points without Q; with
//      additive Q and linear H the unscented transform of the redrawn points gives exactly the forms
//      above, which is what makes the filter equal the Kalman filter on a linear model.)
//   Every covariance is symmetrised after each step; a covariance without a Cholesky factor is
//   repaired (ukf::RepairSpd) and counted.
// Adaptation (adaptive_noise.h, Mohamed & Schwarz 1999): R̂ = C_k − ⟨H P_{k|k−½} Hᵀ⟩ (averaged over the
//   same memory) replaces R from the
//   next update; Q̂ = K_k C_k K_kᵀ is the process noise of one interval τ_k, used per unit time
//   (Q̂/τ_k) and scaled by the sub-step length for each half step.
// Angles (columns ending `_deg`, radians inside): wrap-safe sigma-point means, innovations, state
//   after each update, smoother differences (all wrapped to (−π, π]).
// Initialisation (documented in docs/rk-smooth.md), causal: each column starts at its first value z_i,
//   x = [z_i, 0, 0], P = diag(σ², (30σ/T)², (100σ/T²)²) (diffuse in rate and acceleration: the next two
//   values determine them, as a two- or three-point start would, without reading ahead). Before its first
//   value a column has no estimate (empty output fields).
// Default noise (when not given), per column (NoiseEstimator::kMaxLikelihood):
//   σ̂ from high-order differences (NoiseSigmaFromDifferences, singer_series.h), q̂ by maximum likelihood of
//   the innovations with that σ̂ (FitWhiteJerkQMl, noise_ml.h), started from the moments below.
//   Moments (NoiseEstimator::kDifferences alone): third differences at lags h = 1, 2, 4, 8 samples,
//   v_h = mean (Δ³_h z)², with E v_h = 20σ² + 0.55 q (hT)⁵ for white jerk (0.55 = ∫B₂², B₂ the quadratic
//   B-spline): weighted least-squares fit of a + b h⁵ (weights 1/v_h²), q̂ = b/(0.55 T⁵) ≥ 0,
//   σ̂² = (v₁ − b)/20 (T = median interval; assumes near-regular sampling).
// When the noise is fitted (NoiseFit):
//   kCausal (default): every `estimate` and `prediction` depends on no later sample. The fit is redone on the
//     rows 0..k−1 after the update of row k−1, for k = first_fit … dense_until − 1 and k = dense_until·2^j
//     (CausalNoiseOptions), and used from that node on; a refit with k ≤ restart_until re-runs the filter over
//     rows 0..k−1 with the new noise (cheap, and the early state then matches its noise), later refits keep
//     the state. Causal fits start on few samples: σ̂ uses difference orders 3…min(8, rows/9), the likelihood
//     leaves out 3 innovations, and q̂ is the upper end of q's 95 % likelihood interval (NoiseMlFit::q_upper),
//     since an under-estimated q makes the filter over-confident. Before a column's first fit, the filter runs with a provisional noise (σ_p, q_p = σ_p²/T⁵:
//     the means of a linear filter do not depend on the common scale of P₀, Q and R) and the column's 1σ is
//     not output (empty).
//   kFile: σ and q fitted once on the whole file (the rows before k then depend on later samples).
// The smoothed rows (smooth_noise_fit) may use everything: by default a second forward pass with the whole-file fit.
// Smoother: unscented RTS over the sequence of half steps (sample and mid-times alike): from the
//   stored filtered (x_j, P_j) of every node, sigma points are propagated to node j+1,
//   x⁻ = Σ W ΦX, P⁻ = Σ W (ΦX − x⁻)(·)ᵀ + Q_j, C = Σ W (X − x_j)(ΦX − x⁻)ᵀ, G = C (P⁻)⁻¹,
//   x_j^s = x_j + G (x_{j+1}^s − x⁻), P_j^s = P_j + G (P_{j+1}^s − P⁻) Gᵀ.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "filter/adaptive_noise.h"
#include "filter/noise_ml.h"
#include "filter/series.h"
#include "filter/ukf.h"
#include "io/csv.h"
#include "io/json_util.h"
#include "io/options.h"
#include "io/run_summary.h"

namespace rk::filter {

enum class NoiseEstimator { kMaxLikelihood, kDifferences };
std::string NoiseEstimatorName(NoiseEstimator e);  // "ml", "moments"

// Which samples the fitted σ and q of the forward pass may use: those up to each time, or the whole file.
enum class NoiseFit { kCausal, kFile };
std::string NoiseFitName(NoiseFit f);  // "causal", "file"

// Refit schedule of NoiseFit::kCausal, in rows available (see the header comment).
struct CausalNoiseOptions {
  int first_fit = 16;       // rows before the first fit (≥ 4: the moments need 4 consecutive values)
  int dense_until = 32;     // refit after every row below this count, then at dense_until·2^j rows
  int restart_until = 256;  // refits at up to this many rows re-run the filter over the rows so far
  bool Check(std::string* why) const;
  bool IsRefit(std::size_t rows) const;
};

struct AukfOptions {
  double lead = 0.5;   // fraction ℓ of each interval at which the prediction is output, in (0, 1)
  double kappa = 1.0;  // sigma-point parameter κ (the paper's m): W0 = κ/(n+κ); n + κ > 0
  // Initial measurement noise σ per column, SI/radians (one value = all columns); empty → estimated.
  std::vector<double> meas_sigma;
  // White-jerk intensity q per column, SI/radians: unit²/s⁵ (one value = all columns); empty → estimated.
  std::vector<double> q;
  // How σ and q are estimated when not given: σ from high-order differences and q by maximum likelihood of
  // the innovations (noise_ml.h), started from the third-difference moments (EstimateColumnNoise); or those
  // moments alone.
  NoiseEstimator noise_estimator = NoiseEstimator::kMaxLikelihood;
  NoiseMlOptions noise_ml;
  // Data the fitted noise of the forward pass (estimate and prediction rows) may use; and of the smoothed
  // rows (kFile: an extra forward pass with the whole-file fit feeds the smoother; measured better, see
  // docs/rk-smooth.md). Both only matter for σ or q not given.
  NoiseFit noise_fit = NoiseFit::kCausal;
  NoiseFit smooth_noise_fit = NoiseFit::kFile;
  CausalNoiseOptions causal;
  AdaptiveNoiseOptions adapt;
  bool smooth = false;           // run the unscented RTS smoother
  bool keep_covariance = false;  // keep every node's filtered covariance (tests, NEES)
  // Run the unscented transform on the joint state even when the columns are independent (no adaptation),
  // instead of per column block; same results to rounding, slower (tests, benchmarks).
  bool joint_transform = false;

  // --lead, --smooth, --window, --fading, --noise-estimate, --noise-fit, --smooth-noise-fit, --kappa
  // (io/options.h): CLI flags, the bounds in Check() and the report's options keys. --adapt (with its
  // "auto"), the lists --meas-sigma/--q and the choice of memory (--fading given) are read by the app.
  static const io::OptionTable<AukfOptions>& Table();
  bool Check(std::string* why) const;
};

enum class AukfStatus { kOk, kPredicted };

struct AukfResult {
  int m = 0, n = 0;
  // One node per sample time and per mid-time, in time order: sample 0, mid, sample 1, mid, ...
  std::vector<double> t_s;
  std::vector<bool> is_mid;
  std::vector<int> sample;          // sample row of a sample node; preceding sample row of a mid node
  std::vector<AukfStatus> status;   // kPredicted: sample row without any measured column
  Eigen::MatrixXd x_filter, sd_filter;  // n × nodes: filtered (sample) or predicted (mid) mean, 1σ
  Eigen::MatrixXd x_smooth, sd_smooth;  // n × nodes, when smoothing
  std::vector<double> cov_filter;       // packed upper triangles, n(n+1)/2 per node (keep_covariance/smooth)
  ukf::StateMat FilterCovariance(std::size_t node) const;
  // Per column: first sample row with a value (nodes of earlier rows have no estimate for the column), and
  // first sample row from which its noise is known (given or fitted: the 1σ of earlier nodes is not output).
  std::vector<std::size_t> first_row, noise_known_row;
  bool HasValue(std::size_t node, int column) const { return sample_row(node) >= first_row[static_cast<std::size_t>(column)]; }
  bool HasSigma(std::size_t node, int column) const {
    return HasValue(node, column) && sample_row(node) >= noise_known_row[static_cast<std::size_t>(column)];
  }
  std::size_t sample_row(std::size_t node) const { return static_cast<std::size_t>(sample[node]); }

  // What was used.
  double interval_s = 0.0;          // median sample interval T
  std::vector<double> meas_sigma;   // initial σ per column (SI/radians)
  std::vector<double> q;            // white-jerk intensity per column (SI/radians)
  bool meas_sigma_estimated = false, q_estimated = false;
  std::vector<NoiseMlFit> noise_fit;  // per column, when σ or q came from maximum likelihood (the last fit)
  std::vector<bool> noise_fit_used;   // per column: the ML fit was used (false: moments only)
  struct NoiseRefit {                 // NoiseFit::kCausal: one fit on the rows 0..rows−1
    std::size_t rows = 0;
    bool restarted = false;           // the filter was re-run over those rows with the new noise
    std::vector<double> meas_sigma, q;
  };
  std::vector<NoiseRefit> noise_refits;
  // Noise of the smoothed rows when they came from an extra whole-file-fit pass (smooth_noise_fit kFile).
  std::vector<double> smooth_meas_sigma, smooth_q;
  ukf::MeasMat final_R;             // R at the end (SI/radians²)
  ukf::StateMat final_Q;            // process noise of one interval T at the end
  bool final_Q_adapted = false;

  // Counters.
  std::size_t samples = 0;
  std::size_t updates = 0;           // sample rows with at least one measured column
  std::size_t partial_updates = 0;   // ... of which some columns were missing
  std::size_t skipped_updates = 0;   // sample rows without any measured column (status predicted)
  std::size_t adapt_steps = 0;       // Q/R re-estimated
  std::size_t adapt_skipped = 0;     // partial rows that did not enter C_k
  std::size_t q_repairs = 0, r_repairs = 0, p_repairs = 0;
  double nis_sum = 0.0;              // Σ dᵀ P_y⁻¹ d over updates
  std::size_t nis_dof = 0;           // Σ dim(d)
  double NisMean() const { return updates ? nis_sum / static_cast<double>(updates) : 0.0; }
};

// Runs the cycle (and the smoother with options.smooth). Throws UsageError for options that do not
// fit the series (more σ/q values than columns, more than 12 columns), DataError when a column has
// fewer than two values.
AukfResult RunAukf(const Series& series, const AukfOptions& options);

// White-jerk Q of one column block over τ (unit²/s⁵ · s⁵ …).
Eigen::Matrix3d WhiteJerkQ(double tau_s, double q);

// Per-column noise estimate from third differences (see header comment). Returns false when the
// column has no run of 4 consecutive values.
// `rows`: use the rows [0, rows) only (the data up to a time).
bool EstimateColumnNoise(const Series& series, int column, double interval_s, double* sigma, double* q,
                         std::size_t rows = static_cast<std::size_t>(-1));

struct AukfOutputOptions {
  bool derivatives = false;  // <base>_rate_<unit>_s, <base>_accel_<unit>_s2 columns (DerivedColumnName)
  bool sigmas = false;       // <base>_sigma_<unit> (1σ of the value) columns
  int decimals = 9;
  static const io::OptionTable<AukfOutputOptions>& Table();  // --derivatives, --sigmas
};

// Output table `t_s,kind,<columns>,status[,<rate>,<accel> per column][,<base>_sigma_<unit> per column]`, rows in
// time order: `estimate` (sample times) / `prediction` (mid-times), each followed by its `smoothed`
// row when smoothing. Angles in degrees, in [0, 360) for azimuth/yaw-like columns (name starts with
// `az` or `yaw`) or when some input value exceeds 180°, else in (−180, 180] (AngleColumnIs360). Empty fields:
// a column before its first value (AukfResult::HasValue); a forward row's 1σ before its noise is known (HasSigma).
io::CsvWriter AukfCsv(const Series& series, const AukfResult& result, const AukfOutputOptions& out);

// Options, counters, final Q and R (SI/radians) and NIS for the JSON report.
io::Json AukfReportJson(const Series& series, const AukfOptions& options, const AukfResult& result);
// The run's summary (io/run_summary.h): the written rows by status (ok / predicted), the warning for sample rows
// without a value (on stderr), the share of sample rows updated as headline, AukfReportJson as details.
io::RunSummary AukfSummary(const Series& series, const AukfOptions& options, const AukfResult& result);

}  // namespace rk::filter

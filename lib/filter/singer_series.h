// Singer-model Kalman filter and Rauch–Tung–Striebel smoother over a Series, one
// independent 3-state filter per value column (rk-smooth singer; seed 001 §2.2,
// Guan et al. 2014, Singer model: R. A. Singer, IEEE Trans. AES-6(4), 1970).
//
// Model per column (lib/track/singer.h): x = [p, p', p'']ᵀ, a = 1/τ_m,
//   x_{k+1} = Ψ(T_k) x_k + ζ_k,  ζ_k ~ N(0, Q(T_k)),  T_k = t_{k+1} − t_k (irregular),
//   Q = Singer's exact discrete noise for intensity q = 2 a σ_m² (series form for aT < 1),
//   z_k = p_k + v_k,  v_k ~ N(0, σ_z²).
// Forward pass (Kalman filter):
//   x_{k|k−1} = Ψ x_{k−1|k−1},  P_{k|k−1} = Ψ P_{k−1|k−1} Ψᵀ + Q
//   ν = z_k − p_{k|k−1} (angles: wrapped to (−π, π], i.e. z unwrapped next to the state),
//   S = P_{k|k−1}(0,0) + σ_z², K = P_{k|k−1} e₁ / S,  x_{k|k} = x_{k|k−1} + K ν,
//   P_{k|k} = (I − K e₁ᵀ) P (I − K e₁ᵀ)ᵀ + K σ_z² Kᵀ (Joseph form), symmetrised.
//   A row without a value for the column (empty field, or masked by a device status)
//   gets no update: x_{k|k} = x_{k|k−1}.
// Backward pass (RTS, Rauch, Tung & Striebel 1965):
//   C_k = P_{k|k} Ψ_kᵀ P_{k+1|k}⁻¹,
//   x_{k|N} = x_{k|k} + C_k (x_{k+1|N} − x_{k+1|k}),  P_{k|N} = P_{k|k} + C_k (P_{k+1|N} − P_{k+1|k}) C_kᵀ.
// Estimates between rows (resampling): the smoother is evaluated at any time t in
// (t_k, t_{k+1}) exactly as if t had been inserted into the forward pass as a step without
// measurement (the Markov chain splits: Ψ(T) = Ψ(T−τ)Ψ(τ), Q(T) = Ψ(T−τ)Q(τ)Ψ(T−τ)ᵀ + Q(T−τ)),
// see EvaluateSinger.
// Initialisation: at a column's first usable sample, p = z, var p = σ_z², p' ~ N(0, σ_v²)
// with σ_v = 2 × the largest |Δz/Δt| of the column (a diffuse prior on the scale of the
// data), p'' ~ N(0, σ_m²) (Singer's stationary acceleration variance). The column has no
// estimate before its first usable sample.
// Measurement noise σ_z: given, or estimated from the data: the k-th differences of the
// usable samples of white noise have variance C(2k, k) σ_z²; σ_z = 1.4826 · MAD / √C(2k, k)
// with k = kNoiseDifferenceOrder (the signal's k-th derivative must be small against the
// noise at the sample interval: see docs/rk-smooth-singer-resample.md for the measurement).
// Assumptions: columns are uncorrelated; white Gaussian measurement noise; near-uniform
// sampling for the σ_z estimate. Angles: radians inside, state kept unwrapped.
// Memory: RunSingerSeries keeps every row's estimates (short series); SingerSmoother gives the same
// numbers block by block from checkpoints, in memory independent of the length (long logs, issue 27).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <span>
#include <string>
#include <vector>

#include "filter/series.h"
#include "io/csv.h"
#include "io/options.h"
#include "track/singer.h"

namespace rk::io {
struct RunSummary;
}

namespace rk::filter {

// Order k of the differences used to estimate σ_z.
inline constexpr int kNoiseDifferenceOrder = 4;

// Default acceleration RMS σ_m by column unit (column units / s²), used when
// --accel-sigma is not given. Tuned on seed 001's range case (see the doc).
inline constexpr double kDefaultAccelSigmaMps2 = 0.5;   // `_m` columns
inline constexpr double kDefaultAccelSigmaDegS2 = 5.0;  // `_deg` columns
inline constexpr double kDefaultAccelSigmaPxS2 = 50.0;  // `_px` columns
inline constexpr double kDefaultManeuverTimeS = 2.0;    // τ_m

inline constexpr int kAutoAccelGridLow = -8;  // 1/16 × default
inline constexpr int kAutoAccelGridHigh = 6;  // 8 × default

struct SingerSeriesOptions {
  double maneuver_time_s = kDefaultManeuverTimeS;  // τ_m = 1/a (s), > 0
  // σ_m per column (internal units: m, rad, ... per s²); empty = default by unit
  // (DefaultAccelSigma), one value = every column, else one per column. ≥ 0.
  std::vector<double> accel_sigma;
  // σ_z per column (internal units); empty = estimate from the data; one or one per column. > 0.
  std::vector<double> meas_sigma;
  // With accel_sigma empty: choose σ_m per column by maximum likelihood of the forward
  // pass's innovations, Σ (ln S + ν²/S), over the grid DefaultAccelSigma × 2^(k/2),
  // k = kAutoAccelGridLow..kAutoAccelGridHigh. false: use the unit default as is.
  bool auto_accel_sigma = true;
  bool smooth = true;  // run the RTS backward pass

  // The numeric options, one line each (docs/architecture.md "Adding an option"): --maneuver-time.
  static const io::OptionTable<SingerSeriesOptions>& Table();
  // Table().Check, then the lists: accel_sigma >= 0, meas_sigma > 0.
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
};

// Default σ_m (internal units/s²) for a column name; NaN if the unit is unknown.
double DefaultAccelSigma(const std::string& column);

struct SingerColumnStats {
  std::size_t updates = 0;      // rows with a measurement
  std::size_t missing = 0;      // rows without (after the first usable one)
  std::size_t first_row = 0;    // row index of the first measurement
  double meas_sigma = 0.0;      // σ_z used (internal units)
  bool meas_sigma_estimated = false;
  double accel_sigma = 0.0;     // σ_m used (internal units/s²)
  bool accel_sigma_selected = false;  // chosen by maximum likelihood
  double nis_mean = 0.0;        // mean of ν²/S over updates after the first (expected 1)
  std::size_t nis_count = 0;
};

enum class SingerRowStatus { kOk, kPredicted, kLost };
std::string SingerRowStatusName(SingerRowStatus s);  // "ok", "predicted", "lost"

// One column's estimates; vectors indexed by row (by row − begin in a SingerBlock), rows < first_row unused.
struct SingerTrack {
  std::vector<Eigen::Vector3d> x_pred, x_filt, x_smooth;
  std::vector<Eigen::Matrix3d> P_pred, P_filt, P_smooth;
  double a_per_s = 0.0, q = 0.0;  // Singer a and white-noise intensity q = 2 a σ_m²
};

// What the reports need of a run: per-column figures and row counts.
struct SingerSeriesSummary {
  bool smoothed = false;                 // the RTS backward pass was run
  std::vector<SingerColumnStats> stats;  // per column
  std::size_t rows = 0, rows_ok = 0, rows_predicted = 0, rows_lost = 0;

  // Reports, in column units (degrees for _deg columns; docs/rk-smooth-singer-resample.md "Report").
  // {column: {updates, meas_sigma, meas_sigma_estimated, accel_sigma, nis_mean}}; `counts` adds missing
  // and nis_count. A NIS without updates is null.
  nlohmann::json ColumnsJson(const Series& series, bool counts) const;
  // The "summary" rk-run copies: {"nis_mean": {column: mean NIS or null}, "rows_lost": n}.
  nlohmann::json SummaryJson(const Series& series) const;
  // rk-smooth singer's report body: smoothed, maneuver_time_s, rows, rows_ok, rows_predicted, rows_lost,
  // columns (with counts) and summary.
  nlohmann::json ToJson(const Series& series, double maneuver_time_s) const;
  // The run's summary (io/run_summary.h): rows by status, a report-only warning for lost rows, the share of
  // rows ok as headline, ToJson as details.
  io::RunSummary Summary(const Series& series, double maneuver_time_s) const;
};

// A whole run kept in memory: x and P predicted, filtered and smoothed of every row and column, 288 bytes a
// row and column (RunSingerSeries; for short series: rk-intersect --smooth, tests). Long series go through
// SingerSmoother, which gives the same numbers block by block.
struct SingerSeriesResult : SingerSeriesSummary {
  std::vector<SingerTrack> tracks;       // per column
  std::vector<SingerRowStatus> status;   // per row: ok = some column measured, predicted = none but
                                         // some column has an estimate, lost = no estimate at all
  // Best estimate at a row (smoothed if available, else filtered); false before first_row.
  bool At(std::size_t column, std::size_t row, Eigen::Vector3d* x, Eigen::Matrix3d* P) const;
};

// Status of row `row` of `series` given each column's stats (first_row, updates): see SingerSeriesResult::status.
SingerRowStatus SingerRowStatusAt(const Series& series, const std::vector<SingerColumnStats>& stats, std::size_t row);

// A column's filter state after a row: x, P and whether the column has started (had its first value).
struct SingerState {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  bool started = false;
};

// A column's model once σ_z and σ_m are fixed.
struct SingerColumnModel {
  bool angle = false;    // innovations wrapped to (−π, π]
  double a = 0.0;        // 1/τ_m (1/s)
  double R = 0.0;        // σ_z² (internal units²)
  double vel_sigma = 0.0, accel_sigma = 0.0;  // prior σ of p' at the first value; σ_m
  double q = 0.0;        // 2 a σ_m²
};

// Rows per block of SingerSmoother: 4096 rows × (x, P predicted, filtered, smoothed) = 1.2 MB a column,
// against 288 bytes a row and column for the whole series in SingerSeriesResult.
inline constexpr std::size_t kSingerBlockRows = 4096;

// The estimates of every column over one block of rows [begin, end), while SingerSmoother::ForEachBlock
// visits it: tracks (indexed by row − begin) hold x/P predicted and filtered, and smoothed when the run
// smooths, for rows begin..end − 1, and row end's predicted and smoothed state when end < rows (what the RTS
// step and an evaluation between rows end − 1 and end need).
class SingerBlock {
 public:
  std::size_t begin() const { return begin_; }
  std::size_t end() const { return end_; }
  // As SingerSeriesResult::At, for a row in [begin, end).
  bool At(std::size_t column, std::size_t row, Eigen::Vector3d* x, Eigen::Matrix3d* P) const;

 private:
  friend class SingerSmoother;
  std::size_t begin_ = 0, end_ = 0;
  bool smoothed_ = false;
  const std::vector<SingerColumnStats>* stats_ = nullptr;
  std::vector<SingerTrack> tracks_;  // per column, block_rows + 1 entries
};

// The same filter and RTS smoother as RunSingerSeries, in memory independent of the series' length
// (checkpointed smoother). The forward pass (run by the constructor, every candidate σ_m of every column in
// one pass over the rows) keeps only each column's filtered state at the start of every block of
// `block_rows` rows, besides the counts. A first backward sweep, from the last block to the first,
// recomputes each block forward from its checkpoint and smooths it backwards from the smoothed state of the
// row after it, keeping the smoothed state at the block's first row; ForEachBlock then recomputes and
// smooths each block again, in time order, and hands it over. Every recomputation runs the same arithmetic
// in the same order on the same inputs as the single forward and backward pass, so the numbers are those of
// RunSingerSeries exactly. Cost: the forward pass once per candidate, then twice again (once without
// smoothing) and the RTS step twice; memory: two states per block and column, plus one block.
class SingerSmoother {
 public:
  // Throws as RunSingerSeries. `series` must outlive the smoother. block_rows ≥ 1 (RK_CHECK).
  SingerSmoother(const Series& series, const SingerSeriesOptions& options, std::size_t block_rows = kSingerBlockRows);

  const SingerSeriesSummary& summary() const { return summary_; }
  SingerRowStatus RowStatus(std::size_t row) const { return SingerRowStatusAt(series_, summary_.stats, row); }
  std::size_t blocks() const { return (series_.rows() + block_rows_ - 1) / block_rows_; }

  // Calls visit(block) for every block, in time order (smoothed estimates if the run smooths, else filtered).
  void ForEachBlock(const std::function<void(const SingerBlock&)>& visit) const;

  // EvaluateSinger, block by block: the row whose block holds what an estimate of `column` (with at least one
  // update) at t_s needs (the first row with a value for t_s before it, else the last row at or before t_s;
  // non-decreasing in t_s), and the estimate itself from that row's block.
  std::size_t EvaluationRow(std::size_t column, double t_s) const;
  void Evaluate(const SingerBlock& block, std::size_t column, double t_s, Eigen::Vector3d* x,
                Eigen::Matrix3d* P) const;

 private:
  struct Column {
    SingerColumnModel model;
    std::vector<SingerState> start;       // [b], b ≥ 1: filtered state after row b·block_rows − 1
    std::vector<SingerState> smooth_end;  // [b]: smoothed state at row (b + 1)·block_rows (first sweep)
  };
  void Forward(const std::vector<std::vector<SingerColumnModel>>& candidates, const std::vector<std::size_t>& fallback);
  void SmoothBlockEnds();
  SingerBlock NewBlock() const;
  void BlockSteps(std::size_t b, std::vector<track::SingerStep>* steps) const;
  bool Recompute(std::size_t b, std::size_t column, const std::vector<track::SingerStep>& steps,
                 SingerBlock* block) const;
  void Smooth(std::size_t b, std::size_t column, const std::vector<track::SingerStep>& steps,
              SingerBlock* block) const;

  const Series& series_;
  std::size_t block_rows_;
  SingerSeriesSummary summary_;
  std::vector<Column> columns_;
};

// Robust σ of white noise from the k-th differences of the usable (finite) values; angles
// are unwrapped first. Returns NaN if fewer than k + 3 usable values.
double EstimateNoiseSigma(std::span<const double> values, bool angle, int order = kNoiseDifferenceOrder);
inline double EstimateNoiseSigma(const std::vector<double>& values, bool angle, int order = kNoiseDifferenceOrder) {
  return EstimateNoiseSigma(std::span<const double>(values), angle, order);
}
// Measurement-noise σ of a series from its k-th differences, k = min_order..max_order: for each order the
// RMS of the differences within 4 robust σ (1.4826·MAD) of their median, divided by √C(2k, k) (the variance
// gain of Δᵏ on white noise); the smallest over the orders is returned (with the order that gave it). Δᵏ
// cancels a polynomial motion of degree < k and damps a motion at frequency f by |2 sin(πfT)|ᵏ relative to
// white noise, so motion inflates the low orders and the smallest estimate is the least contaminated.
// Measured on rk-sim posetrack (docs/rk-smooth.md): mean ratio to the true σ 0.985 (head profile, 2 Hz
// motion at 20 Hz, 180 columns) and 0.991 (turntable), spread 6 %; the 4th difference alone over-estimated
// σ by up to 3× on the head profile. Values need not be uniform in time (consecutive values are
// differenced). NaN when fewer than min_order + 3 values.
double NoiseSigmaFromDifferences(const std::vector<double>& values, bool angle, int min_order = 3, int max_order = 8,
                                 int* order_used = nullptr);

// Runs filter (+ smoother) on every column. Throws UsageError for option lists of the wrong
// length or an unknown unit without --accel-sigma.
SingerSeriesResult RunSingerSeries(const Series& series, const SingerSeriesOptions& options);

// Estimate of column `column` at any time t (s): at a row, that row's; between rows k and
// k+1, the smoother (or, without smoothing, the filter prediction from row k) evaluated at
// t as an inserted no-measurement step; after the last row, predicted forward; before the
// first usable row, predicted backward (Ψ(τ)⁻¹ x, covariance Ψ⁻¹ P Ψ⁻ᵀ + Q(τ)).
void EvaluateSinger(const SingerSeriesResult& result, const Series& series, std::size_t column, double t_s,
                    Eigen::Vector3d* x, Eigen::Matrix3d* P);

// SPEC.md §2 status column of the input, if any: a numeric code (range log: 0 ok, else a
// device error) or a tool status (ok, reacquired = measurement; predicted, lost, invalid = no
// measurement); an empty field = ok. Rows that are not measurements get NaN in every value
// column. Other text is a DataError at file:line:col. Returns the number of rows masked
// that still had a value. Throws DataError if fewer than `min_samples` rows keep a value.
std::size_t MaskByStatus(const io::CsvTable& table, Series* series, std::size_t min_samples = 3);

// Per-column option values given in column units (degrees for `_deg` columns, as on the
// command line) → one value per column in internal units (radians). Empty stays empty; one
// value applies to every column. Throws UsageError (naming `option`) for another count.
std::vector<double> ColumnUnitsToInternal(const std::vector<double>& values, const Series& series,
                                          const std::string& option);

// Output column names: DerivedColumnName (series.h).

// True if an angle column is written in [0, 360): azimuth-like name (starts with "az" or
// "yaw", SPEC.md §2), or no input value < 0 and some > 180° (the aukf rule); else (−180, 180].
bool AngleColumnIs360(const std::string& column, std::span<const double> values_rad);
inline bool AngleColumnIs360(const std::string& column, const std::vector<double>& values_rad) {
  return AngleColumnIs360(column, std::span<const double>(values_rad));
}
// AngleColumnIs360 of every column of `series` (false for a column that is not an angle).
std::vector<bool> AngleColumnsIn360(const Series& series);

}  // namespace rk::filter

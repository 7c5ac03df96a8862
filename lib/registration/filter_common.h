// What the recursive bias filters (Bernoulli, known-association KF) share: the state model,
// options, the Joseph-form pair update and the per-step output.
//
// State (eq. 17): x = [Δr_a Δθ_a Δφ_a Δϑ_a Δϕ_a Δα_a Δr_b … Δα_b] (m, rad), random walk (eq. 21)
//   x_k = x_{k−1} + w_{k−1},  w ~ N(0, Q),  Q = diag(process_sigma², process_sigma²) per step.
// Prior x_0 ~ N(0, P_0), P_0 = diag(initial_sigma², initial_sigma²) (both radars alike).
// Update with one pair (z = H x + G v, radar_model.h), Joseph form:
//   S = H P Hᵀ + G R Gᵀ,  K = P Hᵀ S⁻¹,  m ← m + K ν,
//   P ← (I − K H) P (I − K H)ᵀ + K G R Gᵀ Kᵀ, then symmetrised; a P that is not positive
//   definite afterwards is repaired (eigenvalues clamped) and counted.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/json_util.h"
#include "io/options.h"
#include "io/row_status.h"
#include "io/run_summary.h"
#include "registration/input.h"
#include "registration/radar_model.h"

namespace rk::registration {

constexpr double kLog2Pi = 1.8378770664093453;  // ln(2π), in Gaussian log-densities

struct FilterOptions {
  MeasurementNoise noise;
  Linearization linearization = Linearization::kEstimate;
  // P_0 1-sigma of each bias of a radar (m, rad); the initial mean is 0 (biases unknown).
  RadarBias initial_sigma = (RadarBias() << 2000.0, 0.03, 0.03, 0.03, 0.03, 0.03).finished();
  // Q 1-sigma per step of the random walk (m, rad); > 0 keeps the filter from freezing.
  RadarBias process_sigma = (RadarBias() << 0.05, 2e-7, 2e-7, 2e-7, 2e-7, 2e-7).finished();

  // The noise options and --linearize (io/options.h). The six-value lists initial_sigma and
  // process_sigma (--p0, --q, in file units) are parsed by the app and checked by hand in Check().
  static const io::OptionTable<FilterOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const;  // the table's keys, plus initial_sigma and process_sigma_per_step (file units)
};

BiasMatrix InitialCovariance(const FilterOptions& opt);
BiasMatrix ProcessCovariance(const FilterOptions& opt);

// Counters every filter reports.
struct FilterCounters {
  std::int64_t steps = 0;
  std::int64_t steps_updated = 0;     // steps with at least one accepted pair
  std::int64_t steps_predicted = 0;   // steps without an update (status 'predicted')
  std::int64_t pairs_evaluated = 0;   // pair likelihoods computed
  std::int64_t updates = 0;           // pair updates applied (all hypotheses)
  std::int64_t innovation_not_pd = 0;  // S not positive definite: pair skipped
  std::int64_t covariance_repairs = 0; // P not positive definite after an update: eigenvalues clamped
  io::Json ToJson() const;
};

// Symmetrises P; if it is not positive definite, clamps its eigenvalues to a small positive
// floor and returns true (a repair).
bool SymmetrizeAndRepair(BiasMatrix* P);

// Joseph-form update of (m, P) with the pair (a, b): ν = g_b(m_b) − g_a(m_a); with a 2-D plot, the reduced
// pair of radar_model.h (ReducePair: ν, H, R of dimension 3 − number of 2-D plots). Returns false (nothing
// changed) if S is not positive definite. d2 = νᵀ S⁻¹ ν; log_q = ln N(ν; 0, S); dim = the dimension of ν.
bool UpdateWithPair(const PlotLinearization& a, const PlotLinearization& b, BiasVector* m, BiasMatrix* P,
                    FilterCounters* counters, double* d2 = nullptr, double* log_q = nullptr, int* dim = nullptr);

// Per radar and bias: true where the data cannot give it (docs/rk-register.md "2-D radars"), written as empty.
using BiasMask = std::array<std::array<bool, kRadarBiasDim>, 2>;
// A 2-D radar's pitch or roll bias whose final 1σ is above this fraction of its prior 1σ counts as unresolved: the
// data did not reduce its variance four-fold (a 2-D plot feels those biases only through the target's elevation in
// the radar frame and the platform's tilt, which a trial of low targets and a level platform does not provide).
inline constexpr double kUnresolvedSigmaRatio = 0.5;
// The el bias of every 2-D radar (input.two_d), always; its pitch and roll where sqrt(P) > kUnresolvedSigmaRatio ·
// prior_sigma (or P is not finite). Nothing for a radar with el_deg.
BiasMask UnobservableBiases(const RegistrationInput& input, const BiasMatrix& P, const RadarBias& prior_sigma);

// Per-step output of any method.
struct StepEstimate {
  double t_s = 0.0;
  RowStatus status = RowStatus::kPredicted;
  BiasVector x = BiasVector::Zero();
  BiasVector sigma = BiasVector::Zero();
  int pairs_used = 0;   // pairs in the reported estimate's update this step
  int components = 1;   // Gaussian components after pruning/merging (1 for the KF)
};

struct RegistrationResult {
  std::string method;  // "bernoulli", "kf", "batch"
  std::vector<StepEstimate> steps;
  BiasVector x = BiasVector::Zero();  // final estimate
  BiasMatrix P = BiasMatrix::Zero();  // its covariance
  io::Json stats = io::Json::object();  // method-specific statistics (counters, options)
  BiasMask unobservable{};  // biases left empty in the outputs (UnobservableBiases), set by each method

  // The report's body (docs/rk-register.md "Report"): radars, input, estimate, sigma, correlation,
  // stats, options, and the "summary" rk-run copies: the final estimate and its 1-sigma per radar.
  io::Json ToJson(const RegistrationInput& input) const;
  // The run's summary (io/run_summary.h): bias rows by status, the folded-pitch warning per radar's nav,
  // covariance repairs (report only), the solver's termination where `stats` has one (batch: Ceres' type,
  // a warning unless it converged), each radar's range bias with its 1σ as headline, ToJson as details.
  io::RunSummary Summary(const RegistrationInput& input) const;
};

// Biases CSV of SPEC.md §2.1: t_s + per radar R: R_range_m,R_az_deg,R_el_deg,R_yaw_deg,
// R_pitch_deg,R_roll_deg, then status; with `sigmas`, R_range_sigma_m … R_roll_sigma_deg after. The biases
// in result.unobservable are empty cells (value and sigma), in every row.
io::CsvWriter BiasesCsv(const RegistrationInput& input, const RegistrationResult& result, bool sigmas);
// Final estimate, 1-sigma and correlation for the report: {"<radar>": {"range_m": .., ...},
// "sigma": {...}, "correlation": 12x12}; the biases in `unobservable` are null (and their correlations).
io::Json EstimateJson(const RegistrationInput& input, const BiasVector& x, const BiasMatrix& P,
                      const BiasMask& unobservable = {});

}  // namespace rk::registration

// Innovation-based adaptive estimation of the noise covariances Q and R (A. H. Mohamed,
// K. P. Schwarz, "Adaptive Kalman filtering for INS/GPS", Journal of Geodesy 73, 1999), as used by
// seed 000 eqs. 17–20 (Sun & Zhang 2015; the extracted equations mix two variants, corrected per
// docs/seed-notes.md):
//   innovation     d_k = Z_k − H X_{k|k−1}
//   its covariance C_k = (1/N) Σ_{j=k−N+1..k} d_j d_jᵀ          (window of N samples), or
//                  C_k = Σ_j λ^{k−j} d_j d_jᵀ / Σ_j λ^{k−j}      (fading memory, 0 < λ < 1)
//   R̂_k = C_k − ⟨H P_{k|k−1} Hᵀ⟩,   Q̂_k = K_k C_k K_kᵀ,
// where ⟨H P_{k|k−1} Hᵀ⟩ is averaged over the same memory as C_k (so that both terms describe the same
// samples; with the current value only, R̂ swung and the loop diverged on the turntable benchmark).
// Assumptions: d is zero-mean and stationary over the memory; only rows in which every column is
// measured contribute (a partial innovation has a different dimension). R̂ and Q̂ are estimates and
// can be indefinite (R̂ is a difference; Q̂ = K C Kᵀ has rank ≤ m < n), so both are repaired to
// symmetric positive definite by eigenvalue clamping (ukf::RepairSpd) and every repair is counted.
// Measured (docs/rk-smooth.md): the R̂ loop can oscillate and run away when the motion model is poor
// (R̂ absorbs the prediction error); the clamps bound it, they do not make it good. Default: no adaptation.
#pragma once

#include <string>
#include <vector>

#include "filter/ukf.h"
#include "io/options.h"

namespace rk::filter {

enum class AdaptMode { kNone, kR, kQ, kQR };
enum class AdaptMemory { kWindow, kFading };

bool ParseAdaptMode(const std::string& s, AdaptMode* mode);
const char* AdaptModeName(AdaptMode mode);
inline bool AdaptsR(AdaptMode m) { return m == AdaptMode::kR || m == AdaptMode::kQR; }
inline bool AdaptsQ(AdaptMode m) { return m == AdaptMode::kQ || m == AdaptMode::kQR; }

struct AdaptiveNoiseOptions {
  AdaptMode mode = AdaptMode::kNone;
  AdaptMemory memory = AdaptMemory::kWindow;
  int window = 40;       // N, samples (≥ 2) for kWindow
  double fading = 0.98;  // λ in (0, 1) for kFading; effective memory 1/(1−λ) samples
  // Eigenvalue floors in the scaled spaces of ukf::RepairSpd (dimensionless): R ≥ r_floor·R₀ in
  // every direction (R₀ = initial R), Q ≥ q_floor in units of the measurement-noise scale
  // (position σ_R, rate σ_R/T, acceleration σ_R/T², T = median sample interval).
  double r_floor = 1e-2;     // σ_R ≥ 0.1 σ_R₀
  double r_ceiling = 1e2;    // σ_R ≤ 10 σ_R₀: the innovation-based R̂ absorbs model error and can run away
  double q_floor = 1e-10;
  double q_ceiling = 1e6;    // bounds Q̂ = K C Kᵀ in the same scaled space

  // --window and --fading (io/options.h); both are checked whichever memory is used (defaults valid).
  static const io::OptionTable<AdaptiveNoiseOptions>& Table();
  bool Check(std::string* why) const;
  // Samples needed before C_k is used: N (window) or ⌈1/(1−λ)⌉ (fading).
  int Warmup() const;
};

// Running innovation covariance C_k over m components (window or fading memory).
class InnovationCovariance {
 public:
  void Reset(int m, const AdaptiveNoiseOptions& options);
  // Adds an innovation d and the filter's predicted H P Hᵀ for it.
  void Add(const ukf::MeasVec& d, const ukf::MeasMat& HPH);
  bool Ready() const { return count_ >= warmup_; }
  const ukf::MeasMat& C() const { return C_; }
  const ukf::MeasMat& HPH() const { return HPH_; }  // ⟨H P_{k|k−1} Hᵀ⟩ over the same memory
  int count() const { return count_; }

 private:
  AdaptMemory memory_ = AdaptMemory::kWindow;
  int m_ = 0, window_ = 0, warmup_ = 0, count_ = 0, next_ = 0;
  double fading_ = 0.0, weight_ = 0.0;
  std::vector<ukf::MeasVec> ring_;     // window memory (allocated once in Reset)
  std::vector<ukf::MeasMat> ring_hph_;
  ukf::MeasMat S_, C_, S_hph_, HPH_;  // fading sums; current estimates
};

}  // namespace rk::filter

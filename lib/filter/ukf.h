// Generic pieces of the unscented Kalman filter (Julier, Uhlmann, Durrant-Whyte, "A new approach for
// filtering nonlinear systems", ACC 1995), as used by seed 000 (Sun & Zhang 2015, eqs. 3–16).
//
// Sigma points of a state x (n × 1) with covariance P (eq. 3, 7):
//   X_0 = x,  X_i = x + (√((n+κ) P))_i,  X_{n+i} = x − (√((n+κ) P))_i,  i = 1..n,
//   √ = lower Cholesky factor, (·)_i its i-th column.
// Weights (eq. 4, 8; the paper calls κ "m"):  W_0 = κ / (n+κ),  W_i = 1 / (2 (n+κ)).
// Moments of transformed points Y_i:  ŷ = Σ W_i Y_i,  P_y = Σ W_i (Y_i − ŷ)(Y_i − ŷ)ᵀ.
//
// Angle components (radians) are wrap-safe: their mean is taken over residuals relative to the
// reference point Y_0, ŷ = wrap(Y_0 + Σ W_i wrap(Y_i − Y_0)), and every residual Y_i − ŷ is wrapped
// to (−π, π]. For sigma points that lie within ±π of Y_0 this equals the linear weighted mean exactly,
// so a linear model gives the Kalman filter's moments to rounding (tests/filter/test_aukf_series.cc).
//
// Matrices are Eigen max-size types (storage on the stack, up to kMaxStates states and kMaxSigma
// points): no heap allocation per step.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <array>
#include <cmath>

namespace rk::filter::ukf {

inline constexpr int kMaxColumns = 12;                    // measured components (rk-smooth --columns)
inline constexpr int kMaxStates = 3 * kMaxColumns;        // [p, p', p''] per column
inline constexpr int kMaxSigma = 2 * kMaxStates + 1;      // 2n + 1 sigma points

using StateVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxStates, 1>;
using StateMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxStates, kMaxStates>;
using SigmaMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxStates, kMaxSigma>;
using SigmaWeights = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSigma, 1>;
using MeasVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxColumns, 1>;
using MeasMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxColumns, kMaxColumns>;
using GainMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxStates, kMaxColumns>;

// Which state rows are angles (radians, wrap-safe).
struct AngleRows {
  int count = 0;
  std::array<int, kMaxStates> rows{};
  void Add(int row) { rows[static_cast<std::size_t>(count++)] = row; }
};

// Weights W_0 = κ/(n+κ), W_i = 1/(2(n+κ)); requires n + κ > 0.
SigmaWeights MakeWeights(int n, double kappa);

// Sigma points of (x, P) into X (n × (2n+1)). Returns false (X untouched) when (n+κ)P has no
// Cholesky factor (P not positive definite).
bool SigmaPoints(const StateVec& x, const StateMat& P, double kappa, SigmaMat* X);

// Wrap-safe weighted mean of the columns of X.
StateVec SigmaMean(const SigmaMat& X, const SigmaWeights& w, const AngleRows& angles);

// D = X − mean (column-wise), angle rows wrapped to (−π, π].
void SigmaResiduals(const SigmaMat& X, const StateVec& mean, const AngleRows& angles, SigmaMat* D);

// Σ W_i D_i D_iᵀ (symmetric by construction; uses W_1 = … = W_2n as made by MakeWeights).
StateMat SigmaCovariance(const SigmaMat& D, const SigmaWeights& w);
// Σ W_i A_i B_iᵀ.
StateMat SigmaCrossCovariance(const SigmaMat& A, const SigmaMat& B, const SigmaWeights& w);

// Wraps the angle rows of x to (−π, π].
void WrapAngles(const AngleRows& angles, StateVec* x);

// A ← (A + Aᵀ)/2.
template <typename M>
void Symmetrise(M* A) {
  const auto n = A->rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i + 1; j < n; ++j) {
      const double v = 0.5 * ((*A)(i, j) + (*A)(j, i));
      (*A)(i, j) = v;
      (*A)(j, i) = v;
    }
  }
}

// Symmetric positive-definite repair by eigenvalue clamping in a scaled space: with S = diag(scale)
// (one standard deviation per component, so that components of different units compare),
// A_s = S⁻¹ A S⁻¹ = V Λ Vᵀ; any λ < floor is raised to floor (and any λ > ceiling lowered to it),
// A = S V Λ' Vᵀ S. Returns true when A was changed (a repair to count). A is symmetrised first; a
// non-finite A is replaced by S min(1, ceiling) S (the scale itself) and counted.
bool RepairSpd(StateMat* A, const StateVec& scale, double floor, double ceiling = HUGE_VAL);
bool RepairSpd(MeasMat* A, const MeasVec& scale, double floor, double ceiling = HUGE_VAL);

}  // namespace rk::filter::ukf

// Internal to the AUKF smoother (filter/aukf_series.h), shared by its three stages and nowhere else:
//   aukf_noise.cc     the measurement and process noise per column (moments, maximum likelihood, causal refits)
//   aukf_forward.cc   the forward filter over the rows (prediction to the lead time, update, adaptation)
//   aukf_smoother.cc  Rauch–Tung–Striebel backwards over the stored filter nodes
//   aukf_series.cc    the options, the input checks and RunAukf, which calls the three in turn.
#pragma once

#include <Eigen/Cholesky>
#include <cstddef>
#include <vector>

#include "filter/aukf_series.h"
#include "geo/angles.h"
#include "io/error.h"

namespace rk::filter::aukf_detail {

using ukf::MeasMat;
using ukf::MeasVec;
using ukf::SigmaMat;
using ukf::StateMat;
using ukf::StateVec;

constexpr double kQCoefficient = 0.55;  // ∫ B₂(u)² du of the quadratic B-spline: Δ³ of triple-integrated noise

inline double Diff(double a, double b, bool angle) { return angle ? geo::AngleDiff(a, b) : a - b; }

inline void Pack(const StateMat& P, std::vector<double>* out) {
  const Eigen::Index n = P.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i; j < n; ++j) out->push_back(P(i, j));
  }
}

inline void Unpack(const double* p, int n, StateMat* P) {
  P->resize(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      (*P)(i, j) = *p;
      (*P)(j, i) = *p;
      ++p;
    }
  }
}

// Φ(τ) applied in place to every column of X (block-wise, no 18×18 product).
inline void PropagateSigma(int m, double tau, SigmaMat* X) {
  const double h = 0.5 * tau * tau;
  for (int c = 0; c < m; ++c) {
    const int r = 3 * c;
    X->row(r) += tau * X->row(r + 1) + h * X->row(r + 2);
    X->row(r + 1) += tau * X->row(r + 2);
  }
}

// The time-update machinery shared by the forward pass and the smoother.
struct Model {
  int m = 0, n = 0;
  double kappa = 1.0;
  ukf::SigmaWeights w;
  ukf::AngleRows angles;
  std::vector<double> q;      // per column
  StateVec scale;             // per state: σ, σ/T, σ/T² (repair scale)
  std::vector<bool> is_angle; // per column
  bool block_diagonal = false;  // P block diagonal per column (no adaptation): PredictBlocks
  double p_floor = 1e-12;

  // Process noise of a sub-step of length s: the model's white-jerk Q, or Q_rate·s when adapted.
  void AddQ(double s, const StateMat* Q_rate, StateMat* P) const {
    if (Q_rate) {
      *P += s * *Q_rate;
      return;
    }
    for (int c = 0; c < m; ++c) P->block<3, 3>(3 * c, 3 * c) += WhiteJerkQ(s, q[static_cast<std::size_t>(c)]);
  }

  // Sigma points of (x, P); repairs P in place when it has no Cholesky factor.
  void Sigma(const StateVec& x, StateMat* P, SigmaMat* X, std::size_t* repairs) const {
    if (ukf::SigmaPoints(x, *P, kappa, X)) return;
    ukf::RepairSpd(P, scale, p_floor);
    ++*repairs;
    if (!ukf::SigmaPoints(x, *P, kappa, X)) {
      throw ProcessingError("covariance could not be repaired to positive definite (non-finite values?)");
    }
  }

  // (x, P) at node j → predicted (x⁻, P⁻) over s. Optionally returns the smoother's cross-covariance
  // C = Σ W (X − x)(ΦX − x⁻)ᵀ. With block_diagonal, P is block diagonal (one 3×3 block per column) and the
  // unscented transform runs per column block (PredictBlocks).
  void Predict(const StateVec& x, StateMat* P, double s, const StateMat* Q_rate, StateVec* x_pred, StateMat* P_pred,
               std::size_t* repairs, StateMat* C = nullptr) const {
    if (block_diagonal && !Q_rate && PredictBlocks(x, *P, s, x_pred, P_pred, C)) return;
    SigmaMat X;
    Sigma(x, P, &X, repairs);
    SigmaMat D0;
    if (C) ukf::SigmaResiduals(X, x, angles, &D0);
    PropagateSigma(m, s, &X);
    *x_pred = ukf::SigmaMean(X, w, angles);
    SigmaMat D;
    ukf::SigmaResiduals(X, *x_pred, angles, &D);
    *P_pred = ukf::SigmaCovariance(D, w);
    AddQ(s, Q_rate, P_pred);
    if (C) *C = ukf::SigmaCrossCovariance(D0, D, w);
  }

  // The same transform per column block: with no adaptation the columns are independent (Φ, Q and R are
  // block diagonal and H picks one state per column, so P stays block diagonal), and the unscented
  // transform of the joint state factors into one 3-state transform per column (n = 3, 7 points, weights
  // κ/(3+κ) and 1/(2(3+κ))). For this linear Φ both are exact, so the results agree to rounding (golden
  // test); the cost falls from O(n³) with 2n+1 = 37 points to 6 small blocks. Returns false (nothing
  // written) when a block has no Cholesky factor: the caller then takes the joint path, which repairs P.
  bool PredictBlocks(const StateVec& x, const StateMat& P, double s, StateVec* x_pred, StateMat* P_pred,
                     StateMat* C) const {
    const double k3 = 3.0 + kappa;
    const double w0 = kappa / k3, wi = 1.0 / (2.0 * k3);
    x_pred->resize(n);
    P_pred->setZero(n, n);
    if (C) C->setZero(n, n);
    Eigen::Matrix3d F;
    F << 1, s, 0.5 * s * s, 0, 1, s, 0, 0, 1;
    for (int c = 0; c < m; ++c) {
      const int r = 3 * c;
      const Eigen::Matrix3d Pc = P.block<3, 3>(r, r);
      const Eigen::LLT<Eigen::Matrix3d> llt(k3 * Pc);
      if (llt.info() != Eigen::Success) return false;
      const Eigen::Matrix3d L = llt.matrixL();
      const Eigen::Vector3d xc = x.segment<3>(r);
      Eigen::Matrix<double, 3, 7> X;
      X.col(0) = xc;
      for (int i = 0; i < 3; ++i) {
        X.col(1 + i) = xc + L.col(i);
        X.col(4 + i) = xc - L.col(i);
      }
      const Eigen::Matrix<double, 3, 7> Y = F * X;
      Eigen::Vector3d mean = w0 * Y.col(0) + wi * (Y.rightCols<6>().rowwise().sum());
      const bool angle = is_angle[static_cast<std::size_t>(c)];
      if (angle) {  // wrap-safe mean of the angle row, as ukf::SigmaMean
        double acc = 0.0;
        for (int i = 0; i < 7; ++i) acc += (i == 0 ? w0 : wi) * geo::WrapPi(Y(0, i) - Y(0, 0));
        mean(0) = geo::WrapPi(Y(0, 0) + acc);
      }
      Eigen::Matrix<double, 3, 7> D = Y.colwise() - mean;
      if (angle) {
        for (int i = 0; i < 7; ++i) D(0, i) = geo::WrapPi(D(0, i));
      }
      Eigen::Matrix3d Pp = w0 * D.col(0) * D.col(0).transpose() + wi * (D.rightCols<6>() * D.rightCols<6>().transpose());
      Pp += WhiteJerkQ(s, q[static_cast<std::size_t>(c)]);
      P_pred->block<3, 3>(r, r) = 0.5 * (Pp + Pp.transpose());
      x_pred->segment<3>(r) = mean;
      if (C) {
        Eigen::Matrix<double, 3, 7> D0 = X.colwise() - xc;  // X_0 = x: no wrap needed (residuals of ±L)
        C->block<3, 3>(r, r) = w0 * D0.col(0) * D.col(0).transpose() +
                               wi * (D0.rightCols<6>() * D.rightCols<6>().transpose());
      }
    }
    return true;
  }
};

// σ and q of every column not given, fitted on the rows [0, rows); given values are copied. `known[c]` is
// set when column c has its noise (given, or estimated now). Columns that cannot be estimated yet (no 4
// consecutive values) keep their previous entries.
struct NoiseFitOut {
  std::vector<double> sigma, q;
  std::vector<bool> known;
  std::vector<NoiseMlFit> ml;
  std::vector<bool> ml_used;
  double interval_s = 0.0;
};

constexpr int kCausalBurnIn = 3;  // innovations left out by a causal ML fit (its start is diffuse in 3 states)

// The noise in use per column (provisional until its first fit in causal mode) and its interval.
struct NoiseInUse {
  std::vector<double> sigma, q;
  double T = 0.0;
};

// Per-interval noise for the smoother: adapted Q, or the q of a causal refit schedule.
struct IntervalNoise {
  bool store_q = false;               // adapted Q per interval
  bool store_model_q = false;         // the model's q per interval
  std::vector<double> q_store;        // packed Q_rate per sample interval
  std::vector<char> q_store_used;     // 1 if the interval used an adapted Q
  std::vector<double> model_q_store;  // m per sample interval
};

// Median sample interval of the rows [0, rows) (rows ≥ 2).
double MedianInterval(const std::vector<double>& t, std::size_t rows);

// σ and q per column fitted on the rows [0, rows) (see NoiseFitOut); causal fits take q's upper 95 % bound.
void FitNoise(const Series& series, std::size_t rows, const AukfOptions& options, bool est_sigma, bool est_q,
              bool causal, NoiseFitOut* out);

// Noise per column: given, or fitted (on the whole file, or on the rows up to each refit). Fills *noise
// with the whole-file fit (not causal); throws when a column cannot be estimated even on the whole file.
NoiseInUse InitialNoise(const Series& series, const AukfOptions& options, const AukfResult& res, bool causal,
                        NoiseFitOut* noise);

// The forward pass over every row with `model` and the noise in `use` (the causal schedule refits it): the
// filtered nodes, counters, noise and final R and Q into *res; what the smoother needs per interval into
// *intervals; covariances kept when keep_cov.
void RunForward(const Series& series, const AukfOptions& options, bool causal, bool keep_cov, Model* model,
                NoiseFitOut* noise, NoiseInUse* use, IntervalNoise* intervals, AukfResult* res);

// Rauch–Tung–Striebel over the stored filter nodes (cov_filter kept), backwards from the last node.
void RtsSmooth(const AukfOptions& options, const IntervalNoise& intervals, Model* model, AukfResult* res);

}  // namespace rk::filter::aukf_detail

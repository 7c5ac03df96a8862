#include "filter/ukf.h"

// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's SelfAdjointEigenSolver for max-size
// (fixed-capacity dynamic) matrices; the solver writes every element it reads.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <Eigen/Eigenvalues>

#include <algorithm>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::filter::ukf {

namespace {
// geo::WrapPi with a fast path for values already in (−π, π] (std::remainder dominated the step time).
inline double Wrap(double a) { return (a > -geo::kPi && a <= geo::kPi) ? a : geo::WrapPi(a); }
}  // namespace

SigmaWeights MakeWeights(int n, double kappa) {
  RK_CHECK(n > 0 && n <= kMaxStates && n + kappa > 0, "bad sigma-point parameters");
  SigmaWeights w(2 * n + 1);
  w.setConstant(1.0 / (2.0 * (n + kappa)));
  w(0) = kappa / (n + kappa);
  return w;
}

bool SigmaPoints(const StateVec& x, const StateMat& P, double kappa, SigmaMat* X) {
  const Eigen::Index n = x.size();
  StateMat scaled = (static_cast<double>(n) + kappa) * P;
  Eigen::LLT<Eigen::Ref<StateMat>> llt(scaled);  // in place: factor stored in `scaled`
  if (llt.info() != Eigen::Success) return false;
  X->resize(n, 2 * n + 1);
  X->col(0) = x;
  for (Eigen::Index i = 0; i < n; ++i) {
    // Column i of the lower factor L (zeros above the diagonal).
    for (Eigen::Index r = 0; r < n; ++r) {
      const double l = r >= i ? scaled(r, i) : 0.0;
      (*X)(r, 1 + i) = x(r) + l;
      (*X)(r, 1 + n + i) = x(r) - l;
    }
  }
  return true;
}

StateVec SigmaMean(const SigmaMat& X, const SigmaWeights& w, const AngleRows& angles) {
  StateVec m = X * w;
  for (int k = 0; k < angles.count; ++k) {
    const int r = angles.rows[static_cast<std::size_t>(k)];
    const double ref = X(r, 0);
    double s = 0.0;
    for (Eigen::Index i = 0; i < X.cols(); ++i) s += w(i) * Wrap(X(r, i) - ref);
    m(r) = Wrap(ref + s);
  }
  return m;
}

void SigmaResiduals(const SigmaMat& X, const StateVec& mean, const AngleRows& angles, SigmaMat* D) {
  *D = X.colwise() - mean;
  for (int k = 0; k < angles.count; ++k) {
    const int r = angles.rows[static_cast<std::size_t>(k)];
    for (Eigen::Index i = 0; i < D->cols(); ++i) (*D)(r, i) = Wrap((*D)(r, i));
  }
}

StateMat SigmaCovariance(const SigmaMat& D, const SigmaWeights& w) {
  // W_1 = … = W_2n (eq. 4): one symmetric rank-2n update of the lower triangle plus W_0 D_0 D_0ᵀ.
  const Eigen::Index n = D.rows(), L = D.cols();
  StateMat P = StateMat::Zero(n, n);
  P.selfadjointView<Eigen::Lower>().rankUpdate(D.rightCols(L - 1), w(1));
  P.selfadjointView<Eigen::Lower>().rankUpdate(D.col(0), w(0));
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = j + 1; i < n; ++i) P(j, i) = P(i, j);
  }
  return P;
}

StateMat SigmaCrossCovariance(const SigmaMat& A, const SigmaMat& B, const SigmaWeights& w) {
  SigmaMat AW = A * w.asDiagonal();
  StateMat C(A.rows(), B.rows());
  C.noalias() = AW * B.transpose();
  return C;
}

void WrapAngles(const AngleRows& angles, StateVec* x) {
  for (int k = 0; k < angles.count; ++k) {
    const int r = angles.rows[static_cast<std::size_t>(k)];
    (*x)(r) = Wrap((*x)(r));
  }
}

namespace {

template <typename Mat, typename Vec>
bool RepairSpdImpl(Mat* A, const Vec& scale, double floor, double ceiling) {
  Symmetrise(A);
  if (!A->allFinite()) {
    A->setZero();
    for (Eigen::Index i = 0; i < A->rows(); ++i) (*A)(i, i) = std::min(1.0, ceiling) * scale(i) * scale(i);
    return true;
  }
  const Eigen::Index n = A->rows();
  Mat As(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) As(i, j) = (*A)(i, j) / (scale(i) * scale(j));
  }
  Eigen::SelfAdjointEigenSolver<Mat> es(As);
  if (es.info() != Eigen::Success) {
    // Not expected for a finite symmetric matrix; fall back to the floor itself.
    As.setIdentity();
    As *= floor;
  } else {
    const auto& lambda = es.eigenvalues();
    if (lambda.minCoeff() >= floor && lambda.maxCoeff() <= ceiling) return false;
    Vec clamped = lambda.cwiseMax(floor).cwiseMin(ceiling);
    As.noalias() = es.eigenvectors() * clamped.asDiagonal() * es.eigenvectors().transpose();
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) (*A)(i, j) = As(i, j) * scale(i) * scale(j);
  }
  Symmetrise(A);
  return true;
}

}  // namespace

bool RepairSpd(StateMat* A, const StateVec& scale, double floor, double ceiling) {
  return RepairSpdImpl(A, scale, floor, ceiling);
}
bool RepairSpd(MeasMat* A, const MeasVec& scale, double floor, double ceiling) {
  return RepairSpdImpl(A, scale, floor, ceiling);
}

}  // namespace rk::filter::ukf

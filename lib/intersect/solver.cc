// Per-row intersection; the model and its equations are in solver.h.
#include "intersect/solver.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <bit>
#include <cmath>

#include "geo/angles.h"

namespace rk::intersect {
namespace {

// Unit direction of an azimuth / elevation in the station's ENU frame.
Eigen::Vector3d Direction(double az, double el) {
  return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

bool Has(std::uint64_t mask, int i) { return (mask >> i) & 1U; }

// Linear closest point: Σ (I − u uᵀ) p = Σ (I − u uᵀ) a, plus p = a + ρ u for a range.
bool InitialGuess(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, std::uint64_t mask,
                  Eigen::Vector3d* p) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    if (!Has(mask, i)) continue;
    const StationFrame& f = frames[obs[i].station];
    const Eigen::Vector3d u = f.M.transpose() * Direction(obs[i].az_rad, obs[i].el_rad);
    const Eigen::Matrix3d Q = Eigen::Matrix3d::Identity() - u * u.transpose();
    A += Q;
    b += Q * f.a;
    if (obs[i].has_range) {
      A += Eigen::Matrix3d::Identity();
      b += f.a + obs[i].range_m * u;
    }
  }
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return false;
  *p = ldlt.solve(b);
  return p->allFinite();
}

// Normal equations JᵀJ, Jᵀz and Σz² of the masked observations at p.
void Accumulate(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, std::uint64_t mask,
                const Eigen::Vector3d& p, Eigen::Matrix3d* A, Eigen::Vector3d* g, double* chi2, int* m) {
  A->setZero();
  g->setZero();
  *chi2 = 0.0;
  *m = 0;
  for (int i = 0; i < n; ++i) {
    if (!Has(mask, i)) continue;
    const Prediction pr = Predict(frames[obs[i].station], p);
    const Eigen::Vector3d z = NormalisedResiduals(obs[i], pr);
    const int rows = obs[i].has_range ? 3 : 2;
    const Eigen::Matrix3d Jn = NormalisedJacobian(obs[i], pr);
    for (int r = 0; r < rows; ++r) {
      const Eigen::RowVector3d h = Jn.row(r);
      *A += h.transpose() * h;
      *g += h.transpose() * z(r);
      *chi2 += z(r) * z(r);
      ++*m;
    }
  }
}

// Largest range from a used station to p (m): the scale of the step tolerance.
double Scale(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, std::uint64_t mask,
             const Eigen::Vector3d& p) {
  double s = 1.0;
  for (int i = 0; i < n; ++i) {
    if (Has(mask, i)) s = std::max(s, 1.0 + (p - frames[obs[i].station].a).norm());
  }
  return s;
}

bool InFront(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, std::uint64_t mask,
             const Eigen::Vector3d& p) {
  for (int i = 0; i < n; ++i) {
    if (!Has(mask, i)) continue;
    const Eigen::Vector3d d = Predict(frames[obs[i].station], p).d;
    if (d.dot(Direction(obs[i].az_rad, obs[i].el_rad)) <= 0.0) return false;
  }
  return true;
}

// Standardised leave-one-out residual of observation i: the largest |z_j| / sqrt(1 + h_j P₋ᵢ h_jᵀ), or −1
// when the others cannot be solved.
double LeaveOneOut(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, std::uint64_t mask,
                   int i) {
  const std::uint64_t others = mask & ~(std::uint64_t{1} << i);
  if (!Solvable(obs, n, others)) return -1.0;
  const Solution s = SolveMasked(frames, obs, n, others);
  if (s.status != SolveStatus::kOk) return -1.0;
  const Prediction pr = Predict(frames[obs[i].station], s.p);
  const Eigen::Vector3d z = NormalisedResiduals(obs[i], pr);
  const Eigen::Matrix3d Jn = NormalisedJacobian(obs[i], pr);
  double worst = 0.0;
  for (int r = 0; r < (obs[i].has_range ? 3 : 2); ++r) {
    const Eigen::RowVector3d h = Jn.row(r);
    worst = std::max(worst, std::abs(z(r)) / std::sqrt(1.0 + h * s.P * h.transpose()));
  }
  return worst;
}

// Largest |z| of the masked observations at p.
double LargestResidual(const std::vector<StationFrame>& frames, const LineObservation* obs, int n,
                       std::uint64_t mask, const Eigen::Vector3d& p) {
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    if (!Has(mask, i)) continue;
    const Eigen::Vector3d z = NormalisedResiduals(obs[i], Predict(frames[obs[i].station], p));
    worst = std::max({worst, std::abs(z(0)), std::abs(z(1)), obs[i].has_range ? std::abs(z(2)) : 0.0});
  }
  return worst;
}

// Residual RMS (arcsec) and geometry figures of the final solution.
void Figures(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, RowResult* r) {
  const Eigen::Vector3d& p = r->solution.p;
  double sum2 = 0.0, sig2 = 0.0, rho2 = 0.0, best_sin = 0.0;
  int lines = 0;
  for (int i = 0; i < n; ++i) {
    if (!Has(r->used, i)) continue;
    const Prediction pr = Predict(frames[obs[i].station], p);
    const double ce = std::cos(obs[i].el_rad);
    const double daz = geo::WrapPi(obs[i].az_rad - pr.az) * ce, del = obs[i].el_rad - pr.el;
    sum2 += daz * daz + del * del;
    sig2 += 0.5 * (std::pow(obs[i].sigma_az_rad * ce, 2) + obs[i].sigma_el_rad * obs[i].sigma_el_rad);
    rho2 += pr.range * pr.range;
    ++lines;
    const Eigen::Vector3d ui = (p - frames[obs[i].station].a).normalized();
    for (int j = i + 1; j < n; ++j) {
      if (!Has(r->used, j)) continue;
      const Eigen::Vector3d uj = (p - frames[obs[j].station].a).normalized();
      best_sin = std::max(best_sin, ui.cross(uj).norm());
    }
  }
  if (lines == 0) return;
  r->rms_residual_arcsec = std::sqrt(sum2 / (2.0 * lines)) * geo::kArcsecPerRad;
  r->intersection_angle_deg = geo::RadToDeg(std::asin(std::min(1.0, best_sin)));
  r->gdop = std::sqrt(r->solution.P.trace()) / (std::sqrt(sig2 / lines) * std::sqrt(rho2 / lines));
}

}  // namespace

Prediction Predict(const StationFrame& f, const Eigen::Vector3d& p) {
  Prediction pr;
  pr.d = f.c + f.M * p;
  const double e = pr.d(0), nn = pr.d(1), u = pr.d(2);
  const double h2 = e * e + nn * nn, h = std::sqrt(h2), r2 = h2 + u * u;
  pr.az = geo::WrapTwoPi(std::atan2(e, nn));
  pr.el = std::atan2(u, h);
  pr.range = std::sqrt(r2);
  Eigen::Matrix3d Jd;
  Jd << nn / h2, -e / h2, 0.0,                       // ∂az/∂d
      -e * u / (h * r2), -nn * u / (h * r2), h / r2,  // ∂el/∂d
      e / pr.range, nn / pr.range, u / pr.range;      // ∂ρ/∂d
  pr.J = Jd * f.M;
  return pr;
}

namespace {
// ρ and sqrt(1 − ρ²) of an observation, ρ capped at ±kMaxCorrelation.
void Correlation(const LineObservation& o, double* rho, double* s) {
  *rho = std::clamp(o.corr_az_el, -kMaxCorrelation, kMaxCorrelation);
  *s = std::sqrt(1.0 - *rho * *rho);
}
}  // namespace

Eigen::Vector3d NormalisedResiduals(const LineObservation& o, const Prediction& pr) {
  double rho = 0.0, s = 1.0;
  Correlation(o, &rho, &s);
  const double z_az = geo::WrapPi(o.az_rad - pr.az) / o.sigma_az_rad;
  return {z_az, ((o.el_rad - pr.el) / o.sigma_el_rad - rho * z_az) / s,
          o.has_range ? (o.range_m - pr.range) / o.sigma_range_m : 0.0};
}

Eigen::Matrix3d NormalisedJacobian(const LineObservation& o, const Prediction& pr) {
  double rho = 0.0, s = 1.0;
  Correlation(o, &rho, &s);
  Eigen::Matrix3d Jn;
  Jn.row(0) = pr.J.row(0) / o.sigma_az_rad;
  Jn.row(1) = (pr.J.row(1) / o.sigma_el_rad - rho * Jn.row(0)) / s;
  Jn.row(2) = o.has_range ? Eigen::RowVector3d(pr.J.row(2) / o.sigma_range_m) : Eigen::RowVector3d::Zero();
  return Jn;
}

bool Solvable(const LineObservation* obs, int n, std::uint64_t mask) {
  int lines = 0, ranges = 0;
  for (int i = 0; i < n; ++i) {
    if (!Has(mask, i)) continue;
    ++lines;
    ranges += obs[i].has_range ? 1 : 0;
  }
  return lines >= 2 || (lines == 1 && ranges == 1);
}

Solution SolveMasked(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, std::uint64_t mask) {
  Solution s;
  if (!Solvable(obs, n, mask)) return s;
  if (!InitialGuess(frames, obs, n, mask, &s.p)) {
    s.status = SolveStatus::kSingular;
    return s;
  }
  Eigen::Matrix3d A;
  Eigen::Vector3d g;
  s.status = SolveStatus::kNotConverged;
  for (s.iterations = 1; s.iterations <= kMaxIterations; ++s.iterations) {
    Accumulate(frames, obs, n, mask, s.p, &A, &g, &s.chi2, &s.residuals);
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) {
      s.status = SolveStatus::kSingular;
      return s;
    }
    const Eigen::Vector3d step = ldlt.solve(g);
    if (!step.allFinite()) {
      s.status = SolveStatus::kSingular;
      return s;
    }
    s.p += step;
    if (step.norm() <= kStepTolerance * Scale(frames, obs, n, mask, s.p)) {
      s.status = SolveStatus::kOk;
      break;
    }
  }
  if (s.status != SolveStatus::kOk) return s;
  Accumulate(frames, obs, n, mask, s.p, &A, &g, &s.chi2, &s.residuals);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A, Eigen::EigenvaluesOnly);
  if (!(eig.eigenvalues()(0) > kMinConditionRatio * eig.eigenvalues()(2))) {
    s.status = SolveStatus::kSingular;
    return s;
  }
  s.P = A.inverse();
  s.P = 0.5 * (s.P + s.P.transpose());
  if (!InFront(frames, obs, n, mask, s.p)) s.status = SolveStatus::kBehind;
  return s;
}

RowResult SolveRow(const std::vector<StationFrame>& frames, const LineObservation* obs, int n,
                   const SolverOptions& options) {
  RowResult r;
  r.used = n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
  r.solution = SolveMasked(frames, obs, n, r.used);
  while (r.solution.status == SolveStatus::kOk && std::popcount(r.used) >= 3 &&
         LargestResidual(frames, obs, n, r.used, r.solution.p) > options.reject_sigma) {
    int worst_i = -1;
    double worst = options.reject_sigma;
    for (int i = 0; i < n; ++i) {
      if (!Has(r.used, i)) continue;
      const double z = LeaveOneOut(frames, obs, n, r.used, i);
      if (z > worst) worst = z, worst_i = i;
    }
    if (worst_i < 0) break;
    const std::uint64_t bit = std::uint64_t{1} << worst_i;
    r.used &= ~bit;
    r.rejected |= bit;
    r.solution = SolveMasked(frames, obs, n, r.used);
  }
  if (r.solution.status == SolveStatus::kOk) Figures(frames, obs, n, &r);
  return r;
}

}  // namespace rk::intersect

// Isosceles P3P solvers of seed 004; method and equations in cylinder_solve.h.
#include "attitude/cylinder_solve.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>

#include "attitude/polynomial.h"
#include "geo/angles.h"

namespace rk::attitude {

bool ParseCylinderMethod(const std::string& name, CylinderMethod* method) {
  if (name == "search") {
    *method = CylinderMethod::kSearch;
    return true;
  }
  if (name == "p3p") {
    *method = CylinderMethod::kP3P;
    return true;
  }
  return false;
}

std::string CylinderMethodName(CylinderMethod method) {
  return method == CylinderMethod::kSearch ? "search" : "p3p";
}

const io::OptionTable<CylinderSolveOptions>& CylinderSolveOptions::Table() {
  static const io::OptionTable<CylinderSolveOptions> table = io::OptionTable<CylinderSolveOptions>().Choice(
      "--method", &CylinderSolveOptions::method, {CylinderMethod::kP3P, CylinderMethod::kSearch}, CylinderMethodName,
      "Solver: p3p (closed form, Ferrari quartic) or search (the paper's R1 search)");
  return table;
}

bool CylinderSolveOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (!(max_edge_tilt_deg > 0.0 && max_edge_tilt_deg <= 90.0)) {
    *why = "maximum edge tilt must be in (0, 90] degrees";
    return false;
  }
  if (!(max_miss_rad >= 0.0) || !std::isfinite(max_miss_rad)) {
    *why = "maximum miss must be a finite angle >= 0";
    return false;
  }
  if (search_steps_per_slant < 4 || search_steps_per_slant > 4096) {
    *why = "search steps per slant length must be in [4, 4096]";
    return false;
  }
  if (search_max_samples < 100 || search_max_samples > 10000000) {
    *why = "search samples per branch must be in [100, 1e7]";
    return false;
  }
  return true;
}

namespace {

constexpr std::array<std::array<int, 2>, 4> kBranches = {{{+1, +1}, {+1, -1}, {-1, +1}, {-1, -1}}};

struct Context {
  const CylinderRays& rays;
  const RayAngles& a;
  const target::CylinderShape& t;
  const CylinderSolveOptions& opt;
  CylinderSolveResult* out;
  std::vector<CylinderSolution> exact, near;
};

BranchPoint Eval(Context& c, int s2, int s3, double R1) {
  ++c.out->function_evaluations;
  return EvaluateBranch(c.a, c.t, s2, s3, R1);
}

bool Negative(double f) { return f < 0.0; }

// Bisection of a sign change of f in [lo, hi] to machine precision (until the midpoint equals an end).
BranchPoint Bisect(Context& c, int s2, int s3, BranchPoint lo, BranchPoint hi) {
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo.R1 + hi.R1);
    if (!(mid > lo.R1 && mid < hi.R1)) break;
    const BranchPoint m = Eval(c, s2, s3, mid);
    if (!m.valid) break;
    if (m.f == 0.0) return m;
    if (Negative(m.f) == Negative(lo.f)) {
      lo = m;
    } else {
      hi = m;
    }
  }
  return std::abs(lo.f) <= std::abs(hi.f) ? lo : hi;
}

// Golden-section minimum of sign·f on [lo, hi] (invalid points count as +inf): with sign = the sign of f
// around a dip, this is the bottom of the dip — of the opposite sign when a pair of roots hides in it (a
// minimum of |f| could instead stop at one of the roots from either side).
BranchPoint GoldenDip(Context& c, int s2, int s3, double lo, double hi, double sign) {
  constexpr double kInvPhi = 0.6180339887498949;
  auto g = [sign](const BranchPoint& p) { return p.valid ? sign * p.f : std::numeric_limits<double>::infinity(); };
  double x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
  BranchPoint p1 = Eval(c, s2, s3, x1), p2 = Eval(c, s2, s3, x2);
  for (int it = 0; it < 90 && hi - lo > 1e-15 * std::abs(hi); ++it) {
    if (g(p1) <= g(p2)) {
      hi = x2;
      x2 = x1;
      p2 = p1;
      x1 = hi - kInvPhi * (hi - lo);
      p1 = Eval(c, s2, s3, x1);
    } else {
      lo = x1;
      x1 = x2;
      p1 = p2;
      x2 = lo + kInvPhi * (hi - lo);
      p2 = Eval(c, s2, s3, x2);
    }
  }
  return g(p1) <= g(p2) ? p1 : p2;
}

void AddExact(Context& c, const BranchPoint& p) {
  const Eigen::Vector3d R = PolishRanges(c.a, c.t, Eigen::Vector3d(p.R1, p.R2, p.R3));
  CylinderSolution s = SolutionFromRanges(c.rays, c.a, c.t, R);
  s.exact = true;
  c.exact.push_back(s);
}

void AddNearMiss(Context& c, const BranchPoint& p) {
  if (!(c.opt.max_miss_rad > 0.0) || !p.valid) return;
  CylinderSolution s = SolutionFromRanges(c.rays, c.a, c.t, Eigen::Vector3d(p.R1, p.R2, p.R3));
  s.exact = false;
  const double r_tail = 0.5 * (p.R2 + p.R3);
  if (s.miss_m / r_tail <= c.opt.max_miss_rad) c.near.push_back(s);
}

// A grid minimum of |f| at `mid` between `lo` and `hi` (same sign throughout): a hidden root pair or a near miss.
void ExamineMinimum(Context& c, int s2, int s3, const BranchPoint& lo, const BranchPoint& mid, const BranchPoint& hi) {
  const BranchPoint m = GoldenDip(c, s2, s3, lo.R1, hi.R1, Negative(mid.f) ? -1.0 : 1.0);
  if (!m.valid) return;
  if (m.f == 0.0) {
    AddExact(c, m);
  } else if (Negative(m.f) != Negative(mid.f)) {
    AddExact(c, Bisect(c, s2, s3, lo, m));
    AddExact(c, Bisect(c, s2, s3, m, hi));
  } else {
    AddNearMiss(c, m);
  }
}

void Finish(Context& c) {
  auto same = [](const CylinderSolution& x, const CylinderSolution& y, double rel) {
    return (x.range_m - y.range_m).cwiseAbs().maxCoeff() <= rel * x.range_m.maxCoeff();
  };
  std::vector<CylinderSolution>& out = c.out->solutions;
  auto admit = [&](const std::vector<CylinderSolution>& candidates, double rel) {
    for (const CylinderSolution& s : candidates) {
      if (!(s.range_m.minCoeff() > 0.0) || !s.axis_enu.allFinite()) continue;
      bool dup = false;
      for (const CylinderSolution& o : out) dup = dup || same(s, o, rel);
      if (dup) continue;
      if (s.edge_tilt_rad > geo::DegToRad(c.opt.max_edge_tilt_deg)) {
        ++c.out->rejected_tilted;
        continue;
      }
      out.push_back(s);
    }
  };
  admit(c.exact, 1e-9);
  // A near miss stands for a root pair that noise has removed: it is only offered when no exact
  // admissible solution exists (elsewhere it would be a mere dip of f, not a solution).
  if (out.empty()) admit(c.near, 1e-6);
  std::sort(out.begin(), out.end(),
            [](const CylinderSolution& x, const CylinderSolution& y) { return x.range_m(0) < y.range_m(0); });
}

}  // namespace

CylinderSolveResult SolveCylinderSearch(const CylinderRays& rays, const target::CylinderShape& target,
                                        const CylinderSolveOptions& opt) {
  CylinderSolveResult result;
  const RayAngles a = AnglesOf(rays);
  Context c{rays, a, target, opt, &result, {}, {}};
  const double L = target.SlantM(), d = target.diameter_m;
  const double gap23 = std::sqrt(2.0 * a.k23);  // |u2 − u3|
  if (!(gap23 > 0.0)) return result;            // tail rays coincide: degenerate
  const double r_edge = d / gap23;
  const double r1_max = MaxNoseRange(a, target);
  // 10 % margin on the tilt: |R2 − R3|/d and the geometric tilt differ by the (tiny) angle between the rays.
  const double tilt = std::min(1.1 * geo::DegToRad(opt.max_edge_tilt_deg), M_PI / 2);
  const double lo = std::max(r_edge * std::cos(tilt) - d - L, 1e-9 * r_edge);
  const double hi = std::min(r_edge + d + L, r1_max);
  if (!(hi > lo)) return result;
  const double step = L / opt.search_steps_per_slant;
  const long n = std::clamp(static_cast<long>(std::ceil((hi - lo) / step)), 2L, static_cast<long>(opt.search_max_samples));
  // Where the band ends at the joint of the branches (R1 = L'/max(s12, s13), the square roots vanish) the
  // roots crowd towards it like the square root does (a pair within 1e-3 m of it at a side-on view): the last
  // interval is replaced by points closing in geometrically, R1max − step·2^−k, k = 1 … 45.
  const bool joint = hi == r1_max;
  constexpr int kJointPoints = 45;
  const long total = joint ? n - 1 + kJointPoints + 1 : n;
  auto grid = [&](long j) {
    if (joint && j >= n - 1) {
      const long k = j - (n - 1);  // 0 … kJointPoints
      if (k == kJointPoints) return hi;
      const double h = (hi - lo) / static_cast<double>(n);
      return hi - h * std::ldexp(1.0, -static_cast<int>(k));
    }
    return j == n ? hi : lo + (hi - lo) * static_cast<double>(j) / static_cast<double>(n);
  };
  for (const auto& br : kBranches) {
    const int s2 = br[0], s3 = br[1];
    BranchPoint p2, p1;  // previous two grid points
    for (long j = 0; j <= total; ++j) {
      const double R1 = grid(j);
      const BranchPoint p = Eval(c, s2, s3, R1);
      if (p1.valid && p.valid) {
        if (p.f == 0.0) {
          AddExact(c, p);
        } else if (Negative(p1.f) != Negative(p.f) && p1.f != 0.0) {
          AddExact(c, Bisect(c, s2, s3, p1, p));
        } else if (p2.valid && Negative(p2.f) == Negative(p1.f) && std::abs(p1.f) < std::abs(p2.f) &&
                   std::abs(p1.f) <= std::abs(p.f)) {
          ExamineMinimum(c, s2, s3, p2, p1, p);
        }
      }
      p2 = p1;
      p1 = p;
    }
    // The joint itself can be the bottom of a dip (the branch continues on its partner beyond it).
    if (joint && p1.valid && p2.valid && p1.f != 0.0 && Negative(p1.f) == Negative(p2.f) &&
        std::abs(p1.f) < std::abs(p2.f)) {
      ExamineMinimum(c, s2, s3, p2, p1, p1);
    }
  }
  Finish(c);
  return result;
}

namespace {

// Polynomials of degree ≤ 4 as coefficient arrays (index = power).
using Poly = std::array<double, 5>;
Poly Mul(const Poly& p, const Poly& q) {
  Poly r{};
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; i + j <= 4; ++j) r[static_cast<std::size_t>(i + j)] += p[static_cast<std::size_t>(i)] * q[static_cast<std::size_t>(j)];
  return r;
}
Poly Sub(const Poly& p, const Poly& q) {
  Poly r{};
  for (std::size_t i = 0; i < 5; ++i) r[i] = p[i] - q[i];
  return r;
}
double Horner(const Poly& p, double x) {
  double v = 0.0;
  for (int i = 4; i >= 0; --i) v = v * x + p[static_cast<std::size_t>(i)];
  return v;
}

}  // namespace

CylinderSolveResult SolveCylinderP3P(const CylinderRays& rays, const target::CylinderShape& target,
                                     const CylinderSolveOptions& opt) {
  CylinderSolveResult result;
  const RayAngles a = AnglesOf(rays);
  Context c{rays, a, target, opt, &result, {}, {}};
  const double L = target.SlantM(), d = target.diameter_m;
  const double alpha = std::sqrt(2.0 * std::max(a.k12, a.k13));
  if (!(alpha > 0.0) || !(a.k23 > 0.0)) return result;  // coincident rays: degenerate
  const double kappa = (d * d) / (L * L);
  const double a2 = alpha * alpha;
  // Q1, Q2 monic in Y = η/α with coefficients polynomial in X = ξ/α (see header), divided by α and α².
  const Poly b1{2.0 * a.k13 / alpha, 0, 0, 0, 0};
  const Poly c1{-2.0 * (a.k12 - a.k13) / a2, -2.0 * a.k12 / alpha, -1.0, 0, 0};
  const double g = a.k23 - kappa * a.k12;
  const Poly b2{2.0 * a.k23 / alpha, 2.0 * a.k23 - 2.0, 0, 0, 0};
  const Poly c2{2.0 * g / a2, 2.0 * g / alpha, 1.0 - kappa, 0, 0};
  const Poly dc = Sub(c1, c2);
  const Poly db = Sub(b1, b2);
  const Poly res = Sub(Mul(dc, dc), Mul(db, Sub(Mul(b2, c1), Mul(b1, c2))));
  std::array<std::complex<double>, 4> roots;
  const int nroots = SolveQuartic(res, &roots);

  // (ξ, η) → ranges; returns false when x or y is not positive.
  auto ranges = [&](double X, double Y, Eigen::Vector3d* R) {
    const double xi = alpha * X, eta = alpha * Y;
    const double x = 1.0 + xi, y = 1.0 + eta;
    const double q = xi * xi + 2.0 * a.k12 * x;
    if (!(x > 0.0) || !(y > 0.0) || !(q > 0.0)) return false;
    const double R1 = L / std::sqrt(q);
    *R = Eigen::Vector3d(R1, x * R1, y * R1);
    return true;
  };
  // Y for a root X: from Q1 − Q2 where well conditioned, else the root of Q1 that best satisfies Q2.
  auto solve_y = [&](double X) {
    const double B1 = Horner(b1, X), C1 = Horner(c1, X), B2 = Horner(b2, X), C2 = Horner(c2, X);
    const double den = B1 - B2;
    const double scale = std::max({std::abs(B1), std::abs(B2), 1e-300});
    if (std::abs(den) > 1e-8 * scale) return (C2 - C1) / den;
    std::complex<double> y0, y1;
    const std::complex<double> disc = std::sqrt(std::complex<double>(B1 * B1 - 4.0 * C1));
    y0 = 0.5 * (-B1 + disc);
    y1 = 0.5 * (-B1 - disc);
    auto q2 = [&](double Y) { return std::abs(Y * Y + B2 * Y + C2); };
    return q2(y0.real()) <= q2(y1.real()) ? y0.real() : y1.real();
  };

  for (int i = 0; i < nroots; ++i) {
    const std::complex<double> z = roots[static_cast<std::size_t>(i)];
    const bool real = std::abs(z.imag()) <= 1e-9 * std::max(1.0, std::abs(z.real()));
    if (!real && (z.imag() < 0.0 || !(opt.max_miss_rad > 0.0))) continue;  // one seed per complex pair
    const double X = z.real();
    Eigen::Vector3d R;
    if (!ranges(X, solve_y(X), &R)) continue;
    if (real) {
      const Eigen::Vector3d Rp = PolishRanges(a, target, R);
      CylinderSolution s = SolutionFromRanges(rays, a, target, Rp);
      if (s.miss_m <= 1e-9 * L) {
        c.exact.push_back(s);
        continue;
      }
      if (!(opt.max_miss_rad > 0.0)) continue;
    }
    // Complex pair (or a real root that does not polish): closest approach along its branch.
    const int s2 = R(1) - R(0) * a.c12 >= 0.0 ? +1 : -1;
    const int s3 = R(2) - R(0) * a.c13 >= 0.0 ? +1 : -1;
    const double lo = std::max(R(0) - 0.5 * L, 1e-9 * R(0));
    const double hi = std::min(R(0) + 0.5 * L, MaxNoseRange(a, target));
    if (!(hi > lo)) continue;
    const BranchPoint plo = EvaluateBranch(a, target, s2, s3, lo), phi = EvaluateBranch(a, target, s2, s3, hi);
    const BranchPoint seed = EvaluateBranch(a, target, s2, s3, R(0));
    if (!seed.valid) continue;
    const BranchPoint m = GoldenDip(c, s2, s3, lo, hi, Negative(seed.f) ? -1.0 : 1.0);
    if (!m.valid) continue;
    if (plo.valid && Negative(plo.f) != Negative(m.f)) {
      AddExact(c, Bisect(c, s2, s3, plo, m));
    } else if (phi.valid && Negative(phi.f) != Negative(m.f)) {
      AddExact(c, Bisect(c, s2, s3, m, phi));
    } else {
      AddNearMiss(c, m);
    }
  }
  Finish(c);
  return result;
}

CylinderSolveResult SolveCylinder(const CylinderRays& rays, const target::CylinderShape& target,
                                  const CylinderSolveOptions& options) {
  return options.method == CylinderMethod::kSearch ? SolveCylinderSearch(rays, target, options)
                                                   : SolveCylinderP3P(rays, target, options);
}

}  // namespace rk::attitude

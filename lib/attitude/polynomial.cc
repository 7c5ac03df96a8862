// Closed-form polynomial roots; see polynomial.h.
#include "attitude/polynomial.h"

#include <algorithm>
#include <cmath>

namespace rk::attitude {
namespace {

using cd = std::complex<double>;

cd Eval(const std::array<double, 5>& a, int degree, cd x) {
  cd v = a[static_cast<std::size_t>(degree)];
  for (int i = degree - 1; i >= 0; --i) v = v * x + a[static_cast<std::size_t>(i)];
  return v;
}
cd EvalDerivative(const std::array<double, 5>& a, int degree, cd x) {
  cd v = static_cast<double>(degree) * a[static_cast<std::size_t>(degree)];
  for (int i = degree - 1; i >= 1; --i) v = v * x + static_cast<double>(i) * a[static_cast<std::size_t>(i)];
  return v;
}

// Newton polish on the original polynomial: keeps a step only while it reduces |p|.
cd Polish(const std::array<double, 5>& a, int degree, cd x) {
  double best = std::abs(Eval(a, degree, x));
  for (int it = 0; it < 6 && best > 0.0; ++it) {
    const cd dp = EvalDerivative(a, degree, x);
    if (dp == cd(0.0)) break;
    const cd next = x - Eval(a, degree, x) / dp;
    const double v = std::abs(Eval(a, degree, next));
    if (!(v < best)) break;
    x = next;
    best = v;
  }
  return x;
}

// Roots of x² + b x + c (complex), computed without cancellation.
void MonicQuadratic(cd b, cd c, cd* r0, cd* r1) {
  const cd disc = std::sqrt(b * b - 4.0 * c);
  // q = −(b + sign·disc)/2 with the sign that avoids cancellation.
  const cd q = (std::real(std::conj(b) * disc) >= 0.0) ? -0.5 * (b + disc) : -0.5 * (b - disc);
  if (q == cd(0.0)) {
    *r0 = *r1 = 0.0;
    return;
  }
  *r0 = q;
  *r1 = c / q;
}

}  // namespace

int SolveMonicCubicReal(double b, double c, double d, std::array<double, 3>* roots) {
  // x = t − b/3: t³ + p t + q = 0.
  const double p = c - b * b / 3.0;
  const double q = 2.0 * b * b * b / 27.0 - b * c / 3.0 + d;
  const double shift = -b / 3.0;
  int n = 0;
  const double disc = q * q / 4.0 + p * p * p / 27.0;
  if (disc > 0.0) {
    // One real root (Cardano).
    const double s = std::sqrt(disc);
    const double u = std::cbrt(-q / 2.0 + s);
    const double v = std::cbrt(-q / 2.0 - s);
    (*roots)[0] = u + v + shift;
    n = 1;
  } else if (p == 0.0) {
    (*roots)[0] = shift;
    n = 1;
  } else {
    // Three real roots (trigonometric form).
    const double m = 2.0 * std::sqrt(-p / 3.0);
    const double arg = std::clamp(3.0 * q / (p * m), -1.0, 1.0);
    const double theta = std::acos(arg) / 3.0;
    for (int k = 0; k < 3; ++k) (*roots)[static_cast<std::size_t>(k)] = m * std::cos(theta - 2.0 * M_PI * k / 3.0) + shift;
    n = 3;
  }
  // Newton polish on the cubic itself.
  for (int i = 0; i < n; ++i) {
    double x = (*roots)[static_cast<std::size_t>(i)];
    double fx = ((x + b) * x + c) * x + d;
    for (int it = 0; it < 4; ++it) {
      const double df = (3.0 * x + 2.0 * b) * x + c;
      if (df == 0.0) break;
      const double nx = x - fx / df;
      const double nf = ((nx + b) * nx + c) * nx + d;
      if (!(std::abs(nf) < std::abs(fx))) break;
      x = nx;
      fx = nf;
    }
    (*roots)[static_cast<std::size_t>(i)] = x;
  }
  std::sort(roots->begin(), roots->begin() + n);
  return n;
}

int SolveQuartic(const std::array<double, 5>& a, std::array<std::complex<double>, 4>* roots) {
  double scale = 0.0;
  for (double v : a) scale = std::max(scale, std::abs(v));
  if (scale == 0.0) return 0;
  int degree = 4;
  while (degree > 0 && std::abs(a[static_cast<std::size_t>(degree)]) < 1e-15 * scale) --degree;
  if (degree == 0) return 0;
  const double lead = a[static_cast<std::size_t>(degree)];
  if (degree == 1) {
    (*roots)[0] = -a[0] / lead;
    return 1;
  }
  if (degree == 2) {
    MonicQuadratic(a[1] / lead, a[0] / lead, &(*roots)[0], &(*roots)[1]);
    for (int i = 0; i < 2; ++i) (*roots)[static_cast<std::size_t>(i)] = Polish(a, 2, (*roots)[static_cast<std::size_t>(i)]);
    return 2;
  }
  if (degree == 3) {
    const double b = a[2] / lead, c = a[1] / lead, d = a[0] / lead;
    std::array<double, 3> r{};
    const int n = SolveMonicCubicReal(b, c, d, &r);
    (*roots)[0] = r[0];
    if (n == 3) {
      (*roots)[1] = r[1];
      (*roots)[2] = r[2];
    } else {
      // Deflate: x³ + b x² + c x + d = (x − r0)(x² + (b + r0) x + (c + r0 (b + r0))).
      const double bb = b + r[0];
      const double cc = c + r[0] * bb;
      MonicQuadratic(bb, cc, &(*roots)[1], &(*roots)[2]);
    }
    for (int i = 0; i < 3; ++i) (*roots)[static_cast<std::size_t>(i)] = Polish(a, 3, (*roots)[static_cast<std::size_t>(i)]);
    return 3;
  }
  // Ferrari. Monic x⁴ + b x³ + c x² + d x + e; x = y − b/4 gives y⁴ + p y² + q y + r = 0.
  const double b = a[3] / lead, c = a[2] / lead, d = a[1] / lead, e = a[0] / lead;
  const double b2 = b * b;
  const double p = c - 3.0 * b2 / 8.0;
  const double q = d - b * c / 2.0 + b2 * b / 8.0;
  const double r = e - b * d / 4.0 + b2 * c / 16.0 - 3.0 * b2 * b2 / 256.0;
  const double shift = -b / 4.0;
  const double qscale = std::max({1.0, std::abs(p), std::sqrt(std::abs(r))});
  if (std::abs(q) < 1e-14 * qscale * std::sqrt(qscale)) {
    // Biquadratic: z² + p z + r = 0 with z = y².
    cd z0, z1;
    MonicQuadratic(p, r, &z0, &z1);
    const cd w0 = std::sqrt(z0), w1 = std::sqrt(z1);
    (*roots)[0] = w0 + shift;
    (*roots)[1] = -w0 + shift;
    (*roots)[2] = w1 + shift;
    (*roots)[3] = -w1 + shift;
  } else {
    // (y² + p/2 + m)² = 2m y² − q y + (m² + m p + p²/4 − r); a perfect square when
    // m³ + p m² + (p²/4 − r) m − q²/8 = 0 with m > 0 (exists since the cubic is −q²/8 < 0 at 0).
    std::array<double, 3> mr{};
    const int nm = SolveMonicCubicReal(p, p * p / 4.0 - r, -q * q / 8.0, &mr);
    const double m = mr[static_cast<std::size_t>(nm - 1)];  // largest real root
    const double s = std::sqrt(std::max(2.0 * m, 0.0));
    cd y0, y1, y2, y3;
    if (s == 0.0) {
      MonicQuadratic(0.0, p / 2.0, &y0, &y1);
      y2 = y0;
      y3 = y1;
    } else {
      // y² + p/2 + m = ±(s y − q/(2 s)).
      MonicQuadratic(-s, p / 2.0 + m + q / (2.0 * s), &y0, &y1);
      MonicQuadratic(s, p / 2.0 + m - q / (2.0 * s), &y2, &y3);
    }
    (*roots)[0] = y0 + shift;
    (*roots)[1] = y1 + shift;
    (*roots)[2] = y2 + shift;
    (*roots)[3] = y3 + shift;
  }
  for (int i = 0; i < 4; ++i) (*roots)[static_cast<std::size_t>(i)] = Polish(a, 4, (*roots)[static_cast<std::size_t>(i)]);
  return 4;
}

}  // namespace rk::attitude

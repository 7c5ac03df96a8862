// Roots of real polynomials of degree ≤ 4 in closed form (Cardano / trigonometric cubic, Ferrari quartic),
// each root polished by complex Newton steps on the original polynomial. Used by the closed-form P3P of
// cylinder_solve.h.
#pragma once

#include <array>
#include <complex>

namespace rk::attitude {

// Roots of a[4] x⁴ + a[3] x³ + a[2] x² + a[1] x + a[0] (leading coefficients that are negligible relative
// to the largest, |a_n| < 1e-15 max|a|, lower the degree). Returns the number of roots written (complex,
// with multiplicity): the degree, or 0 for a constant.
int SolveQuartic(const std::array<double, 5>& a, std::array<std::complex<double>, 4>* roots);

// Real roots of x³ + b x² + c x + d (1 or 3, ascending); returns the count.
int SolveMonicCubicReal(double b, double c, double d, std::array<double, 3>* roots);

}  // namespace rk::attitude

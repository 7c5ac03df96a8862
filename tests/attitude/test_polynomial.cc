// Polynomial roots (attitude/polynomial.h): the quartic solver on polynomials with known roots.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

#include "attitude/polynomial.h"

namespace rk::attitude {
namespace {

TEST(Polynomial, QuarticRootsOfKnownPolynomials) {
  // Residuals of the roots of: an arbitrary quartic, x⁴ + 1 (all complex) and a double-root quartic.
  const std::array<std::array<double, 5>, 3> polys = {{
      {3.0, -9.5, 6.5, 1.5, -1.0},
      {1.0, 0.0, 0.0, 0.0, 1.0},
      {4.0, -4.0, -3.0, 2.0, 1.0},  // (x² + x − 2)² = x⁴ + 2x³ − 3x² − 4x + 4
  }};
  // Coefficients above are highest power first for readability; SolveQuartic wants index = power.
  for (const auto& hp : polys) {
    std::array<double, 5> a{};
    for (int i = 0; i < 5; ++i) a[static_cast<std::size_t>(i)] = hp[static_cast<std::size_t>(4 - i)];
    std::array<std::complex<double>, 4> r;
    ASSERT_EQ(SolveQuartic(a, &r), 4);
    for (const auto& z : r) {
      std::complex<double> v = 0.0;
      for (int i = 4; i >= 0; --i) v = v * z + a[static_cast<std::size_t>(i)];
      EXPECT_LT(std::abs(v), 1e-7) << z;  // double roots are only ~sqrt(eps) accurate
    }
  }
  // (x − 1)(x − 2)(x + 3)(x − 0.5) = x⁴ − 0.5x³ − 7x² + 9.5x − 3 (index = power).
  std::array<double, 5> a{-3.0, 9.5, -7.0, -0.5, 1.0};
  std::array<std::complex<double>, 4> r;
  ASSERT_EQ(SolveQuartic(a, &r), 4);
  std::vector<double> re;
  for (const auto& z : r) {
    EXPECT_NEAR(z.imag(), 0.0, 1e-12);
    re.push_back(z.real());
  }
  std::sort(re.begin(), re.end());
  EXPECT_NEAR(re[0], -3.0, 1e-12);
  EXPECT_NEAR(re[1], 0.5, 1e-12);
  EXPECT_NEAR(re[2], 1.0, 1e-12);
  EXPECT_NEAR(re[3], 2.0, 1e-12);
}

}  // namespace
}  // namespace rk::attitude

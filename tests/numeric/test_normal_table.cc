// The tabulated normal CDF and density against the C library's erfc and exp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "numeric/normal_table.h"

namespace {

constexpr double kTableTolerance = 2e-10;  // interpolation error bound claimed in normal_table.h

TEST(NormalTable, MatchesErfcAndExpEverywhere) {
  const rk::numeric::NormalTable& t = rk::numeric::NormalTable::Get();
  double worst_cdf = 0, worst_pdf = 0;
  for (double z = -12.0; z <= 12.0; z += 1.0 / 1024 + 1e-7) {  // off the table's nodes
    double c = 0, p = 0;
    t.CdfPdf(z, &c, &p);
    worst_cdf = std::max(worst_cdf, std::abs(c - 0.5 * std::erfc(-z / std::sqrt(2.0))));
    worst_pdf = std::max(worst_pdf, std::abs(p - std::exp(-0.5 * z * z) / std::sqrt(2 * M_PI)));
  }
  EXPECT_LT(worst_cdf, kTableTolerance);
  EXPECT_LT(worst_pdf, kTableTolerance);
  EXPECT_GT(worst_cdf, 0.0);  // an interpolation, not the library's values: the test can see a difference
}

TEST(NormalTable, TailsAndNaN) {
  const rk::numeric::NormalTable& t = rk::numeric::NormalTable::Get();
  double c = -1, p = -1;
  t.CdfPdf(40.0, &c, &p);
  EXPECT_EQ(c, 1.0);
  EXPECT_EQ(p, 0.0);
  t.CdfPdf(-std::numeric_limits<double>::infinity(), &c, &p);
  EXPECT_EQ(c, 0.0);
  EXPECT_EQ(p, 0.0);
  t.CdfPdf(std::numeric_limits<double>::quiet_NaN(), &c, &p);
  EXPECT_TRUE(std::isnan(c) && std::isnan(p));
  t.CdfPdf(0.0, &c, &p);
  EXPECT_NEAR(c, 0.5, 1e-15);
}

}  // namespace

// The standard normal CDF Φ(z) and density φ(z) together, by cubic Hermite interpolation of a table (step
// 1/64 over |z| < 9; beyond, Φ is 0 or 1 and φ is 0 to double precision's needs here). Both errors are below
// 2e-10 (tests/numeric/test_normal_table.cc checks them against std::erfc and std::exp on a dense grid),
// far below any image model's noise, at a fifth of erfc + exp's cost: the blurred-edge models of the disc
// (extract/disk_model.h) evaluate both for every pixel of every Levenberg–Marquardt step.
#pragma once

#include <array>
#include <cmath>
#include <limits>

namespace rk::numeric {

class NormalTable {
 public:
  static constexpr double kZMax = 9.0;
  static constexpr int kPerUnit = 64;
  static constexpr int kIntervals = static_cast<int>(2 * kZMax) * kPerUnit;

  // The one table (made on first use).
  static const NormalTable& Get() {
    static const NormalTable table;
    return table;
  }

  // Φ(z) and φ(z); NaN for a NaN z.
  void CdfPdf(double z, double* cdf, double* pdf) const {
    if (!(std::abs(z) < kZMax)) {
      if (std::isnan(z)) {
        *cdf = *pdf = std::numeric_limits<double>::quiet_NaN();
      } else {
        *cdf = z > 0 ? 1.0 : 0.0;
        *pdf = 0.0;
      }
      return;
    }
    const double u = (z + kZMax) * kPerUnit;
    int i = static_cast<int>(u);
    if (i >= kIntervals) i = kIntervals - 1;
    const double t = u - i, t2 = t * t, t3 = t2 * t;
    const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = 3 * t2 - 2 * t3, h11 = t3 - t2;
    const auto k = static_cast<std::size_t>(i);
    constexpr double h = 1.0 / kPerUnit;
    const double z0 = -kZMax + i * h, z1 = z0 + h;
    *cdf = h00 * cdf_[k] + h01 * cdf_[k + 1] + h * (h10 * pdf_[k] + h11 * pdf_[k + 1]);  // Φ' = φ
    *pdf = h00 * pdf_[k] + h01 * pdf_[k + 1] - h * (h10 * z0 * pdf_[k] + h11 * z1 * pdf_[k + 1]);  // φ' = −zφ
  }

 private:
  NormalTable() {
    for (int i = 0; i <= kIntervals; ++i) {
      const double z = -kZMax + static_cast<double>(i) / kPerUnit;
      cdf_[static_cast<std::size_t>(i)] = 0.5 * std::erfc(-z * 0.70710678118654752440);
      pdf_[static_cast<std::size_t>(i)] = 0.39894228040143267794 * std::exp(-0.5 * z * z);
    }
  }
  std::array<double, kIntervals + 1> cdf_{}, pdf_{};
};

}  // namespace rk::numeric

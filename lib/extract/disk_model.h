// The blurred-disc model of a round marker, shared by rk-extract features (its markers) and rk-extract
// points' `circle` method:
//   I(x) = b0 + bx (x − x0) + by (y − y0) + a · Φ((ρ − ‖x − c‖) / s),  Φ = normal CDF,
// θ = (cx, cy, ρ, s, a, b0, bx, by), the plane about the window's centre pixel (x0, y0). For ρ ≫ s it is a
// disc convolved with a Gaussian PSF of std s; the fitted centre of any centrally symmetric profile is
// unbiased. Evaluated over the window of ±half px about (x0, y0) of a CV_32FC1 image, or only over the
// annulus inner ≤ ‖x − (ax, ay)‖ ≤ outer of it (the rim: a highlight or a hole inside the disc then has no
// weight). operator() returns the SSE and, with H and g, the Gauss–Newton normal equations JᵀJ, Jᵀr. Φ and φ
// come from numeric/normal_table.h (within 2e-10 of erfc and exp).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <opencv2/core.hpp>

#include "numeric/normal_table.h"

namespace rk::extract {

inline constexpr double kDiskInvSqrt2 = 0.70710678118654752440;
inline constexpr double kDiskInvSqrt2Pi = 0.39894228040143267794;

class DiskModel {
 public:
  using Vec8 = Eigen::Matrix<double, 8, 1>;
  using Mat8 = Eigen::Matrix<double, 8, 8>;

  DiskModel(const cv::Mat& image, int x0, int y0, int half) : image_(image), x0_(x0), y0_(y0), half_(half) {}
  // Only pixels whose centre lies in the annulus inner_px ≤ r ≤ outer_px about (ax, ay).
  void SetAnnulus(double ax, double ay, double inner_px, double outer_px) {
    annulus_ = true;
    ax_ = ax;
    ay_ = ay;
    r2_in_ = inner_px > 0 ? inner_px * inner_px : -1.0;
    r2_out_ = outer_px * outer_px;
  }
  // Pixels of `mask` (CV_8UC1, the image's size) that are non-zero are left out (outliers: a highlight that
  // reaches the rim, a partly covering cloud); nullptr uses every pixel.
  void SetExcluded(const cv::Mat* mask) { excluded_ = mask; }
  // The model's value at pixel (x, y).
  double Value(const Vec8& t, int x, int y) const {
    const double r = std::sqrt((x - t(0)) * (x - t(0)) + (y - t(1)) * (y - t(1)));
    double Phi = 0, phi = 0;
    table_.CdfPdf((t(2) - r) / t(3), &Phi, &phi);
    return t(5) + t(6) * (x - x0_) + t(7) * (y - y0_) + t(4) * Phi;
  }
  bool Used(int x, int y) const {
    if (excluded_ && excluded_->at<unsigned char>(y, x)) return false;
    if (!annulus_) return true;
    const double r2 = (x - ax_) * (x - ax_) + (y - ay_) * (y - ay_);
    return r2 >= r2_in_ && r2 <= r2_out_;
  }
  // Pixels the model is evaluated on.
  int Pixels() const {
    int n = 0;
    for (int y = y0_ - half_; y <= y0_ + half_; ++y)
      for (int x = x0_ - half_; x <= x0_ + half_; ++x) n += Used(x, y) ? 1 : 0;
    return n;
  }

  double operator()(const Vec8& t, Mat8* H, Vec8* g) const {
    double sse = 0.0;
    if (H) {
      H->setZero();
      g->setZero();
    }
    const double k = 1.0 / t(3);
    for (int y = y0_ - half_; y <= y0_ + half_; ++y) {
      const float* row = image_.ptr<float>(y);
      const double dy = y - t(1);
      for (int x = x0_ - half_; x <= x0_ + half_; ++x) {
        if ((annulus_ || excluded_) && !Used(x, y)) continue;
        const double dx = x - t(0);
        const double r = std::sqrt(dx * dx + dy * dy);
        const double z = (t(2) - r) * k;
        double Phi = 0, phi = 0;
        table_.CdfPdf(z, &Phi, &phi);
        const double model = t(5) + t(6) * (x - x0_) + t(7) * (y - y0_) + t(4) * Phi;
        const double res = model - row[x];
        sse += res * res;
        if (H) {
          const double aphi = t(4) * phi * k;  // a φ(z) / s
          Vec8 J;
          J(0) = r > 1e-12 ? aphi * dx / r : 0.0;
          J(1) = r > 1e-12 ? aphi * dy / r : 0.0;
          J(2) = aphi;
          J(3) = -aphi * z;
          J(4) = Phi;
          J(5) = 1.0;
          J(6) = x - x0_;
          J(7) = y - y0_;
          H->template selfadjointView<Eigen::Upper>().rankUpdate(J);
          *g += J * res;
        }
      }
    }
    if (H) *H = H->template selfadjointView<Eigen::Upper>();
    return sse;
  }

 private:
  const cv::Mat& image_;
  const int x0_, y0_, half_;
  bool annulus_ = false;
  const cv::Mat* excluded_ = nullptr;
  const numeric::NormalTable& table_ = numeric::NormalTable::Get();  // Φ and φ: erfc + exp at a fifth of the cost
  double ax_ = 0, ay_ = 0, r2_in_ = -1, r2_out_ = 0;
};

}  // namespace rk::extract

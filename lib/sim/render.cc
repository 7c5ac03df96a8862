#include "sim/render.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rk::sim {

const io::OptionTable<SensorOptions>& SensorOptions::Table() {
  static const io::OptionTable<SensorOptions> table =
      io::OptionTable<SensorOptions>()
          .Choice("--bit-depth", &SensorOptions::bit_depth, {{8, "8"}, {16, "16"}}, "8 or 16 (16-bit: every DN x256)")
          .Real("--background-dn", &SensorOptions::background_dn, "DN", io::Bounds::Closed(0.0, 255.0),
                "Background level (8-bit DN)")
          .Real("--read-noise-dn", &SensorOptions::read_noise_dn, "DN", io::Bounds::Closed(0.0, 100.0),
                "Read noise std (8-bit DN)")
          .Real("--gain-e-per-dn", &SensorOptions::gain_e_per_dn, "e-/DN", io::Bounds::Closed(0.0, 1e6),
                "Photo-electrons per 8-bit DN (shot noise); 0 = none");
  return table;
}

bool SensorOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (bit_depth != 8 && bit_depth != 16) {
    if (why) *why = "--bit-depth must be 8 or 16";
    return false;
  }
  return true;
}
namespace {

// Fraction of a unit 1-D Gaussian (mean mu, std s) falling in [a, b).
inline double Mass(double a, double b, double mu, double s) {
  const double k = 1.0 / (std::sqrt(2.0) * s);
  return 0.5 * (std::erf((b - mu) * k) - std::erf((a - mu) * k));
}

}  // namespace

void AddSpots(cv::Mat* signal, std::span<const Spot> spots) {
  CV_Assert(signal->type() == CV_32FC1);
  std::vector<double> wx, wy;
  for (const Spot& s : spots) {
    const double flux = 2.0 * M_PI * s.sigma_px * s.sigma_px * s.amplitude_dn;
    const double reach = 5.0 * s.sigma_px + 1.0;
    const int x0 = std::max(0, static_cast<int>(std::floor(s.x_px - reach)));
    const int x1 = std::min(signal->cols - 1, static_cast<int>(std::ceil(s.x_px + reach)));
    const int y0 = std::max(0, static_cast<int>(std::floor(s.y_px - reach)));
    const int y1 = std::min(signal->rows - 1, static_cast<int>(std::ceil(s.y_px + reach)));
    if (x0 > x1 || y0 > y1) continue;
    wx.resize(static_cast<std::size_t>(x1 - x0 + 1));
    wy.resize(static_cast<std::size_t>(y1 - y0 + 1));
    for (int x = x0; x <= x1; ++x) wx[static_cast<std::size_t>(x - x0)] = Mass(x - 0.5, x + 0.5, s.x_px, s.sigma_px);
    for (int y = y0; y <= y1; ++y) wy[static_cast<std::size_t>(y - y0)] = Mass(y - 0.5, y + 0.5, s.y_px, s.sigma_px);
    for (int y = y0; y <= y1; ++y) {
      float* row = signal->ptr<float>(y);
      const double fy = flux * wy[static_cast<std::size_t>(y - y0)];
      for (int x = x0; x <= x1; ++x) row[x] += static_cast<float>(fy * wx[static_cast<std::size_t>(x - x0)]);
    }
  }
}

cv::Mat Digitise(const cv::Mat& signal, const SensorOptions& opt, std::mt19937_64& rng) {
  CV_Assert(signal.type() == CV_32FC1);
  const bool deep = opt.bit_depth == 16;
  const double max_dn = deep ? 65535.0 : 255.0;
  cv::Mat out(signal.size(), deep ? CV_16UC1 : CV_8UC1);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double read_var = opt.read_noise_dn * opt.read_noise_dn;
  for (int y = 0; y < signal.rows; ++y) {
    const float* in = signal.ptr<float>(y);
    for (int x = 0; x < signal.cols; ++x) {
      const double mean = opt.background_dn + std::max(0.0f, in[x]);
      double v = mean;
      if (opt.gain_e_per_dn > 0) {
        const double electrons = mean * opt.gain_e_per_dn;
        if (electrons < 20.0) {
          // Few electrons: draw the Poisson itself, then the read noise.
          v = static_cast<double>(std::poisson_distribution<int>(electrons)(rng)) / opt.gain_e_per_dn +
              opt.read_noise_dn * normal(rng);
        } else {
          // Shot (Poisson, normal above ~20 e-) and read noise are independent Gaussians: one draw
          // with the summed variance mean/gain + read² (half the cost of two draws).
          v = mean + std::sqrt(mean / opt.gain_e_per_dn + read_var) * normal(rng);
        }
      } else {
        v += opt.read_noise_dn * normal(rng);
      }
      v = std::clamp(std::round(v), 0.0, max_dn);
      if (deep) {
        out.ptr<std::uint16_t>(y)[x] = static_cast<std::uint16_t>(v);
      } else {
        out.ptr<std::uint8_t>(y)[x] = static_cast<std::uint8_t>(v);
      }
    }
  }
  return out;
}

cv::Point2d FluxWeightedCentre(std::span<const Spot> spots) {
  double sw = 0, sx = 0, sy = 0;
  for (const Spot& s : spots) {
    const double w = s.sigma_px * s.sigma_px * s.amplitude_dn;
    sw += w;
    sx += w * s.x_px;
    sy += w * s.y_px;
  }
  return sw > 0 ? cv::Point2d(sx / sw, sy / sw) : cv::Point2d(0, 0);
}

}  // namespace rk::sim

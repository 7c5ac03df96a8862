// The quadrant (checkerboard saddle) measurer; model in point_measure.h.
#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "extract/ncc_search.h"
#include "extract/point_measurers.h"
#include "numeric/levenberg_marquardt.h"

namespace rk::extract {
namespace {

constexpr double kQuadSqrt2 = 1.41421356237309504880;
constexpr double kQuadSqrt2OverPi = 0.79788456080286535588;  // √(2/π)
using Vec7 = Eigen::Matrix<double, 7, 1>;
using Mat7 = Eigen::Matrix<double, 7, 7>;

// θ = (cx, cy, θ1, θ2, s, a, b) over the square window ±half about (x0, y0) of a float ROI whose pixel (0, 0)
// is image pixel (ox, oy).
class SaddleModel {
 public:
  SaddleModel(const cv::Mat& roi, int ox, int oy, int x0, int y0, int half)
      : roi_(roi), ox_(ox), oy_(oy), x0_(x0), y0_(y0), half_(half) {}

  double operator()(const Vec7& t, Mat7* H, Vec7* g, double* sst = nullptr) const {
    double sse = 0, sum = 0, sum2 = 0;
    int n = 0;
    if (H) {
      H->setZero();
      g->setZero();
    }
    const double c1 = std::cos(t(2)), s1 = std::sin(t(2)), c2 = std::cos(t(3)), s2 = std::sin(t(3));
    const double k = 1.0 / (kQuadSqrt2 * t(4));
    for (int y = y0_ - half_; y <= y0_ + half_; ++y) {
      const float* row = roi_.ptr<float>(y - oy_);
      const double dy = y - t(1);
      for (int x = x0_ - half_; x <= x0_ + half_; ++x) {
        const double dx = x - t(0);
        const double d1 = c1 * dx + s1 * dy, d2 = c2 * dx + s2 * dy;
        const double E1 = std::erf(d1 * k), E2 = std::erf(d2 * k);
        const double v = row[x - ox_];
        const double res = t(6) + t(5) * E1 * E2 - v;
        sse += res * res;
        sum += v;
        sum2 += v * v;
        ++n;
        if (!H) continue;
        const double g1 = kQuadSqrt2OverPi / t(4) * std::exp(-d1 * d1 * k * k);  // dE1/dd1
        const double g2 = kQuadSqrt2OverPi / t(4) * std::exp(-d2 * d2 * k * k);
        const double a = t(5);
        Vec7 J;
        J(0) = -a * (g1 * c1 * E2 + E1 * g2 * c2);
        J(1) = -a * (g1 * s1 * E2 + E1 * g2 * s2);
        J(2) = a * g1 * (-s1 * dx + c1 * dy) * E2;
        J(3) = a * E1 * g2 * (-s2 * dx + c2 * dy);
        J(4) = -a * (g1 * d1 * E2 + E1 * g2 * d2) / t(4);
        J(5) = E1 * E2;
        J(6) = 1.0;
        H->selfadjointView<Eigen::Upper>().rankUpdate(J);
        *g += J * res;
      }
    }
    if (H) *H = H->selfadjointView<Eigen::Upper>();
    if (sst) *sst = sum2 - sum * sum / std::max(n, 1);
    return sse;
  }
  int Pixels() const { return (2 * half_ + 1) * (2 * half_ + 1); }

 private:
  const cv::Mat& roi_;
  const int ox_, oy_, x0_, y0_, half_;
};

class QuadrantMeasurer final : public PointMeasurer {
 public:
  QuadrantMeasurer(std::optional<double> size_px, const PointMeasureOptions& o) : opt_(o) {
    half_ = size_px ? std::clamp(static_cast<int>(std::lround(0.3 * *size_px)), 3, 15) : 6;
  }

  PointMeasurement Seed(const cv::Mat& frame, const Eigen::Vector2d& px, double search_px) override {
    // The best of 8 edge angles (θ2 = θ1 + 90°; the sign of the best correlation gives the polarity).
    double best = -1;
    for (int i = 0; i < 8; ++i) {
      const double th = i * M_PI / 16.0;
      for (double sign : {1.0, -1.0}) {
        MakeTemplate(th, th + M_PI / 2, 1.0, sign);
        const auto c = TemplatePeaks(frame, templ_, px, search_px + 1, 1, -1.0, 1.0);
        if (!c.empty() && c[0].score > best) {
          best = c[0].score;
          th1_ = th;
          th2_ = th + M_PI / 2;
          sign_ = sign;
        }
      }
    }
    edge_ = 1.0;
    return Measure(frame, px, search_px);
  }

  PointMeasurement Measure(const cv::Mat& frame, const Eigen::Vector2d& predicted, double search_px) override {
    PointMeasurement m;
    MakeTemplate(th1_, th2_, edge_, sign_);
    cv::Point tl;
    NccPeak peak;
    if (!SearchWindow(frame, templ_, predicted, search_px, 2, opt_.ncc_min, &roi_, &map_, &tl, &peak, &m)) return m;
    return Fit(tl, peak.sub, peak.score);
  }

  std::vector<PointCandidate> Candidates(const cv::Mat& frame, const Eigen::Vector2d& center, double search_px,
                                         int max_n) override {
    MakeTemplate(th1_, th2_, edge_, sign_);
    return TemplatePeaks(frame, templ_, center, search_px, max_n, opt_.ncc_min, half_);
  }

  void Accept(const PointMeasurement&) override {
    th1_ = fit_th1_;
    th2_ = fit_th2_;
    edge_ = fit_edge_;
    sign_ = fit_sign_;
  }
  int SupportHalfPx() const override { return half_ + 2; }

 private:
  void MakeTemplate(double th1, double th2, double s, double sign) {
    const int n = 2 * half_ + 1;
    templ_.create(n, n, CV_32FC1);
    const double k = 1.0 / (kQuadSqrt2 * std::max(s, 0.5));
    for (int y = -half_; y <= half_; ++y) {
      float* r = templ_.ptr<float>(y + half_);
      for (int x = -half_; x <= half_; ++x) {
        const double d1 = std::cos(th1) * x + std::sin(th1) * y, d2 = std::cos(th2) * x + std::sin(th2) * y;
        r[x + half_] = static_cast<float>(sign * std::erf(d1 * k) * std::erf(d2 * k));
      }
    }
  }

  PointMeasurement Fit(const cv::Point& tl, const Eigen::Vector2d& start, double ncc);

  PointMeasureOptions opt_;
  int half_ = 6;
  double th1_ = 0, th2_ = M_PI / 2, edge_ = 1.0, sign_ = 1.0;
  double fit_th1_ = 0, fit_th2_ = M_PI / 2, fit_edge_ = 1.0, fit_sign_ = 1.0;
  cv::Mat roi_, templ_, map_;
};

PointMeasurement QuadrantMeasurer::Fit(const cv::Point& tl, const Eigen::Vector2d& start, double ncc) {
  PointMeasurement m;
  m.score = std::max(0.0, ncc);
  const int x0 = static_cast<int>(std::lround(start.x())), y0 = static_cast<int>(std::lround(start.y()));
  if (x0 - half_ < tl.x || y0 - half_ < tl.y || x0 + half_ >= tl.x + roi_.cols || y0 + half_ >= tl.y + roi_.rows) {
    m.why = "at the window border";
    return m;
  }
  const SaddleModel model(roi_, tl.x, tl.y, x0, y0, half_);
  // Start: a and b by linear least squares at the coarse position and the last angles.
  Vec7 th;
  th << start.x(), start.y(), th1_, th2_, std::max(edge_, 0.5), sign_, 0.0;
  {
    double sxx = 0, sx = 0, sy = 0, sxy = 0, n = 0;
    const double k = 1.0 / (kQuadSqrt2 * th(4));
    for (int y = y0 - half_; y <= y0 + half_; ++y)
      for (int x = x0 - half_; x <= x0 + half_; ++x) {
        const double dx = x - th(0), dy = y - th(1);
        const double e = std::erf((std::cos(th1_) * dx + std::sin(th1_) * dy) * k) *
                         std::erf((std::cos(th2_) * dx + std::sin(th2_) * dy) * k);
        const double v = roi_.at<float>(y - tl.y, x - tl.x);
        sxx += e * e;
        sx += e;
        sy += v;
        sxy += e * v;
        n += 1;
      }
    const double det = n * sxx - sx * sx;
    if (det > 1e-9) {
      th(5) = (n * sxy - sx * sy) / det;
      th(6) = (sy - th(5) * sx) / n;
    }
  }
  struct Lm {
    const SaddleModel& f;
    Vec7 th, cand;
    bool TryStep(const Vec7& step, double* cost) {
      cand = th + step;
      cand(4) = std::clamp(cand(4), 0.2, 10.0);
      *cost = f(cand, nullptr, nullptr);
      return std::isfinite(*cost);
    }
    void Accept() { th = cand; }
    bool Linearize(Mat7* H, Vec7* g) {
      f(th, H, g);
      return true;
    }
    // 1e-4 px: far below the centre's σ; a tighter test only adds iterations.
    bool Converged(const Vec7& step, double, double) const { return step.head<2>().norm() < 1e-4; }
  } lm{model, th, th};
  Mat7 H;
  Vec7 g;
  const numeric::LmDamping damping{.initial = 1e-3, .diagonal_floor = 1e-12, .increase = 10.0, .decrease = 0.2,
                                   .min = 1e-9, .max_tries = 8, .accept_equal_cost = false};
  const numeric::LmSummary s = numeric::LevenbergMarquardt<7>(lm, model(th, &H, &g), damping, opt_.max_iterations, &H, &g);
  th = lm.th;
  double sst = 0;
  const double sse = model(th, nullptr, nullptr, &sst);
  const bool converged = s.status == numeric::LmStatus::kConverged || s.status == numeric::LmStatus::kNonFiniteStep;
  const double var = sse / std::max(1, model.Pixels() - 7);
  const Mat7 cov = var * H.ldlt().solve(Mat7::Identity());
  m.px = th.head<2>();
  m.cov = cov.topLeftCorner<2, 2>();
  m.cov.diagonal().array() += opt_.sigma_floor_px * opt_.sigma_floor_px;
  m.size_px = th(4);
  m.score = sst > 0 ? std::sqrt(std::max(0.0, 1.0 - sse / sst)) : 0.0;
  const double noise = WindowNoise(roi_);
  fit_th1_ = th(2);
  fit_th2_ = th(3);
  fit_edge_ = th(4);
  fit_sign_ = th(5) >= 0 ? 1.0 : -1.0;
  if (!converged) {
    m.why = "fit did not converge";
  } else if (!(std::abs(th(5)) >= opt_.min_contrast_sigmas * noise)) {
    m.why = "too faint";
  } else if (std::abs(std::sin(th(3) - th(2))) < 0.5 || th(4) > 0.5 * half_) {
    m.why = "not a quadrant marker";
  } else if ((m.px - start).norm() > 0.5 * half_ || !cov.allFinite() || !(m.cov.determinant() > 0)) {
    m.why = "fit left its window";
  } else if (m.score < opt_.ncc_min) {
    m.why = "poor fit";
  } else {
    m.ok = true;
  }
  return m;
}

}  // namespace

std::unique_ptr<PointMeasurer> MakeQuadrantMeasurer(std::optional<double> size_px, const PointMeasureOptions& o) {
  return std::make_unique<QuadrantMeasurer>(size_px, o);
}

}  // namespace rk::extract

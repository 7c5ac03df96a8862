// The circle measurer: the blurred-disc model fitted on the rim only; model in point_measure.h.
#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "extract/disk_model.h"
#include "extract/ncc_search.h"
#include "extract/point_measurers.h"
#include "numeric/levenberg_marquardt.h"
#include "numeric/robust_stats.h"

namespace rk::extract {
namespace {

using CVec8 = DiskModel::Vec8;
using CMat8 = DiskModel::Mat8;

// A rim pixel this many robust σ off the model is left out. Not fewer: at 3.5 σ noise alone sent fits round
// again for nothing (bench/points_speed: 4.7 k point-frames/s against 5.3 k at 4.5 σ, and the same errors in
// bench/points_accuracy); a highlight or a cloud edge on the rim is tens of σ off.
constexpr double kCircleOutlierSigmas = 4.5;
constexpr double kCircleMaxExcluded = 0.2;    // ... unless that would leave out more than this share of the band

// Levenberg–Marquardt on the disc model from *th; radius ≥ 0.5 px, edge in [0.3, 10] px.
numeric::LmSummary FitDisk(const DiskModel& model, int max_iterations, CVec8* th, CMat8* H) {
  struct Lm {
    const DiskModel& f;
    CVec8 th, cand;
    bool TryStep(const CVec8& step, double* cost) {
      cand = th + step;
      cand(2) = std::max(cand(2), 0.5);
      cand(3) = std::clamp(cand(3), 0.3, 10.0);
      *cost = f(cand, nullptr, nullptr);
      return std::isfinite(*cost);
    }
    void Accept() { th = cand; }
    bool Linearize(CMat8* h, CVec8* g) {
      f(th, h, g);
      return true;
    }
    // 1e-4 px: far below the centre's σ; a tighter test only adds iterations.
    bool Converged(const CVec8& step, double, double) const { return step.head<2>().norm() < 1e-4; }
  } lm{model, *th, *th};
  CVec8 g;
  const numeric::LmDamping damping{.initial = 1e-3, .diagonal_floor = 1e-12, .increase = 10.0, .decrease = 0.2,
                                   .min = 1e-9, .max_tries = 8, .accept_equal_cost = false};
  const double cost = model(*th, H, &g);
  const numeric::LmSummary s = numeric::LevenbergMarquardt<8>(lm, cost, damping, max_iterations, H, &g);
  *th = lm.th;
  return s;
}

class CircleMeasurer final : public PointMeasurer {
 public:
  CircleMeasurer(std::optional<double> size_px, const PointMeasureOptions& o) : opt_(o) {
    if (size_px) radius_ = 0.5 * *size_px;
  }

  PointMeasurement Seed(const cv::Mat& frame, const Eigen::Vector2d& px, double search_px) override {
    if (!(radius_ > 0)) radius_ = RadiusFromProfile(frame, px);
    // Polarity: the rim's inside against its outside.
    const int R = static_cast<int>(std::ceil(radius_ + 4));
    const int ix = static_cast<int>(std::lround(px.x())), iy = static_cast<int>(std::lround(px.y()));
    if (CopyFloatRoi(frame, cv::Rect(ix - R, iy - R, 2 * R + 1, 2 * R + 1), &roi_)) {
      std::vector<double> in, out;
      for (int y = -R; y <= R; ++y)
        for (int x = -R; x <= R; ++x) {
          const double r = std::hypot(x, y);
          if (r > 0.5 * radius_ && r < radius_ - 1) in.push_back(roi_.at<float>(y + R, x + R));
          if (r > radius_ + 1.5) out.push_back(roi_.at<float>(y + R, x + R));
        }
      if (!in.empty() && !out.empty()) sign_ = numeric::Median(in) >= numeric::Median(out) ? 1.0 : -1.0;
    }
    return Measure(frame, px, search_px);
  }

  PointMeasurement Measure(const cv::Mat& frame, const Eigen::Vector2d& predicted, double search_px) override {
    PointMeasurement m;
    MakeTemplate();
    cv::Point tl;
    NccPeak peak;
    if (!SearchWindow(frame, templ_, predicted, search_px, 3, opt_.ncc_min, &roi_, &map_, &tl, &peak, &m)) return m;
    return Fit(tl, peak.sub, peak.score);
  }

  std::vector<PointCandidate> Candidates(const cv::Mat& frame, const Eigen::Vector2d& center, double search_px,
                                         int max_n) override {
    MakeTemplate();
    return TemplatePeaks(frame, templ_, center, search_px, max_n, opt_.ncc_min, std::max(2.0, radius_));
  }

  void Accept(const PointMeasurement&) override {
    radius_ = fit_radius_;
    edge_ = fit_edge_;
  }
  int SupportHalfPx() const override { return static_cast<int>(std::ceil(radius_ + 3 * edge_ + 3)); }

 private:
  // The radius where the mean radial intensity profile about px changes fastest (seeds without size_px).
  static double RadiusFromProfile(const cv::Mat& frame, const Eigen::Vector2d& px) {
    constexpr int kMax = 40;
    std::vector<double> sum(kMax + 2, 0.0), n(kMax + 2, 0.0);
    for (int y = -kMax; y <= kMax; ++y)
      for (int x = -kMax; x <= kMax; ++x) {
        const int u = static_cast<int>(std::lround(px.x())) + x, v = static_cast<int>(std::lround(px.y())) + y;
        const int r = static_cast<int>(std::lround(std::hypot(x, y)));
        if (r > kMax || u < 0 || v < 0 || u >= frame.cols || v >= frame.rows) continue;
        sum[static_cast<std::size_t>(r)] += frame.depth() == CV_16U ? frame.at<std::uint16_t>(v, u) : frame.at<std::uint8_t>(v, u);
        n[static_cast<std::size_t>(r)] += 1;
      }
    double best = 0, at = 3;
    for (int r = 2; r < kMax; ++r) {
      const auto i = static_cast<std::size_t>(r);
      if (n[i - 1] == 0 || n[i + 1] == 0) continue;
      const double d = std::abs(sum[i + 1] / n[i + 1] - sum[i - 1] / n[i - 1]);
      if (d > best) {
        best = d;
        at = r;
      }
    }
    return at;
  }

  // The search template of the current radius, edge and polarity (made again only when they change).
  void MakeTemplate() {
    if (!templ_.empty() && std::abs(radius_ - templ_radius_) < 0.05 && std::abs(edge_ - templ_edge_) < 0.05 &&
        sign_ == templ_sign_) {
      return;
    }
    templ_radius_ = radius_;
    templ_edge_ = edge_;
    templ_sign_ = sign_;
    const int h = static_cast<int>(std::ceil(radius_ + 3 * edge_ + 2));
    templ_.create(2 * h + 1, 2 * h + 1, CV_32FC1);
    const numeric::NormalTable& table = numeric::NormalTable::Get();
    for (int y = -h; y <= h; ++y) {
      float* r = templ_.ptr<float>(y + h);
      for (int x = -h; x <= h; ++x) {
        double Phi = 0, phi = 0;
        table.CdfPdf((radius_ - std::sqrt(static_cast<double>(x * x + y * y))) / edge_, &Phi, &phi);
        r[x + h] = static_cast<float>(sign_ * Phi);
      }
    }
  }

  PointMeasurement Fit(const cv::Point& tl, const Eigen::Vector2d& start, double ncc);

  PointMeasureOptions opt_;
  double radius_ = 0.0, edge_ = 1.0, sign_ = 1.0;
  double fit_radius_ = 0.0, fit_edge_ = 1.0;
  double templ_radius_ = -1.0, templ_edge_ = -1.0, templ_sign_ = 0.0;
  cv::Mat roi_, templ_, map_, excluded_;
};

PointMeasurement CircleMeasurer::Fit(const cv::Point& tl, const Eigen::Vector2d& start, double ncc) {
  PointMeasurement m;
  m.score = std::max(0.0, ncc);
  // The rim's band: the edge's information lies within a few s of it; inside the disc less far (a highlight).
  const double band = std::max(3.0 * edge_, 2.0) + 1.5, band_in = std::max(2.0 * edge_, 1.5) + 1.0;
  const int half = static_cast<int>(std::ceil(radius_ + band + 1));
  const int x0 = static_cast<int>(std::lround(start.x())), y0 = static_cast<int>(std::lround(start.y()));
  const int lx = x0 - tl.x, ly = y0 - tl.y;  // in the window
  if (lx - half < 0 || ly - half < 0 || lx + half >= roi_.cols || ly + half >= roi_.rows) {
    m.why = "at the window border";
    return m;
  }
  DiskModel model(roi_, lx, ly, half);
  const Eigen::Vector2d c0 = start - Eigen::Vector2d(tl.x, tl.y);
  model.SetAnnulus(c0.x(), c0.y(), radius_ - band_in, radius_ + band);
  // Start: background outside the rim, disc level inside it (both on the annulus).
  std::vector<double> in, out;
  double sum = 0, sum2 = 0, n = 0;
  for (int y = ly - half; y <= ly + half; ++y)
    for (int x = lx - half; x <= lx + half; ++x) {
      const double r = std::sqrt((x - c0.x()) * (x - c0.x()) + (y - c0.y()) * (y - c0.y()));
      if (r >= radius_ - band_in && r <= radius_ + band) {
        const double v = roi_.at<float>(y, x);
        sum += v;
        sum2 += v * v;
        n += 1;
      }
      if (r >= radius_ - band_in && r < radius_ - 1.0 * edge_) in.push_back(roi_.at<float>(y, x));
      if (r <= radius_ + band && r > radius_ + 1.5 * edge_) out.push_back(roi_.at<float>(y, x));
    }
  if (in.empty() || out.empty()) {
    m.why = "marker too small";
    return m;
  }
  const double b0 = numeric::Median(out), a0 = numeric::Median(in) - b0;
  CVec8 th;
  th << c0.x(), c0.y(), radius_, std::max(edge_, 0.5), a0, b0, 0.0, 0.0;
  // Levenberg–Marquardt, then again without the pixels whose residual is an outlier (a highlight reaching
  // the rim, a cloud's edge), twice at most.
  const double noise = WindowNoise(roi_);
  excluded_ = cv::Mat::zeros(roi_.size(), CV_8UC1);
  model.SetExcluded(&excluded_);
  CMat8 H;
  numeric::LmSummary s;
  std::vector<double> res;
  for (int pass = 0; pass < 3; ++pass) {
    s = FitDisk(model, opt_.max_iterations, &th, &H);
    // Outliers: residuals beyond 3.5 robust σ (MAD of the residuals, at least the pixel noise). A model that
    // misses everywhere (a textured or shaded disc) is not an outlier: at most a fifth of the band goes.
    res.clear();
    for (int y = ly - half; y <= ly + half; ++y)
      for (int x = lx - half; x <= lx + half; ++x)
        if (model.Used(x, y)) res.push_back(std::abs(model.Value(th, x, y) - roi_.at<float>(y, x)));
    const double used = static_cast<double>(res.size());
    const double thr = kCircleOutlierSigmas * std::max(noise, 1.4826 * numeric::Median(res));
    cv::Mat next = excluded_.clone();
    int added = 0;
    std::size_t k = 0;
    for (int y = ly - half; y <= ly + half; ++y)
      for (int x = lx - half; x <= lx + half; ++x) {
        if (model.Used(x, y) && res[k++] > thr) {
          next.at<std::uint8_t>(y, x) = 1;
          ++added;
        }
      }
    if (added == 0) break;
    cv::dilate(next, next, cv::Mat());
    if (cv::countNonZero(next) > kCircleMaxExcluded * (used + cv::countNonZero(excluded_))) break;
    next.copyTo(excluded_);
  }
  const double sse = s.cost;
  const bool converged = s.status == numeric::LmStatus::kConverged || s.status == numeric::LmStatus::kNonFiniteStep;
  const int npx = model.Pixels();
  const double var = sse / std::max(1, npx - 8);
  const CMat8 cov = var * H.ldlt().solve(CMat8::Identity());
  m.px = th.head<2>() + Eigen::Vector2d(tl.x, tl.y);
  m.cov = cov.topLeftCorner<2, 2>();
  m.cov.diagonal().array() += opt_.sigma_floor_px * opt_.sigma_floor_px;
  m.size_px = 2.0 * th(2);
  // Score: the correlation of the model with the rim's pixels.
  const double sst = sum2 - sum * sum / std::max(n, 1.0);
  m.score = sst > 0 ? std::sqrt(std::max(0.0, 1.0 - sse / sst)) : 0.0;
  fit_radius_ = th(2);
  fit_edge_ = th(3);
  if (!converged) {
    m.why = "fit did not converge";
  } else if (!(std::abs(th(4)) >= opt_.min_contrast_sigmas * noise) || th(4) * sign_ < 0) {
    m.why = "too faint";
  } else if (th(2) > 1.3 * radius_ || th(2) < radius_ / 1.3) {
    m.why = "wrong size";
  } else if ((m.px - start).norm() > 0.5 * radius_ + 1 || !cov.allFinite() || !(m.cov.determinant() > 0)) {
    m.why = "fit left its window";
  } else if (m.score < opt_.ncc_min) {
    m.why = "poor fit";
  } else {
    m.ok = true;
  }
  return m;
}

}  // namespace

std::unique_ptr<PointMeasurer> MakeCircleMeasurer(std::optional<double> size_px, const PointMeasureOptions& o) {
  return std::make_unique<CircleMeasurer>(size_px, o);
}

}  // namespace rk::extract

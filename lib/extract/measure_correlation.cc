// The correlation measurer: affine least-squares matching against the seed's anchor patch; method in
// point_measure.h.
#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "extract/ncc_search.h"
#include "extract/point_measurers.h"
#include "numeric/levenberg_marquardt.h"

namespace rk::extract {
namespace {

using Vec8c = Eigen::Matrix<double, 8, 1>;
using Mat8c = Eigen::Matrix<double, 8, 8>;
// Column-major: each column one anchor-sized image (the rows of an anchor pixel are 8 apart in memory).
using JacobianCols = Eigen::Matrix<double, Eigen::Dynamic, 8>;

// Both the anchor and the frame are smoothed by this Gaussian before matching: matching a noisy image
// interpolated at sub-pixel positions otherwise prefers the positions where interpolation averages the
// noise down (half-pixel phases), a bias of ~0.1 px at 3 DN of noise ("pixel locking"); after the
// prefilter the interpolated noise hardly depends on the phase. Equal symmetric blur moves nothing.
constexpr double kPrefilterSigmaPx = 0.8;
constexpr int kPrefilterMargin = 3;  // px copied around a window so that its blurred pixels are exact

// Σ w² of the 2-D prefilter (the variance of white noise after it, per unit variance before).
double PrefilterGain() {
  static const double gain = [] {
    const int k = static_cast<int>(std::lround(kPrefilterSigmaPx * 8 + 1)) | 1;  // as cv::GaussianBlur sizes float images
    const cv::Mat w = cv::getGaussianKernel(k, kPrefilterSigmaPx, CV_64F);
    const double s = w.dot(w);
    return s * s;
  }();
  return gain;
}

// θ = (cx, cy, a11, a12, a21, a22, g, o): the anchor pixel q maps to c + A (q − seed) in the image, whose
// value should be g T0(q) + o. The image is a float ROI with its top-left at image pixel tl.
class LsmModel {
 public:
  LsmModel(const cv::Mat& roi, const cv::Point& tl, const cv::Mat& anchor, const Eigen::Vector2d& offset)
      : roi_(roi), tl_(tl), anchor_(anchor), offset_(offset) {}

  // SSE (and JᵀJ, Jᵀr), or a negative value when a sample leaves the ROI. n: samples; ncc: the correlation
  // of the warped image with the anchor.
  // jac (anchor pixels × 8, row-major by anchor pixel) receives the Jacobian rows blurred by the prefilter:
  // the position's covariance from white pixel noise through the prefilter (Fit).
  double operator()(const Vec8c& t, Mat8c* H, Vec8c* g, double* ncc = nullptr, JacobianCols* jac = nullptr) const {
    double sse = 0, si = 0, st = 0, sii = 0, stt = 0, sit = 0;
    const int h = anchor_.cols / 2;
    if (H) {
      H->setZero();
      g->setZero();
    }
    for (int v = 0; v < anchor_.rows; ++v) {
      const float* T = anchor_.ptr<float>(v);
      for (int u = 0; u < anchor_.cols; ++u) {
        // q − seed = (u − h, v − h) + offset_ (offset_ = anchor centre pixel − seed).
        const double px = u - h + offset_.x(), py = v - h + offset_.y();
        const double x = t(0) + t(2) * px + t(3) * py - tl_.x, y = t(1) + t(4) * px + t(5) * py - tl_.y;
        double I, gx, gy;
        if (!CubicSample(roi_, x, y, &I, &gx, &gy)) return -1.0;
        const double res = I - t(6) * T[u] - t(7);
        sse += res * res;
        si += I;
        st += T[u];
        sii += I * I;
        stt += static_cast<double>(T[u]) * T[u];
        sit += I * T[u];
        if (!H && !jac) continue;
        Vec8c J;
        J << gx, gy, gx * px, gx * py, gy * px, gy * py, -T[u], -1.0;
        if (jac) jac->row(v * anchor_.cols + u) = J.transpose();
        if (!H) continue;
        H->selfadjointView<Eigen::Upper>().rankUpdate(J);
        *g += J * res;
      }
    }
    if (H) *H = H->selfadjointView<Eigen::Upper>();
    if (jac) {
      for (int c = 0; c < 8; ++c) {
        cv::Mat col(anchor_.rows, anchor_.cols, CV_64FC1, jac->col(c).data());
        cv::GaussianBlur(col, col, cv::Size(0, 0), kPrefilterSigmaPx, kPrefilterSigmaPx, cv::BORDER_REPLICATE);
      }
    }
    if (ncc) {
      const double n = static_cast<double>(anchor_.total());
      const double vi = sii - si * si / n, vt = stt - st * st / n;
      *ncc = vi > 0 && vt > 0 ? (sit - si * st / n) / std::sqrt(vi * vt) : 0.0;
    }
    return sse;
  }

 private:
  const cv::Mat& roi_;
  const cv::Point tl_;
  const cv::Mat& anchor_;
  const Eigen::Vector2d offset_;
};

class CorrelationMeasurer final : public PointMeasurer {
 public:
  CorrelationMeasurer(std::optional<double> size_px, const PointMeasureOptions& o) : opt_(o) {
    half_ = size_px ? std::clamp(static_cast<int>(std::lround(0.5 * *size_px)), 3, 40) : 10;
  }

  PointMeasurement Seed(const cv::Mat& frame, const Eigen::Vector2d& px, double) override {
    PointMeasurement m;
    const int ix = static_cast<int>(std::lround(px.x())), iy = static_cast<int>(std::lround(px.y()));
    const int hm = half_ + kPrefilterMargin;
    if (!CopyFloatRoi(frame, cv::Rect(ix - hm, iy - hm, 2 * hm + 1, 2 * hm + 1), &raw_)) {
      m.why = "at the image border";
      return m;
    }
    anchor_noise_ = WindowNoise(raw_);
    cv::GaussianBlur(raw_, raw_, cv::Size(0, 0), kPrefilterSigmaPx, kPrefilterSigmaPx, cv::BORDER_REPLICATE);
    raw_(cv::Rect(kPrefilterMargin, kPrefilterMargin, 2 * half_ + 1, 2 * half_ + 1)).copyTo(anchor_);
    offset_ = Eigen::Vector2d(ix - px.x(), iy - px.y());
    A_.setIdentity();
    fit_A_.setIdentity();
    accepted_A_.setIdentity();
    gain_ = 1.0;
    offs_ = 0.0;
    // The seed defines the point: its own position, σ from the anchor's gradients (the CR bound).
    double gxx = 0, gyy = 0, gxy = 0;
    for (int y = 1; y + 1 < anchor_.rows; ++y)
      for (int x = 1; x + 1 < anchor_.cols; ++x) {
        const double gx = 0.5 * (anchor_.at<float>(y, x + 1) - anchor_.at<float>(y, x - 1));
        const double gy = 0.5 * (anchor_.at<float>(y + 1, x) - anchor_.at<float>(y - 1, x));
        gxx += gx * gx;
        gyy += gy * gy;
        gxy += gx * gy;
      }
    const double noise = anchor_noise_;
    Eigen::Matrix2d N;
    N << gxx, gxy, gxy, gyy;
    m.px = px;
    m.cov = noise * noise * N.inverse();
    m.cov.diagonal().array() += opt_.sigma_floor_px * opt_.sigma_floor_px;
    m.size_px = 2 * half_ + 1;
    m.score = 1.0;
    m.ok = m.cov.allFinite() && m.cov.determinant() > 0;
    if (!m.ok) m.why = "no texture to correlate";
    return m;
  }

  PointMeasurement Measure(const cv::Mat& frame, const Eigen::Vector2d& predicted, double search_px) override {
    PointMeasurement m;
    if (anchor_.empty()) {
      m.why = "not seeded";
      return m;
    }
    WarpTemplate();
    const int h = templ_.cols / 2, S = std::max(1, static_cast<int>(std::ceil(search_px)));
    const int ix = static_cast<int>(std::lround(predicted.x())), iy = static_cast<int>(std::lround(predicted.y()));
    // The fit samples the anchor's corners too: √2 · half · scale from the centre, plus the search.
    const double scale = std::max(1.0, A_.norm() / std::sqrt(2.0));
    const int pad = static_cast<int>(std::ceil(1.45 * half_ * scale)) + S + 4;
    const cv::Rect want(ix - pad, iy - pad, 2 * pad + 1, 2 * pad + 1);
    if (!CopyFloatRoi(frame, want, &roi_)) {
      m.why = "at the image border";
      return m;
    }
    cv::GaussianBlur(roi_, roi_, cv::Size(0, 0), kPrefilterSigmaPx, kPrefilterSigmaPx, cv::BORDER_REPLICATE);
    const cv::Rect inner(pad - h - S, pad - h - S, 2 * (h + S) + 1, 2 * (h + S) + 1);
    cv::matchTemplate(roi_(inner), templ_, map_, cv::TM_CCOEFF_NORMED);
    const cv::Point tl_inner = want.tl() + inner.tl();
    // The template's centre is the anchor's centre pixel; the seed point is A·(−offset) from it.
    const Eigen::Vector2d centre_pred = predicted + A_ * offset_;
    const NccPeak peak = NearestNearBestPeak(map_, tl_inner, h, h, centre_pred, 0.05, opt_.ncc_min, 0.0);
    if (!peak.found) {
      m.score = std::max(0.0, peak.best);
      m.why = "low correlation";
      return m;
    }
    return Fit(want.tl(), peak.sub - A_ * offset_);
  }

  std::vector<PointCandidate> Candidates(const cv::Mat& frame, const Eigen::Vector2d& center, double search_px,
                                         int max_n) override {
    WarpTemplate();
    std::vector<PointCandidate> c = TemplatePeaks(frame, templ_, center + A_ * offset_, search_px, max_n,
                                                  opt_.ncc_min, half_);
    for (PointCandidate& p : c) p.px -= A_ * offset_;
    return c;
  }

  void Accept(const PointMeasurement&) override {
    A_ = accepted_A_ = fit_A_;
    gain_ = fit_gain_;
    offs_ = fit_offs_;
  }
  void PredictChange(const Eigen::Matrix2d& L) override { A_ = L * accepted_A_; }
  int SupportHalfPx() const override {
    return static_cast<int>(std::ceil(half_ * std::max(1.0, accepted_A_.norm() / std::sqrt(2.0)))) + 2;
  }

 private:
  // The anchor warped by A about its centre (the coarse search's template).
  void WarpTemplate() {
    const double scale = std::max(1.0, A_.norm() / std::sqrt(2.0));
    const int h = static_cast<int>(std::ceil(half_ * scale));
    const Eigen::Matrix2d Ai = A_.inverse();
    cv::Mat M = (cv::Mat_<double>(2, 3) << Ai(0, 0), Ai(0, 1), half_ - Ai(0, 0) * h - Ai(0, 1) * h, Ai(1, 0),
                 Ai(1, 1), half_ - Ai(1, 0) * h - Ai(1, 1) * h);
    cv::warpAffine(anchor_, templ_, M, cv::Size(2 * h + 1, 2 * h + 1), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                   cv::BORDER_REPLICATE);
  }

  PointMeasurement Fit(const cv::Point& tl, const Eigen::Vector2d& start);

  PointMeasureOptions opt_;
  int half_ = 10;
  cv::Mat anchor_, raw_, templ_, roi_, map_;
  double anchor_noise_ = 1.0;  // pixel noise σ (DN) of the seed frame
  JacobianCols jac_;
  Eigen::Vector2d offset_{0, 0};  // anchor centre pixel − seed position
  // A_: the warp searched with (the last accepted, or that times the group's change while hidden).
  Eigen::Matrix2d A_ = Eigen::Matrix2d::Identity(), fit_A_ = Eigen::Matrix2d::Identity(),
                  accepted_A_ = Eigen::Matrix2d::Identity();
  double gain_ = 1.0, offs_ = 0.0, fit_gain_ = 1.0, fit_offs_ = 0.0;
};

PointMeasurement CorrelationMeasurer::Fit(const cv::Point& tl, const Eigen::Vector2d& start) {
  PointMeasurement m;
  const LsmModel model(roi_, tl, anchor_, offset_);
  Vec8c th;
  th << start.x(), start.y(), A_(0, 0), A_(0, 1), A_(1, 0), A_(1, 1), gain_, offs_;
  struct Lm {
    const LsmModel& f;
    Vec8c th, cand;
    bool TryStep(const Vec8c& step, double* cost) {
      cand = th + step;
      *cost = f(cand, nullptr, nullptr);
      return *cost >= 0.0;
    }
    void Accept() { th = cand; }
    bool Linearize(Mat8c* H, Vec8c* g) { return f(th, H, g) >= 0.0; }
    // Converged when the point moves by less than 1e-4 px (far below its σ) and the warp by less than 1e-5.
    bool Converged(const Vec8c& step, double, double) const {
      return step.head<2>().norm() < 1e-4 && step.segment<4>(2).norm() < 1e-5;
    }
  } lm{model, th, th};
  Mat8c H;
  Vec8c g;
  const double cost0 = model(th, &H, &g);
  if (cost0 < 0) {
    m.why = "at the window border";
    return m;
  }
  // A gain and offset start from the anchor's and the image's levels.
  const numeric::LmDamping damping{.initial = 1e-4, .diagonal_floor = 1e-12, .increase = 10.0, .decrease = 0.2,
                                   .min = 1e-10, .max_tries = 8, .accept_equal_cost = false};
  const numeric::LmSummary s = numeric::LevenbergMarquardt<8>(lm, cost0, damping, opt_.max_iterations, &H, &g);
  th = lm.th;
  double ncc = 0;
  const double sse = model(th, nullptr, nullptr, &ncc);
  const bool converged = s.status == numeric::LmStatus::kConverged || s.status == numeric::LmStatus::kNonFiniteStep;
  // Covariance: white pixel noise of the frame and of the anchor (gain-scaled) through the prefilter:
  // H⁻¹ (B J)ᵀ (B J) H⁻¹ σ², B the blur, J the Jacobian at the solution.
  jac_.resize(static_cast<Eigen::Index>(anchor_.total()), 8);
  model(th, nullptr, nullptr, nullptr, &jac_);
  const Mat8c JtJ = jac_.transpose() * jac_;  // of the blurred columns
  const Mat8c Hi = H.ldlt().solve(Mat8c::Identity());
  // The pixel noise (frame, and anchor scaled by the gain, and what the model misses) from the residuals:
  // white noise of variance σ² leaves σ² Σw² per pixel after the prefilter of weights w.
  const double var = sse / (std::max<double>(1.0, static_cast<double>(anchor_.total()) - 8.0) * PrefilterGain());
  const Mat8c cov = var * Hi * JtJ * Hi;
  m.px = th.head<2>();
  m.cov = cov.topLeftCorner<2, 2>();
  m.cov.diagonal().array() += opt_.sigma_floor_px * opt_.sigma_floor_px;
  m.score = std::max(0.0, ncc);
  Eigen::Matrix2d A;
  A << th(2), th(3), th(4), th(5);
  m.size_px = (2 * half_ + 1) * std::sqrt(std::abs(A.determinant()));
  fit_A_ = A;
  fit_gain_ = th(6);
  fit_offs_ = th(7);
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(A);
  const double smax = svd.singularValues()(0), smin = svd.singularValues()(1);
  const double det_ratio = A.determinant() / A_.determinant();
  if (sse < 0 || !converged) {
    m.px = start;
    m.why = sse < 0 ? "at the window border" : "fit did not converge";
  } else if (!(smin > 0.2) || smax > 5.0 * smin || det_ratio < 0.8 || det_ratio > 1.25 || th(6) <= 0) {
    m.why = "implausible warp";
  } else if ((m.px - start).norm() > 0.5 * half_ || !cov.allFinite() || !(m.cov.determinant() > 0)) {
    m.why = "fit left its window";
  } else if (m.score < opt_.ncc_min) {
    m.why = "low correlation";
  } else {
    m.ok = true;
  }
  return m;
}

}  // namespace

std::unique_ptr<PointMeasurer> MakeCorrelationMeasurer(std::optional<double> size_px, const PointMeasureOptions& o) {
  return std::make_unique<CorrelationMeasurer>(size_px, o);
}

}  // namespace rk::extract

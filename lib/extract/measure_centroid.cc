// The centroid measurer (centroid-bright, centroid-dark); method in point_measure.h.
#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string_view>

#include "extract/point_measurers.h"

namespace rk::extract {
namespace {

constexpr double kCentroidBackgroundSigmas = 3.5;  // background pixels further off the plane are left out
constexpr double kMinNoiseDn = 0.3;                // as WindowNoise's floor (quantisation)
constexpr double kMinVarShare = 0.25;              // a dark pixel's variance stays above this share of the background's

class CentroidMeasurer final : public PointMeasurer {
 public:
  CentroidMeasurer(bool dark, std::optional<double> size_px, const PointMeasureOptions& o)
      : opt_(o), dark_(dark), size_(size_px.value_or(0.0)) {}

  PointMeasurement Seed(const cv::Mat& frame, const Eigen::Vector2d& px, double search_px) override {
    area0_ = 0;
    const bool given = size_ > 0;
    if (!given) size_ = 8.0;  // first look; the blob found sets it
    PointMeasurement m = Measure(frame, px, search_px);
    for (int k = 0; k < 4 && !given && !m.ok && std::string_view(m.why) == "blob cut by the window"; ++k) {
      size_ *= 2;  // a larger blob than the first look
      m = Measure(frame, px, search_px);
    }
    if (m.ok) size_ = std::max(2.0, m.size_px);
    return m;
  }

  PointMeasurement Measure(const cv::Mat& frame, const Eigen::Vector2d& predicted, double search_px) override {
    PointMeasurement m;
    const int S = std::max(1, static_cast<int>(std::ceil(search_px)));
    const int w = static_cast<int>(std::ceil(size_)) + 3 + S;
    const int ix = static_cast<int>(std::lround(predicted.x())), iy = static_cast<int>(std::lround(predicted.y()));
    // The window, cut to the frame (a point near the border is still measured if its support fits).
    const cv::Rect want = cv::Rect(ix - w, iy - w, 2 * w + 1, 2 * w + 1) & cv::Rect(0, 0, frame.cols, frame.rows);
    if (!CopyFloatRoi(frame, want, &roi_)) {
      m.why = "at the image border";
      return m;
    }
    if (dark_) roi_ = -roi_;  // the blob is bright in roi_ from here on
    double eta = 0;
    const double thr = OtsuThreshold(roi_, &eta);
    m.score = eta;
    mask_ = roi_ > thr;
    cv::Mat labels, stats, cents;
    const int n = cv::connectedComponentsWithStats(mask_, labels, stats, cents, 8, CV_32S);
    const Eigen::Vector2d p(predicted.x() - want.x, predicted.y() - want.y);
    int pick = -1;
    double best = 1e300;
    for (int i = 1; i < n; ++i) {
      if (stats.at<int>(i, cv::CC_STAT_AREA) < 2) continue;
      const double d2 = (Eigen::Vector2d(cents.at<double>(i, 0), cents.at<double>(i, 1)) - p).squaredNorm();
      if (d2 < best) {
        best = d2;
        pick = i;
      }
    }
    if (pick < 0) {
      m.why = "no blob";
      return m;
    }
    PointMeasurement c = Centroid(labels, stats, pick, want.tl(), predicted, search_px);
    c.score = eta;
    return c;
  }

  std::vector<PointCandidate> Candidates(const cv::Mat& frame, const Eigen::Vector2d& center, double search_px,
                                         int max_n) override;

  void Accept(const PointMeasurement& m) override {
    if (area0_ <= 0) {
      area0_ = last_area_;
      flux0_ = last_flux_;
    }
    size_ = std::max(2.0, 0.8 * size_ + 0.2 * m.size_px);
  }
  int SupportHalfPx() const override { return static_cast<int>(std::ceil(size_)) + 3; }
  void SetShotNoise(double dn2_per_dn) override { shot_slope_ = dn2_per_dn; }

 private:
  PointMeasurement Centroid(const cv::Mat& labels, const cv::Mat& stats, int pick, const cv::Point& tl,
                            const Eigen::Vector2d& predicted, double search_px);

  PointMeasureOptions opt_;
  bool dark_;
  double size_;
  double area0_ = 0, flux0_ = 0, last_area_ = 0, last_flux_ = 0;
  double shot_slope_ = 0.0;  // DN² per DN (ShotNoiseSlope of the recording)
  cv::Mat roi_, mask_, blob_;
};

PointMeasurement CentroidMeasurer::Centroid(const cv::Mat& labels, const cv::Mat& stats, int pick, const cv::Point& tl,
                                            const Eigen::Vector2d& predicted, double search_px) {
  PointMeasurement m;
  const int bx = stats.at<int>(pick, cv::CC_STAT_LEFT), by = stats.at<int>(pick, cv::CC_STAT_TOP);
  const int bw = stats.at<int>(pick, cv::CC_STAT_WIDTH), bh = stats.at<int>(pick, cv::CC_STAT_HEIGHT);
  if (bx <= 2 || by <= 2 || bx + bw >= roi_.cols - 2 || by + bh >= roi_.rows - 2) {
    m.why = "blob cut by the window";
    return m;
  }
  blob_ = labels == pick;
  cv::dilate(blob_, blob_, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
  // Background: a plane fitted to the window's pixels outside every blob (dilated), so that a sky gradient
  // does not pull the centroid (a constant level biased it by 0.02 px on rk-sim's dark spot); then again
  // without the pixels more than 3.5 σ off it.
  cv::Mat any;
  cv::dilate(mask_, any, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
  const double noise = WindowNoise(roi_);
  const double xc = 0.5 * (roi_.cols - 1), yc = 0.5 * (roi_.rows - 1);
  Eigen::Vector3d plane = Eigen::Vector3d::Zero();
  double n_bg = 0, thr = 0, bg_noise = noise;
  std::vector<double> res;
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    double n = 0;
    for (int y = 0; y < roi_.rows; ++y)
      for (int x = 0; x < roi_.cols; ++x) {
        if (any.at<std::uint8_t>(y, x)) continue;
        const Eigen::Vector3d j(1.0, x - xc, y - yc);
        const double v = roi_.at<float>(y, x);
        if (pass > 0 && std::abs(v - plane.dot(j)) > thr) continue;
        A += j * j.transpose();
        r += j * v;
        n += 1;
      }
    if (n < 8) {
      if (pass == 0) {
        m.why = "no background in the window";
        return m;
      }
      break;  // keep the first pass's plane
    }
    plane = A.ldlt().solve(r);
    n_bg = n;
    // The second pass leaves out pixels beyond 3.5 robust σ of the residuals (at least the pixel noise).
    res.clear();
    for (int y = 0; y < roi_.rows; ++y)
      for (int x = 0; x < roi_.cols; ++x)
        if (!any.at<std::uint8_t>(y, x)) {
          res.push_back(std::abs(roi_.at<float>(y, x) - plane.dot(Eigen::Vector3d(1.0, x - xc, y - yc))));
        }
    std::nth_element(res.begin(), res.begin() + static_cast<std::ptrdiff_t>(res.size() / 2), res.end());
    bg_noise = std::max(1.4826 * res[res.size() / 2], kMinNoiseDn);
    thr = kCentroidBackgroundSigmas * std::max(noise, bg_noise);
  }
  const auto b_at = [&](int x, int y) { return plane(0) + plane(1) * (x - xc) + plane(2) * (y - yc); };
  // The pixel noise for σ: the background's scatter about its plane (robust), not the window's neighbour
  // differences, which the blob's own edges inflate (σ 1.5× too large on rk-sim's dark spot).
  const double pixel_noise = bg_noise;
  const double sigma_b = pixel_noise / std::sqrt(n_bg);
  double W = 0, sx = 0, sy = 0, area = 0;
  for (int y = 0; y < roi_.rows; ++y)
    for (int x = 0; x < roi_.cols; ++x) {
      if (!blob_.at<std::uint8_t>(y, x)) continue;
      const double wv = std::max(roi_.at<float>(y, x) - b_at(x, y), 0.0);
      W += wv;
      sx += wv * x;
      sy += wv * y;
      area += 1;
    }
  if (!(W > 0)) {
    m.why = "no blob";
    return m;
  }
  const Eigen::Vector2d c(sx / W, sy / W);
  // Propagated noise: each pixel's variance — the background's, plus the recording's shot noise for its
  // difference from the background (more for a bright spot, less for a dark one) — and the background's error
  // shared by all pixels.
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
  Eigen::Vector2d s1 = Eigen::Vector2d::Zero();
  double peak = 0;
  const double bg_var = pixel_noise * pixel_noise;
  for (int y = 0; y < roi_.rows; ++y)
    for (int x = 0; x < roi_.cols; ++x) {
      if (!blob_.at<std::uint8_t>(y, x)) continue;
      const Eigen::Vector2d d(x - c.x(), y - c.y());
      const double excess = roi_.at<float>(y, x) - b_at(x, y);  // in the frame's own sense: −(I − b) when dark
      const double var = std::max(bg_var + shot_slope_ * (dark_ ? -excess : excess), kMinVarShare * bg_var);
      C += var * d * d.transpose();
      s1 += d;
      peak = std::max(peak, excess);
    }
  m.cov = (C + sigma_b * sigma_b * s1 * s1.transpose()) / (W * W);
  m.cov.diagonal().array() += opt_.sigma_floor_px * opt_.sigma_floor_px;
  m.px = c + Eigen::Vector2d(tl.x, tl.y);
  m.size_px = 2.0 * std::sqrt(static_cast<double>(stats.at<int>(pick, cv::CC_STAT_AREA)) / M_PI);
  last_area_ = area;
  last_flux_ = W;
  if (!(peak >= opt_.min_contrast_sigmas * noise)) {
    m.why = "too faint";
  } else if ((m.px - predicted).norm() > search_px + 0.5 * size_ + 1) {
    m.why = "blob outside the search window";
  } else if (area0_ > 0 && (area > 3 * area0_ || 3 * area < area0_ || W > 3 * flux0_ || 3 * W < flux0_)) {
    m.why = "wrong size";
  } else {
    m.ok = true;
  }
  return m;
}

std::vector<PointCandidate> CentroidMeasurer::Candidates(const cv::Mat& frame, const Eigen::Vector2d& center,
                                                         double search_px, int max_n) {
  std::vector<PointCandidate> out;
  const int S = std::max(1, static_cast<int>(std::ceil(search_px)));
  const int cx = static_cast<int>(std::lround(center.x())), cy = static_cast<int>(std::lround(center.y()));
  const cv::Rect region = cv::Rect(cx - S, cy - S, 2 * S + 1, 2 * S + 1) & cv::Rect(0, 0, frame.cols, frame.rows);
  cv::Mat roi;
  if (!CopyFloatRoi(frame, region, &roi)) return out;
  if (dark_) roi = -roi;
  double eta = 0;
  const double thr = OtsuThreshold(roi, &eta);
  cv::Mat labels, stats, cents;
  const int n = cv::connectedComponentsWithStats(roi > thr, labels, stats, cents, 8, CV_32S);
  const double want = area0_ > 0 ? area0_ : M_PI * 0.25 * size_ * size_;
  for (int i = 1; i < n; ++i) {
    const double a = stats.at<int>(i, cv::CC_STAT_AREA);
    if (a < 2 || a > 4 * want + 10) continue;
    const double score = std::min(a, want) / std::max(a, want);
    out.push_back({Eigen::Vector2d(region.x + cents.at<double>(i, 0), region.y + cents.at<double>(i, 1)), score});
  }
  std::sort(out.begin(), out.end(), [](const PointCandidate& a, const PointCandidate& b) { return a.score > b.score; });
  if (static_cast<int>(out.size()) > max_n) out.resize(static_cast<std::size_t>(max_n));
  return out;
}

}  // namespace

std::unique_ptr<PointMeasurer> MakeCentroidMeasurer(bool dark, std::optional<double> size_px,
                                                    const PointMeasureOptions& o) {
  return std::make_unique<CentroidMeasurer>(dark, size_px, o);
}

}  // namespace rk::extract

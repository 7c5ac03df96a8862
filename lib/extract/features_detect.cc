// Marker detection and least-squares correlation; model in features_detect.h.
#include "extract/features_detect.h"

#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "extract/disk_model.h"
#include "extract/ncc_search.h"
#include "numeric/levenberg_marquardt.h"
#include "numeric/robust_stats.h"

namespace rk::extract {
namespace {

constexpr double kInvSqrt2 = kDiskInvSqrt2;

using Vec8 = DiskModel::Vec8;
using Mat8 = DiskModel::Mat8;

// The fit's start: the background from the median of the window's border, the amplitude from the centre pixel.
Vec8 StartParameters(const cv::Mat& image, const Eigen::Vector2d& start, int x0, int y0, int half, double radius_px,
                     double edge_px) {
  // Background start: median of the window's border.
  std::vector<double> ring;
  for (int k = -half; k <= half; ++k) {
    ring.push_back(image.at<float>(y0 - half, x0 + k));
    ring.push_back(image.at<float>(y0 + half, x0 + k));
    ring.push_back(image.at<float>(y0 + k, x0 - half));
    ring.push_back(image.at<float>(y0 + k, x0 + half));
  }
  const double b_start = numeric::UpperMedianInPlace(ring);
  // θ = (cx, cy, ρ, s, a, b0, bx, by); the plane is about (x0, y0).
  Vec8 th;
  const double phi0 = 0.5 * std::erfc(-radius_px / std::max(edge_px, 0.3) * kInvSqrt2);
  th << start.x(), start.y(), radius_px, std::max(edge_px, 0.5),
      (image.at<float>(static_cast<int>(std::lround(start.y())), static_cast<int>(std::lround(start.x()))) -
       b_start) / std::max(phi0, 0.05),
      b_start, 0.0, 0.0;
  return th;
}

}  // namespace

const io::OptionTable<MarkerDetectOptions>& MarkerDetectOptions::Table() {
  using B = io::Bounds;
  using O = MarkerDetectOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Choice("--polarity", &O::dark, {{false, "bright"}, {true, "dark"}},
                  "Markers brighter (bright) or darker (dark) than their surroundings")
          .Real("--min-radius-px", &O::min_radius_px, "px", B::Closed(0, 500), "Smallest marker image radius (px)")
          .Real("--max-radius-px", &O::max_radius_px, "px", B::LeftOpen(0, 500), "Largest marker image radius (px)")
          .Integer("--downsample", &O::downsample, "", B::Closed(1, 8),
                   "Full-frame detection on frames averaged down by this (1..8)")
          .Real("--k-detect", &O::k_detect, "", B::Positive(), "Detection threshold in noise sigmas (full-frame search)")
          .Real("--min-contrast", &O::min_contrast_dn, "dn", B::AtLeast(0),
                "Smallest marker contrast accepted (DN); 0 = 5 noise sigmas")
          .Real("--ncc-min", &O::ncc_min, "", B::Open(-1, 1), "Correlation score needed to accept a marker")
          .Integer("--max-candidates", &O::max_candidates, "", B::Closed(4, 1000),
                   "Full-frame search keeps this many strongest blobs");
  return table;
}

bool MarkerDetectOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  auto fail = [&](const char* w) {
    *why = w;
    return false;
  };
  if (!(max_radius_px > min_radius_px)) return fail("--max-radius-px must be > --min-radius-px");
  if (max_iterations < 1) return fail("fit iterations must be >= 1");
  if (!(sigma_floor_px >= 0.0)) return fail("sigma floor must be >= 0");
  return true;
}

MarkerDetector::MarkerDetector(const MarkerDetectOptions& opt) : opt_(opt) {}

void MarkerDetector::SetFrame(const cv::Mat& frame) {
  CV_Assert(frame.type() == CV_8UC1 || frame.type() == CV_16UC1);
  frame.convertTo(image_, CV_32F);
  if (opt_.dark) {
    const double full = frame.depth() == CV_16U ? 65535.0 : 255.0;
    image_ = full - image_;
  }
  // Level: median of a sparse grid; noise: MAD of horizontal neighbour differences / √2
  // (insensitive to the smooth background, the body and the few marker pixels).
  std::vector<double> lv, dv;
  const int stride = 16;
  for (int y = stride / 2; y < image_.rows; y += stride) {
    const float* row = image_.ptr<float>(y);
    for (int x = stride / 2; x + 1 < image_.cols; x += stride) {
      lv.push_back(row[x]);
      dv.push_back(row[x + 1] - row[x]);
    }
  }
  level_dn_ = numeric::UpperMedianInPlace(lv);
  noise_dn_ = std::max(1.4826 * numeric::UpperMedianAndMadInPlace(dv).mad / std::sqrt(2.0), 0.3);
}

void MarkerDetector::MakeTemplate(double radius_px, double edge_px, int half) {
  templ_.create(2 * half + 1, 2 * half + 1, CV_32FC1);
  const double k = kInvSqrt2 / edge_px;
  for (int y = -half; y <= half; ++y) {
    float* row = templ_.ptr<float>(y + half);
    for (int x = -half; x <= half; ++x) {
      row[x + half] = static_cast<float>(0.5 * std::erfc((std::hypot(x, y) - radius_px) * k));
    }
  }
}

MarkerMeasurement MarkerDetector::Measure(const Eigen::Vector2d& predicted, double search_px, double radius_px,
                                          double edge_px) {
  MarkerMeasurement m;
  radius_px = std::clamp(radius_px, 0.0, opt_.max_radius_px);
  edge_px = std::clamp(edge_px, 0.5, 10.0);
  const int half = static_cast<int>(std::ceil(radius_px + 3.0 * edge_px + 2.0));
  const int S = std::max(1, static_cast<int>(std::ceil(search_px)));
  const int ix = static_cast<int>(std::lround(predicted.x())), iy = static_cast<int>(std::lround(predicted.y()));
  const cv::Rect want(ix - half - S, iy - half - S, 2 * (half + S) + 1, 2 * (half + S) + 1);
  const cv::Rect region = want & cv::Rect(0, 0, image_.cols, image_.rows);
  if (region.width < 2 * half + 2 || region.height < 2 * half + 2) {
    m.why = "at the image border";
    return m;
  }
  MakeTemplate(radius_px, edge_px, half);
  cv::matchTemplate(image_(region), templ_, ncc_map_, cv::TM_CCOEFF_NORMED);
  const NccPeak peak = NearestNearBestPeak(ncc_map_, region.tl(), half, half, predicted, 0.05, opt_.ncc_min, 0.0);
  if (!peak.found) {
    m.ncc = peak.best;
    m.why = "low correlation";
    return m;
  }
  return Fit(peak.px, radius_px, edge_px, peak.score);
}

MarkerMeasurement MarkerDetector::Fit(const Eigen::Vector2d& start, double radius_px, double edge_px, double ncc) {
  MarkerMeasurement m;
  m.ncc = ncc;
  const int half = static_cast<int>(std::ceil(radius_px + 3.0 * edge_px + 3.0));
  const int x0 = static_cast<int>(std::lround(start.x())), y0 = static_cast<int>(std::lround(start.y()));
  if (x0 - half < 0 || y0 - half < 0 || x0 + half >= image_.cols || y0 + half >= image_.rows) {
    m.why = "at the image border";
    return m;
  }
  Vec8 th = StartParameters(image_, start, x0, y0, half, radius_px, edge_px);
  const DiskModel eval(image_, x0, y0, half);

  // Levenberg–Marquardt; the radius stays >= 0 and the edge width in [0.3, 10] px. Converged: no step
  // lowers the SSE, or the centre moves by less than 1e-5 px.
  struct MarkerLm {
    const DiskModel& evaluate;
    Vec8 th, cand;
    bool TryStep(const Vec8& step, double* cost) {
      cand = th + step;
      cand(2) = std::max(cand(2), 0.0);
      cand(3) = std::clamp(cand(3), 0.3, 10.0);
      *cost = evaluate(cand, nullptr, nullptr);
      return true;
    }
    void Accept() { th = cand; }
    bool Linearize(Mat8* H, Vec8* g) {
      evaluate(th, H, g);
      return true;
    }
    bool Converged(const Vec8& step, double, double) const { return step.head<2>().norm() < 1e-5; }
  } fit{eval, th, th};
  Mat8 H;
  Vec8 g;
  const numeric::LmDamping damping{.initial = 1e-3, .diagonal_floor = 1e-12, .increase = 10.0,
                                   .decrease = 0.2, .min = 1e-9, .max_tries = 8, .accept_equal_cost = false};
  const numeric::LmSummary lm =
      numeric::LevenbergMarquardt<8>(fit, eval(th, &H, &g), damping, opt_.max_iterations, &H, &g);
  th = fit.th;
  const double sse = lm.cost;
  // A non-finite step means no step is left: converged at the current point.
  const bool converged =
      lm.status == numeric::LmStatus::kConverged || lm.status == numeric::LmStatus::kNonFiniteStep;
  m.iterations = lm.iterations - (converged ? 1 : 0);  // iterations before the one that stopped
  const int npx = (2 * half + 1) * (2 * half + 1);
  const double var = sse / std::max(1, npx - 8);
  m.rms_dn = std::sqrt(var);
  m.px = th.head<2>();
  m.radius_px = th(2);
  m.edge_px = th(3);
  m.amplitude_dn = th(4);
  const Mat8 cov = var * H.ldlt().solve(Mat8::Identity());
  const double s2 = 0.5 * (cov(0, 0) + cov(1, 1));
  m.sigma_px = std::sqrt(std::max(s2, 0.0) + opt_.sigma_floor_px * opt_.sigma_floor_px);
  const double min_a = opt_.min_contrast_dn > 0 ? opt_.min_contrast_dn : 5.0 * noise_dn_;
  if (!converged) {
    m.why = "fit did not converge";
  } else if (!(m.amplitude_dn >= min_a)) {
    m.why = "too faint";
  } else if (m.radius_px > 1.5 * opt_.max_radius_px || m.radius_px + m.edge_px < 0.5 * opt_.min_radius_px) {
    m.why = "wrong size";
  } else if ((m.px - start).norm() > 0.5 * half || !cov.allFinite() || !(s2 >= 0)) {
    m.why = "fit left its window";
  } else {
    m.ok = true;
  }
  return m;
}

std::vector<MarkerMeasurement> MarkerDetector::DetectAll() {
  std::vector<MarkerMeasurement> out;
  const int D = opt_.downsample;
  cv::Mat small;
  if (D > 1) {
    cv::resize(image_, small, cv::Size(image_.cols / D, image_.rows / D), 0, 0, cv::INTER_AREA);
  } else {
    small = image_;
  }
  const int k = 2 * static_cast<int>(std::ceil(opt_.max_radius_px / D)) + 3;
  cv::Mat opened, tophat;
  cv::morphologyEx(small, opened, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k)));
  tophat = small - opened;
  // Threshold from the top-hat's own noise.
  std::vector<double> s;
  for (int y = 2; y < tophat.rows; y += 4) {
    for (int x = 2; x < tophat.cols; x += 4) s.push_back(tophat.at<float>(y, x));
  }
  const numeric::MedianMad background = numeric::UpperMedianAndMadInPlace(s);
  const double med = background.median;
  const double sig = std::max(1.4826 * background.mad, noise_dn_ / D * 0.5);
  cv::Mat mask = tophat > (med + opt_.k_detect * sig);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  struct Blob {
    double flux;
    Eigen::Vector2d c;
    double radius;
  };
  std::vector<Blob> blobs;
  const double max_area = M_PI * std::pow(opt_.max_radius_px / D + 1.5, 2);
  const double thr = med + opt_.k_detect * sig;
  // Each component is thresholded again at half its own peak: a blurred disc's half-peak
  // contour is its edge (so the area gives the radius), and a marker fused with a remnant of
  // the body outline or with a touching marker splits into its bright cores. The cores must be
  // marker-shaped (compact, not too large).
  auto marker_shaped = [&](int area, int w, int h) {
    if (area > max_area || std::max(w, h) > 3 * std::min(w, h) + 1) return false;
    return area <= 4 || static_cast<double>(area) / (w * h) >= 0.5;  // a disc fills π/4 of its box
  };
  auto add_blob = [&](const cv::Mat& lab, int id, const cv::Rect& box, int area) {
    double flux = 0, sx = 0, sy = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      for (int x = box.x; x < box.x + box.width; ++x) {
        if (lab.at<int>(y - box.y, x - box.x) != id) continue;
        const double v = tophat.at<float>(y, x);
        flux += v;
        sx += v * x;
        sy += v * y;
      }
    }
    if (!(flux > 0)) return;
    Blob b;
    b.flux = flux;
    b.c = Eigen::Vector2d((sx / flux + 0.5) * D - 0.5, (sy / flux + 0.5) * D - 0.5);
    b.radius = std::max(opt_.min_radius_px, std::sqrt(area / M_PI) * D);
    blobs.push_back(b);
  };
  for (int i = 1; i < n; ++i) {
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    const int w = stats.at<int>(i, cv::CC_STAT_WIDTH), h = stats.at<int>(i, cv::CC_STAT_HEIGHT);
    const cv::Rect box(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP), w, h);
    if (area > 16 * max_area) continue;  // a large bright object (sun glint, the body in poor light)
    double peak = thr;
    for (int y = box.y; y < box.y + h; ++y) {
      for (int x = box.x; x < box.x + w; ++x) {
        if (labels.at<int>(y, x) == i) peak = std::max(peak, static_cast<double>(tophat.at<float>(y, x)));
      }
    }
    const double thr2 = med + 0.5 * (peak - med);
    cv::Mat sub = (tophat(box) > thr2) & (labels(box) == i);
    cv::Mat sl, ss, sc;
    const int m2 = cv::connectedComponentsWithStats(sub, sl, ss, sc, 8, CV_32S);
    for (int j = 1; j < m2; ++j) {
      const int a2 = ss.at<int>(j, cv::CC_STAT_AREA);
      const int w2 = ss.at<int>(j, cv::CC_STAT_WIDTH), h2 = ss.at<int>(j, cv::CC_STAT_HEIGHT);
      if (!marker_shaped(a2, w2, h2)) continue;
      add_blob(sl, j, box, a2);
    }
  }
  std::sort(blobs.begin(), blobs.end(), [](const Blob& a, const Blob& b) { return a.flux > b.flux; });
  if (blobs.size() > static_cast<std::size_t>(opt_.max_candidates)) blobs.resize(static_cast<std::size_t>(opt_.max_candidates));
  for (const Blob& b : blobs) {
    MarkerMeasurement m = Measure(b.c, D + 2.0, b.radius, 1.0);
    if (!m.ok) continue;
    bool dup = false;
    for (auto& o : out) {
      if ((o.px - m.px).norm() < std::max(2.0, 0.5 * std::max(o.radius_px, m.radius_px))) {
        dup = true;
        if (m.ncc > o.ncc) o = m;
        break;
      }
    }
    if (!dup) out.push_back(m);
  }
  return out;
}

}  // namespace rk::extract

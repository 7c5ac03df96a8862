// Shared parts of the point measurers; see point_measure.h.
#include "extract/point_measure.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>

#include "extract/ncc_search.h"
#include "extract/point_measurers.h"
#include "numeric/robust_stats.h"

namespace rk::extract {

std::unique_ptr<PointMeasurer> MakePointMeasurer(formats::PointMethod method, std::optional<double> size_px,
                                                 const PointMeasureOptions& options) {
  switch (method) {
    case formats::PointMethod::kCorrelation: return MakeCorrelationMeasurer(size_px, options);
    case formats::PointMethod::kCentroidDark: return MakeCentroidMeasurer(true, size_px, options);
    case formats::PointMethod::kCentroidBright: return MakeCentroidMeasurer(false, size_px, options);
    case formats::PointMethod::kQuadrant: return MakeQuadrantMeasurer(size_px, options);
    case formats::PointMethod::kCircle: return MakeCircleMeasurer(size_px, options);
  }
  return nullptr;
}

bool CopyFloatRoi(const cv::Mat& frame, const cv::Rect& rect, cv::Mat* roi) {
  if (rect.x < 0 || rect.y < 0 || rect.width <= 0 || rect.height <= 0 || rect.x + rect.width > frame.cols ||
      rect.y + rect.height > frame.rows) {
    return false;
  }
  frame(rect).convertTo(*roi, CV_32F);
  return true;
}

double WindowNoise(const cv::Mat& roi) {
  std::vector<double> d;
  d.reserve(static_cast<std::size_t>(roi.rows) * static_cast<std::size_t>(roi.cols));
  for (int y = 0; y < roi.rows; ++y) {
    const float* r = roi.ptr<float>(y);
    for (int x = 0; x + 1 < roi.cols; ++x) d.push_back(static_cast<double>(r[x + 1]) - r[x]);
  }
  if (d.size() < 8) return 1.0;
  return std::max(1.4826 * numeric::UpperMedianAndMadInPlace(d).mad / std::sqrt(2.0), 0.3);
}

double ShotNoiseSlope(const cv::Mat& frame) {
  constexpr int kBins = 32;
  constexpr double kMaxPairs = 300000;  // rows sampled so that a 5-megapixel frame costs what 640×480 does
  constexpr std::size_t kMinPairs = 500;
  constexpr double kClipMargin = 0.02;
  if (frame.empty() || frame.channels() != 1 || frame.cols < 2) return -1.0;
  const int row_step = std::max(4, static_cast<int>(std::ceil(static_cast<double>(frame.rows) * frame.cols / kMaxPairs)));
  double lo = 0, hi = 0;
  cv::minMaxLoc(frame, &lo, &hi);
  if (!(hi > lo)) return -1.0;
  std::vector<std::vector<double>> diffs(kBins);
  cv::Mat row;
  for (int y = 0; y < frame.rows; y += row_step) {
    frame.row(y).convertTo(row, CV_32F);
    const float* r = row.ptr<float>(0);
    for (int x = 0; x + 1 < frame.cols; ++x) {
      const double level = 0.5 * (static_cast<double>(r[x]) + r[x + 1]);
      const double u = (level - lo) / (hi - lo);
      if (u < kClipMargin || u > 1.0 - kClipMargin) continue;
      diffs[static_cast<std::size_t>(std::min(kBins - 1, static_cast<int>(u * kBins)))].push_back(static_cast<double>(r[x + 1]) - r[x]);
    }
  }
  // Weighted least squares of var = a + slope · level over the bins.
  double sw = 0, sl = 0, sv = 0, sll = 0, slv = 0;
  int bins = 0;
  double lmin = 1e300, lmax = -1e300;
  for (int b = 0; b < kBins; ++b) {
    std::vector<double>& d = diffs[static_cast<std::size_t>(b)];
    if (d.size() < kMinPairs) continue;
    // The variance of the differences about their median, within 4 robust σ of it (edges left out). Not the MAD
    // itself: on integer samples it moves in steps of half a DN, which biased the slope by half again.
    const numeric::MedianMad mm = numeric::UpperMedianAndMadInPlace(d);  // d now holds |d − median|
    const double cut = 4.0 * std::max(1.4826 * mm.mad, 0.5);
    double s2 = 0, n = 0;
    for (double dev : d) {
      if (dev > cut) continue;
      s2 += dev * dev;
      n += 1;
    }
    if (n < static_cast<double>(kMinPairs)) continue;
    const double var = 0.5 * s2 / n;  // of one pixel: half the difference's
    const double level = lo + (b + 0.5) / kBins * (hi - lo);
    const double w = n;
    sw += w;
    sl += w * level;
    sv += w * var;
    sll += w * level * level;
    slv += w * level * var;
    lmin = std::min(lmin, level);
    lmax = std::max(lmax, level);
    ++bins;
  }
  if (bins < 3 || !(lmax - lmin > 0.2 * (hi - lo))) return -1.0;
  const double den = sw * sll - sl * sl;
  if (!(den > 0)) return -1.0;
  return std::max(0.0, (sw * slv - sl * sv) / den);
}

double OtsuThreshold(const cv::Mat& roi, double* separability) {
  double lo = 0, hi = 0;
  cv::minMaxLoc(roi, &lo, &hi);
  *separability = 0.0;
  if (!(hi > lo)) return lo;
  constexpr int kBins = 256;
  std::array<double, kBins> hist{};
  const double scale = (kBins - 1) / (hi - lo);
  double n = 0, sum = 0, sum2 = 0;
  for (int y = 0; y < roi.rows; ++y) {
    const float* r = roi.ptr<float>(y);
    for (int x = 0; x < roi.cols; ++x) {
      hist[static_cast<std::size_t>(std::lround((r[x] - lo) * scale))] += 1.0;
      n += 1;
      sum += r[x];
      sum2 += static_cast<double>(r[x]) * r[x];
    }
  }
  const double var_t = sum2 / n - (sum / n) * (sum / n);
  double w0 = 0, s0 = 0, best = -1, thr = lo;
  double total = 0;
  for (int i = 0; i < kBins; ++i) total += hist[static_cast<std::size_t>(i)] * (lo + i / scale);
  for (int i = 0; i + 1 < kBins; ++i) {
    const double v = lo + i / scale;
    w0 += hist[static_cast<std::size_t>(i)];
    s0 += hist[static_cast<std::size_t>(i)] * v;
    const double w1 = n - w0;
    if (w0 <= 0 || w1 <= 0) continue;
    const double m0 = s0 / w0, m1 = (total - s0) / w1;
    const double between = w0 * w1 * (m0 - m1) * (m0 - m1) / (n * n);
    if (between > best) {
      best = between;
      thr = v + 0.5 / scale;
    }
  }
  if (var_t > 0 && best > 0) *separability = std::min(1.0, best / var_t);
  return thr;
}

namespace {

// Keys' cubic-convolution kernel (a = −0.5) weights and their derivatives for the fractional offset f.
void CubicWeights(double f, double w[4], double dw[4]) {
  const double f2 = f * f, f3 = f2 * f;
  w[0] = -0.5 * f3 + f2 - 0.5 * f;
  w[1] = 1.5 * f3 - 2.5 * f2 + 1.0;
  w[2] = -1.5 * f3 + 2.0 * f2 + 0.5 * f;
  w[3] = 0.5 * f3 - 0.5 * f2;
  dw[0] = -1.5 * f2 + 2.0 * f - 0.5;
  dw[1] = 4.5 * f2 - 5.0 * f;
  dw[2] = -4.5 * f2 + 4.0 * f + 0.5;
  dw[3] = 1.5 * f2 - f;
}

}  // namespace

bool CubicSample(const cv::Mat& img, double x, double y, double* v, double* gx, double* gy) {
  const double fx0 = std::floor(x), fy0 = std::floor(y);
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  if (x0 < 1 || y0 < 1 || x0 + 2 >= img.cols || y0 + 2 >= img.rows) return false;
  double wx[4], dwx[4], wy[4], dwy[4];
  CubicWeights(x - fx0, wx, dwx);
  CubicWeights(y - fy0, wy, dwy);
  double val = 0, dx = 0, dy = 0;
  for (int j = 0; j < 4; ++j) {
    const float* r = img.ptr<float>(y0 - 1 + j) + (x0 - 1);
    const double rv = wx[0] * r[0] + wx[1] * r[1] + wx[2] * r[2] + wx[3] * r[3];
    const double rd = dwx[0] * r[0] + dwx[1] * r[1] + dwx[2] * r[2] + dwx[3] * r[3];
    val += wy[j] * rv;
    dx += wy[j] * rd;
    dy += dwy[j] * rv;
  }
  *v = val;
  *gx = dx;
  *gy = dy;
  return true;
}

bool SearchWindow(const cv::Mat& frame, const cv::Mat& templ, const Eigen::Vector2d& predicted, double search_px,
                  int margin, double ncc_min, cv::Mat* roi, cv::Mat* map, cv::Point* tl, NccPeak* peak,
                  PointMeasurement* m) {
  const int h = templ.cols / 2, S = std::max(1, static_cast<int>(std::ceil(search_px)));
  const int pad = h + S + margin;
  const int ix = static_cast<int>(std::lround(predicted.x())), iy = static_cast<int>(std::lround(predicted.y()));
  // The window, cut to the frame (a point near the border is still measured if its support fits).
  const cv::Rect want =
      cv::Rect(ix - pad, iy - pad, 2 * pad + 1, 2 * pad + 1) & cv::Rect(0, 0, frame.cols, frame.rows);
  if (!CopyFloatRoi(frame, want, roi) || want.width <= templ.cols || want.height <= templ.rows) {
    m->why = "at the image border";
    return false;
  }
  *tl = want.tl();
  cv::matchTemplate(*roi, templ, *map, cv::TM_CCOEFF_NORMED);
  *peak = NearestNearBestPeak(*map, want.tl(), h, h, predicted, 0.05, ncc_min, 0.0);
  if (!peak->found) {
    m->score = std::max(0.0, peak->best);
    m->why = "low correlation";
    return false;
  }
  return true;
}

namespace {

// A re-acquisition over a large area (the whole frame of a 5-megapixel camera by default) is searched coarse
// to fine: at full resolution OpenCV's matchTemplate over 2448×2048 took 160 ms per hidden point and frame,
// at a quarter 9 ms (and the frame is decimated once per call, 3 ms). The level is the coarsest (at most 2)
// at which the template keeps kCoarseMinTemplatePx, its NCC map direct (NccMapDirect: 1–2 ms where
// matchTemplate's DFT took 12); the coarse peaks within kCoarseSlack of the threshold are each searched again
// at full resolution about their place.
constexpr int kCoarseMinArea = 256 * 256;   // px²: smaller areas are searched at full resolution
constexpr int kCoarseMinTemplatePx = 6;
constexpr int kCoarseMaxLevel = 2;
constexpr double kCoarseSlack = 0.2;        // NCC: decimation blurs fine structure (a quadrant's saddle)

// Local maxima of an NCC map above min_score: (map x, y, score).
void MapPeaks(const cv::Mat& map, double min_score, std::vector<PointCandidate>* out, const cv::Point& to_px,
              double scale) {
  for (int y = 1; y + 1 < map.rows; ++y) {
    const float* r = map.ptr<float>(y);
    for (int x = 1; x + 1 < map.cols; ++x) {
      const float v = r[x];
      if (!(v >= min_score)) continue;
      bool is_max = true;
      for (int dy = -1; dy <= 1 && is_max; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if ((dx || dy) && map.at<float>(y + dy, x + dx) > v) is_max = false;
      if (is_max) out->push_back({Eigen::Vector2d(to_px.x + scale * x, to_px.y + scale * y), v});
    }
  }
}

// The strongest first, at least min_sep apart, at most max_n.
std::vector<PointCandidate> Strongest(std::vector<PointCandidate> all, int max_n, double min_sep) {
  std::sort(all.begin(), all.end(), [](const PointCandidate& a, const PointCandidate& b) { return a.score > b.score; });
  std::vector<PointCandidate> kept;
  for (const PointCandidate& c : all) {
    bool near = false;
    for (const PointCandidate& k : kept) near = near || (k.px - c.px).norm() < min_sep;
    if (!near) kept.push_back(c);
    if (static_cast<int>(kept.size()) >= max_n) break;
  }
  return kept;
}

}  // namespace

std::vector<PointCandidate> TemplatePeaks(const cv::Mat& frame, const cv::Mat& templ, const Eigen::Vector2d& center,
                                          double search_px, int max_n, double min_score, double min_sep) {
  const int hx = templ.cols / 2, hy = templ.rows / 2;
  const int S = std::max(1, static_cast<int>(std::ceil(search_px)));
  const int cx = static_cast<int>(std::lround(center.x())), cy = static_cast<int>(std::lround(center.y()));
  const cv::Rect want(cx - hx - S, cy - hy - S, 2 * (hx + S) + 1, 2 * (hy + S) + 1);
  const cv::Rect region = want & cv::Rect(0, 0, frame.cols, frame.rows);
  if (region.width <= templ.cols + 1 || region.height <= templ.rows + 1) return {};
  int level = 0;
  if (region.area() >= kCoarseMinArea) {
    while (level < kCoarseMaxLevel && (std::min(templ.cols, templ.rows) >> (level + 1)) >= kCoarseMinTemplatePx) ++level;
  }
  // Buffers kept between calls: a whole 5-megapixel frame as float is 20 MB, and allocating it anew on every
  // call cost as much in page faults as the search.
  thread_local cv::Mat roi, map, coarse_in, small, small_map, small_templ;
  std::vector<PointCandidate> all;
  if (level == 0) {
    frame(region).convertTo(roi, CV_32F);
    cv::matchTemplate(roi, templ, map, cv::TM_CCOEFF_NORMED);
    MapPeaks(map, min_score, &all, cv::Point(region.x + hx, region.y + hy), 1.0);
    return Strongest(std::move(all), max_n, min_sep);
  }
  cv::pyrDown(frame(region), coarse_in);  // in the frame's own depth (a quarter of the float's bytes for 8-bit)
  for (int l = 1; l < level; ++l) cv::pyrDown(coarse_in, coarse_in);
  coarse_in.convertTo(small, CV_32F);
  templ.copyTo(small_templ);
  for (int l = 0; l < level; ++l) cv::pyrDown(small_templ, small_templ);
  if (small.cols <= small_templ.cols + 1 || small.rows <= small_templ.rows + 1) return {};
  NccMapDirect(small, small_templ, &small_map);  // a small template: direct, not OpenCV's DFT (ncc_search.h)
  const double f = static_cast<double>(1 << level);
  // A coarse map pixel (x, y) is the template's top-left at f·(x, y): its centre at f·(x + half of the small one).
  std::vector<PointCandidate> coarse;
  MapPeaks(small_map, std::max(0.1, min_score - kCoarseSlack), &coarse,
           cv::Point(region.x + static_cast<int>(f * (small_templ.cols / 2)), region.y + static_cast<int>(f * (small_templ.rows / 2))), f);
  coarse = Strongest(std::move(coarse), std::max(16, 4 * max_n), std::max(2.0, min_sep));
  for (const PointCandidate& c : coarse) {
    // Full resolution about the coarse peak (a small area: searched at full resolution).
    for (const PointCandidate& fine : TemplatePeaks(frame, templ, c.px, f + 2, 1, min_score, min_sep)) all.push_back(fine);
  }
  return Strongest(std::move(all), max_n, min_sep);
}

}  // namespace rk::extract

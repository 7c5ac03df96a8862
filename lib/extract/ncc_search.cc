// The correlation peak; see ncc_search.h.
#include "extract/ncc_search.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace rk::extract {
namespace {

bool IsLocalMax(const cv::Mat& map, int x, int y, float v) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int yy = y + dy, xx = x + dx;
      if ((dx || dy) && yy >= 0 && xx >= 0 && yy < map.rows && xx < map.cols && map.at<float>(yy, xx) > v) {
        return false;
      }
    }
  }
  return true;
}

// Vertex offset of the parabola through (−1, a), (0, b), (1, c), within ±0.5.
double ParabolaVertex(double a, double b, double c) {
  const double den = a - 2.0 * b + c;
  if (!(den < 0.0)) return 0.0;
  return std::clamp(0.5 * (a - c) / den, -0.5, 0.5);
}

}  // namespace

NccPeak NearestNearBestPeak(const cv::Mat& map, const cv::Point& region_tl, int hx, int hy,
                            const Eigen::Vector2d& predicted, double near_best, double min_score,
                            double exclusion_px) {
  NccPeak out;
  for (int y = 0; y < map.rows; ++y) {
    const float* row = map.ptr<float>(y);
    for (int x = 0; x < map.cols; ++x) out.best = std::max(out.best, static_cast<double>(row[x]));
  }
  if (!(out.best >= min_score)) return out;
  double best_d2 = 1e300;
  int px = -1, py = -1;
  for (int y = 0; y < map.rows; ++y) {
    const float* row = map.ptr<float>(y);
    for (int x = 0; x < map.cols; ++x) {
      const double v = row[x];
      if (v < out.best - near_best || !IsLocalMax(map, x, y, row[x])) continue;
      const Eigen::Vector2d p(region_tl.x + x + hx, region_tl.y + y + hy);
      const double d2 = (p - predicted).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        out.px = p;
        out.score = v;
        px = x;
        py = y;
      }
    }
  }
  if (px < 0) return out;
  out.found = true;
  out.sub = out.px;
  if (px > 0 && px + 1 < map.cols) {
    out.sub.x() += ParabolaVertex(map.at<float>(py, px - 1), map.at<float>(py, px), map.at<float>(py, px + 1));
  }
  if (py > 0 && py + 1 < map.rows) {
    out.sub.y() += ParabolaVertex(map.at<float>(py - 1, px), map.at<float>(py, px), map.at<float>(py + 1, px));
  }
  if (!(exclusion_px > 0.0)) return out;  // no runner-up wanted
  const double ex2 = exclusion_px * exclusion_px;
  for (int y = 0; y < map.rows; ++y) {
    const float* row = map.ptr<float>(y);
    for (int x = 0; x < map.cols; ++x) {
      if ((x - px) * (x - px) + (y - py) * (y - py) <= ex2 || row[x] <= out.second) continue;
      if (IsLocalMax(map, x, y, row[x])) out.second = row[x];
    }
  }
  return out;
}

void NccMapDirect(const cv::Mat& image, const cv::Mat& templ, cv::Mat* map) {
  CV_Assert(image.type() == CV_32FC1 && templ.type() == CV_32FC1);
  const int w = templ.cols, h = templ.rows;
  const int mw = image.cols - w + 1, mh = image.rows - h + 1;
  if (mw <= 0 || mh <= 0) {
    map->release();
    return;
  }
  const double n = static_cast<double>(w) * h;
  const cv::Scalar tmean = cv::mean(templ);
  cv::Mat tz;
  templ.convertTo(tz, CV_32F, 1.0, -tmean[0]);
  const double tnorm = cv::norm(tz);
  // Σ (T − T̄)(I − Ī) = Σ (T − T̄) I over each window: the correlation with the zero-mean template, anchored at
  // its top-left so that out(x, y) is the window whose top-left is (x, y).
  cv::Mat corr;
  cv::filter2D(image, corr, CV_32F, tz, cv::Point(0, 0), 0.0, cv::BORDER_CONSTANT);
  cv::Mat sum, sqsum;
  cv::integral(image, sum, sqsum, CV_64F, CV_64F);
  map->create(mh, mw, CV_32FC1);
  for (int y = 0; y < mh; ++y) {
    const double* s0 = sum.ptr<double>(y);
    const double* s1 = sum.ptr<double>(y + h);
    const double* q0 = sqsum.ptr<double>(y);
    const double* q1 = sqsum.ptr<double>(y + h);
    const float* c = corr.ptr<float>(y);
    float* out = map->ptr<float>(y);
    for (int x = 0; x < mw; ++x) {
      const double s = s1[x + w] - s1[x] - s0[x + w] + s0[x];
      const double q = q1[x + w] - q1[x] - q0[x + w] + q0[x];
      const double var = q - s * s / n;  // n × the window's variance
      out[x] = var > 1e-9 * std::max(1.0, q) && tnorm > 0 ? static_cast<float>(c[x] / (std::sqrt(var) * tnorm)) : 0.0f;
    }
  }
}

}  // namespace rk::extract

// Marker discs and target body for rk-sim attitude; model in attitude_render.h.
#include "sim/attitude_render.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace rk::sim {

void AddDiscs(cv::Mat* signal, std::span<const Disc> discs) {
  CV_Assert(signal->type() == CV_32FC1);
  constexpr int kSub = 4;  // sub-samples per pixel side
  const double inv_sqrt2 = 1.0 / std::sqrt(2.0);
  for (const Disc& d : discs) {
    const double reach = d.radius_px + 5.0 * d.psf_sigma_px + 1.0;
    const int x0 = std::max(0, static_cast<int>(std::floor(d.x_px - reach)));
    const int x1 = std::min(signal->cols - 1, static_cast<int>(std::ceil(d.x_px + reach)));
    const int y0 = std::max(0, static_cast<int>(std::floor(d.y_px - reach)));
    const int y1 = std::min(signal->rows - 1, static_cast<int>(std::ceil(d.y_px + reach)));
    const double k = inv_sqrt2 / d.psf_sigma_px;
    for (int y = y0; y <= y1; ++y) {
      float* row = signal->ptr<float>(y);
      for (int x = x0; x <= x1; ++x) {
        // Pixels far inside or outside the edge need no sub-sampling.
        const double rc = std::hypot(x - d.x_px, y - d.y_px);
        if (rc > reach) continue;
        double v;
        if (rc < d.radius_px - 5.0 * d.psf_sigma_px - 1.0) {
          v = 1.0;
        } else {
          double sum = 0.0;
          for (int sy = 0; sy < kSub; ++sy) {
            const double py = y - 0.5 + (sy + 0.5) / kSub - d.y_px;
            for (int sx = 0; sx < kSub; ++sx) {
              const double px = x - 0.5 + (sx + 0.5) / kSub - d.x_px;
              sum += 0.5 * std::erfc((std::hypot(px, py) - d.radius_px) * k);
            }
          }
          v = sum / (kSub * kSub);
        }
        row[x] += static_cast<float>(d.amplitude_dn * v);
      }
    }
  }
}

void AddConvexHull(cv::Mat* signal, std::span<const Eigen::Vector2d> points_px, double dn) {
  CV_Assert(signal->type() == CV_32FC1);
  if (points_px.size() < 3 || dn == 0.0) return;
  std::vector<cv::Point2f> pts;
  for (const auto& p : points_px) pts.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  std::vector<cv::Point2f> hull;
  cv::convexHull(pts, hull);
  std::vector<cv::Point> ipts;
  for (const auto& p : hull) ipts.emplace_back(cvRound(p.x), cvRound(p.y));
  const cv::Rect box = cv::boundingRect(ipts) & cv::Rect(0, 0, signal->cols, signal->rows);
  if (box.empty()) return;
  for (auto& p : ipts) p -= box.tl();
  cv::Mat mask = cv::Mat::zeros(box.size(), CV_8UC1);
  cv::fillConvexPoly(mask, ipts, cv::Scalar(255));
  cv::Mat roi = (*signal)(box);
  cv::add(roi, cv::Scalar(dn), roi, mask);
}

}  // namespace rk::sim

// The correlation search shared by rk-extract features and points: normalised cross-correlation
// (cv::matchTemplate, TM_CCOEFF_NORMED) of a template over a search window, and the choice of its peak —
// the local maximum nearest the prediction among those within `near_best` of the best, so that a
// neighbour that correlates as well cannot steal the track — with a parabolic sub-pixel start.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace rk::extract {

struct NccPeak {
  bool found = false;
  Eigen::Vector2d px{0, 0};    // the template centre's image position at the chosen peak (integer)
  Eigen::Vector2d sub{0, 0};   // the same refined by a parabola through the peak and its 4 neighbours
  double score = -2.0;         // NCC at the chosen peak
  double best = -2.0;          // the map's best NCC
  double second = -2.0;        // best NCC of the other local maxima more than `exclusion_px` from the chosen one
};

// `map` is the NCC map of a template of half size (hx, hy) matched over `region` of the image (map (0, 0) ↔
// template centre at region.tl() + (hx, hy)). Peaks below min_score are ignored (found = false when none).
// exclusion_px ≤ 0: the runner-up (`second`) is not looked for.
NccPeak NearestNearBestPeak(const cv::Mat& map, const cv::Point& region_tl, int hx, int hy,
                            const Eigen::Vector2d& predicted, double near_best, double min_score,
                            double exclusion_px = 3.0);

// The same map as cv::matchTemplate(image, templ, *map, TM_CCOEFF_NORMED) (CV_32FC1 images; the valid
// region, (W − w + 1) × (H − h + 1)), computed as a direct correlation with the zero-mean template
// (cv::filter2D) over window sums from integral images; 0 where the window is flat. For small templates
// over large images: OpenCV's matchTemplate always goes through the DFT, which for a 7×7 template over
// 612×512 took 12 ms against 1–2 ms here (the coarse level of a whole-frame re-acquisition).
void NccMapDirect(const cv::Mat& image, const cv::Mat& templ, cv::Mat* map);

}  // namespace rk::extract

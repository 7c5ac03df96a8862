// The measurers behind MakePointMeasurer (point_measure.h), one file each; internal to lib/extract.
#pragma once

#include <memory>
#include <optional>

#include "extract/ncc_search.h"
#include "extract/point_measure.h"

namespace rk::extract {

std::unique_ptr<PointMeasurer> MakeQuadrantMeasurer(std::optional<double> size_px, const PointMeasureOptions& o);
std::unique_ptr<PointMeasurer> MakeCircleMeasurer(std::optional<double> size_px, const PointMeasureOptions& o);
std::unique_ptr<PointMeasurer> MakeCentroidMeasurer(bool dark, std::optional<double> size_px,
                                                    const PointMeasureOptions& o);
std::unique_ptr<PointMeasurer> MakeCorrelationMeasurer(std::optional<double> size_px, const PointMeasureOptions& o);

// The search of quadrant and circle: the window ±(template half + search + margin) about `predicted`, cut to
// the frame, copied into *roi (top-left *tl) and searched with `templ`; *peak the NCC peak nearest the
// prediction among the near-best. false (m->why, m->score set) when the window cannot hold the template or no
// peak reaches ncc_min.
bool SearchWindow(const cv::Mat& frame, const cv::Mat& templ, const Eigen::Vector2d& predicted, double search_px,
                  int margin, double ncc_min, cv::Mat* roi, cv::Mat* map, cv::Point* tl, NccPeak* peak,
                  PointMeasurement* m);

// The NCC peaks of `templ` (half sizes hx, hy) over frame ± (search + half) about `center`, strongest first,
// at least `min_sep` px apart, above min_score.
std::vector<PointCandidate> TemplatePeaks(const cv::Mat& frame, const cv::Mat& templ, const Eigen::Vector2d& center,
                                          double search_px, int max_n, double min_score, double min_sep);

}  // namespace rk::extract

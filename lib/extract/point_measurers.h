// The measurers behind MakePointMeasurer (point_measure.h), one file each; internal to lib/extract.
#pragma once

#include <memory>
#include <optional>

#include "extract/point_measure.h"

namespace rk::extract {

std::unique_ptr<PointMeasurer> MakeQuadrantMeasurer(std::optional<double> size_px, const PointMeasureOptions& o);
std::unique_ptr<PointMeasurer> MakeCircleMeasurer(std::optional<double> size_px, const PointMeasureOptions& o);
std::unique_ptr<PointMeasurer> MakeCentroidMeasurer(bool dark, std::optional<double> size_px,
                                                    const PointMeasureOptions& o);
std::unique_ptr<PointMeasurer> MakeCorrelationMeasurer(std::optional<double> size_px, const PointMeasureOptions& o);

// The NCC peaks of `templ` (half sizes hx, hy) over frame ± (search + half) about `center`, strongest first,
// at least `min_sep` px apart, above min_score.
std::vector<PointCandidate> TemplatePeaks(const cv::Mat& frame, const cv::Mat& templ, const Eigen::Vector2d& center,
                                          double search_px, int max_n, double min_score, double min_sep);

}  // namespace rk::extract

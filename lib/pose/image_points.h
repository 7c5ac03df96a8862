// Image points of target features (SPEC.md §2.1 "image points", read by formats::ReadImagePoints) mapped to
// a target model's ids for rk-attitude oi: each frame's measured points (formats::ImagePoint::measured).
// A point's id must be in the target model (DataError at file:line:col); sigma_px (or sigma_x_px,sigma_y_px:
// their mean) is the 1σ of each coordinate.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/image_points.h"
#include "io/csv.h"
#include "target/feature_model.h"

namespace rk::pose {

struct ImagePoint {
  int model_index = -1;                  // into target::FeatureModel::ids
  Eigen::Vector2d px{0, 0};
  std::optional<double> sigma_px;        // from the file, if given
  std::size_t line = 0, col_x = 0;       // where x_px is (messages)
};

struct PointFrame {
  std::optional<std::int64_t> frame;
  double t_s = 0.0;
  std::vector<ImagePoint> points;        // usable points only
  std::size_t rows = 0;                  // rows of this frame in the file
  std::size_t first_line = 0;
};

struct ImagePoints {
  std::string source;
  bool has_frame = false;
  std::vector<PointFrame> frames;
  std::size_t rows = 0;
  std::size_t unusable_rows = 0;         // rows without a usable measurement
  // Rows of a points track (rk-extract points: a `score` column) whose id the model does not have: skipped.
  std::size_t ignored_rows = 0;
  std::vector<std::string> ignored_ids;
};

ImagePoints ReadImagePoints(const io::CsvTable& table, const target::FeatureModel& model);
// The cells ReadImagePoints needs of every row (for io::CsvReadOptions::rule, --bad-rows skip).
inline io::CsvRowRule ImagePointsRowRule() { return formats::ImagePointsRowRule(); }

}  // namespace rk::pose

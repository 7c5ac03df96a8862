// Image points of target features (SPEC.md §2.1 "image points"), long format, one row per
// point per frame:
//   frame,t_s,id,x_px,y_px[,status][,sigma_px][,...]
// Written by `rk-extract features`, read by `rk-attitude oi`. Pixels per SPEC.md §3 ((0, 0) =
// centre of the top-left pixel). Required columns: t_s, id, x_px, y_px; `frame`, `status`
// (ok, reacquired, predicted, lost, invalid) and `sigma_px` (1σ of each coordinate, px) are
// optional; other columns are ignored.
//
// Reading groups the rows into frames: by `frame` when the column exists (rows of a frame must
// be contiguous and share one t_s), otherwise by equal t_s. A point is usable when x_px and
// y_px are given and its status (if any) is ok or reacquired: a `predicted` position is not a
// measurement. Errors (DataError at file:line:col): an id not in the target model, an id twice
// in one frame, time going backwards, a frame split or with two times, a status not in the
// SPEC vocabulary, sigma_px ≤ 0.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/csv.h"
#include "io/row_status.h"
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
};

ImagePoints ReadImagePoints(const io::CsvTable& table, const target::FeatureModel& model);
// The cells ReadImagePoints needs of every row (for io::CsvReadOptions::rule, --bad-rows skip).
io::CsvRowRule ImagePointsRowRule();

}  // namespace rk::pose

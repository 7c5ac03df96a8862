// Image points (SPEC.md §2.1 `frame,t_s,id,x_px,y_px`, long format: one row per point per frame), and the
// points track of `rk-extract points`, which is readable wherever image points are. Written by rk-extract
// features and silhouette and the simulators; read (through this reader only) by rk-attitude oi
// (pose::ReadImagePoints), rk-attitude cylinder (attitude::ReadCylinderPoints) and rk-calibrate pointing
// (calibrate::ReadImagePoints), each of which maps the ids to its own model.
//
// Required columns: t_s, id, x_px, y_px. Optional: `frame` (rows are grouped by it; without it by equal
// consecutive t_s), `status` (SPEC vocabulary; ok when absent or empty), 1σ per coordinate as
// `sigma_x_px,sigma_y_px` or `sigma_px` (both coordinates); other columns are ignored.
// A point is a measurement (ImagePoint::measured) when x_px and y_px are given and its status is ok or
// reacquired: a `predicted` position was filled in by a tracker's prediction, a `lost` or `invalid` row has
// none to use. Estimators that weigh measurements (pose, pointing calibration) use measured points only;
// rk-attitude cylinder also uses predicted ones and labels its row `predicted` (SPEC.md §2.1).
// Errors (DataError at file:line:col): time going backwards, a negative frame, the rows of a frame not
// together, a frame with two times, an empty id, an id twice in one frame, a status not in the vocabulary,
// a σ that is not > 0.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/beacon_track.h"
#include "io/csv.h"
#include "io/row_status.h"

namespace rk::formats {

struct ImagePoint {
  std::string id;
  std::optional<Eigen::Vector2d> px;        // nullopt: the row has no position
  RowStatus status = RowStatus::kOk;
  std::optional<Eigen::Vector2d> sigma_px;  // 1σ of x_px, y_px when the row gives it
  std::size_t line = 0, col_id = 0, col_x = 0;  // where the row and its cells are (messages)

  bool measured() const { return px && (status == RowStatus::kOk || status == RowStatus::kReacquired); }
};

struct ImagePointFrame {
  std::optional<std::int64_t> frame;  // the `frame` column, when the file has it
  double t_s = 0.0;
  std::size_t line = 0;               // first line of the frame
  std::vector<ImagePoint> points;     // every row of the frame, in file order
};

struct ImagePoints {
  std::string source;
  bool has_frame = false;
  std::size_t rows = 0;
  std::vector<ImagePointFrame> frames;
};

ImagePoints ReadImagePoints(const io::CsvTable& table);
// The cells ReadImagePoints needs of every row (for io::CsvReadOptions::rule, --bad-rows skip).
io::CsvRowRule ImagePointsRowRule();
// A points track (or any image points) as one track per id, ids in order of first appearance, each row of
// the id's frames with its position, status and σ (rk-locate of a points track: one located series per id).
// A frame without a row of an id gives that id no row there.
std::vector<std::pair<std::string, Track>> TracksById(const ImagePoints& points);

// A writer's header: the required columns in SPEC order with `status` (every rangekit writer gives it), then
// the producer's own (sigma_px, ncc, ...).
std::vector<std::string> ImagePointsColumns(const std::vector<std::string>& extra = {});

}  // namespace rk::formats

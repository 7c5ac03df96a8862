// Beacon track (SPEC.md §2.1 `frame,t_s,x_px,y_px,peak,area_px,status`): written by rk-extract beacon, read by
// rk-locate. Columns are found by name; every complaint names file:line:col.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/csv.h"
#include "io/row_status.h"

namespace rk::formats {

struct TrackRow {
  std::optional<std::int64_t> frame;  // `frame` column when present
  double t_s = 0.0;                   // frame time (s since the trial epoch)
  std::optional<Eigen::Vector2d> px;  // beacon centre (x_px, y_px); nullopt = no measurement
  RowStatus status = RowStatus::kOk;
  std::optional<Eigen::Vector2d> sigma_px;  // 1σ of x_px, y_px (sigma_x_px, sigma_y_px) when the track has them
};

// Required: t_s, x_px, y_px. `status` is optional: without it (e.g. rk-sim's truth/beacon.csv) a row
// with both x_px and y_px is `ok` and one without is `lost`. A row whose x_px or y_px is empty is `lost`
// whatever its status says (no measurement). t_s must be non-decreasing. Optional `sigma_x_px,sigma_y_px`
// (rk-extract beacon's centroid 1σ): a row with both (finite, >= 0) carries them; rk-locate's σ
// propagation uses them instead of --sigma-px.
struct Track {
  std::string source;
  bool has_frame = false;
  std::vector<TrackRow> rows;
};
Track ReadTrack(const io::CsvTable& table);
// The cells ReadTrack needs of every row (for io::CsvReadOptions::rule, --bad-rows skip).
io::CsvRowRule TrackRowRule();

}  // namespace rk::formats

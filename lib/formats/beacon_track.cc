// Beacon track reader; format in beacon_track.h.
#include "formats/beacon_track.h"

#include "io/error.h"

namespace rk::formats {

Track ReadTrack(const io::CsvTable& table) {
  Track track;
  track.source = table.name();
  const int c_t = table.RequireColumn("t_s");
  const int c_x = table.RequireColumn("x_px");
  const int c_y = table.RequireColumn("y_px");
  const int c_frame = table.Column("frame");
  const int c_status = table.Column("status");
  const int c_sx = table.Column("sigma_x_px");
  const int c_sy = table.Column("sigma_y_px");
  track.has_frame = c_frame >= 0;
  table.RequireNonDecreasing(c_t);
  track.rows.reserve(table.rows());
  for (std::size_t r = 0; r < table.rows(); ++r) {
    TrackRow row;
    row.t_s = table.Double(r, c_t);
    if (c_frame >= 0 && !table.IsEmpty(r, c_frame)) row.frame = table.Int(r, c_frame);
    const auto x = table.OptionalDouble(r, c_x);
    const auto y = table.OptionalDouble(r, c_y);
    if (c_status >= 0 && !table.IsEmpty(r, c_status)) {
      if (!ParseRowStatus(table.Cell(r, c_status), &row.status)) {
        throw table.CellError(r, c_status,
                              "unknown status '" + std::string(table.Cell(r, c_status)) +
                                  "' (expected ok, reacquired, predicted, lost or invalid)");
      }
    } else {
      row.status = RowStatus::kOk;
    }
    const bool measured = row.status != RowStatus::kLost && row.status != RowStatus::kInvalid;
    if (x && y && measured) {
      row.px = Eigen::Vector2d(*x, *y);
      if (c_sx >= 0 && c_sy >= 0) {
        const auto sx = table.OptionalDouble(r, c_sx);
        const auto sy = table.OptionalDouble(r, c_sy);
        if (sx && !(*sx >= 0.0)) throw table.CellError(r, c_sx, "sigma_x_px must be >= 0");
        if (sy && !(*sy >= 0.0)) throw table.CellError(r, c_sy, "sigma_y_px must be >= 0");
        if (sx && sy) row.sigma_px = Eigen::Vector2d(*sx, *sy);
      }
    } else if (!(x && y)) {
      // No pixel: there is no measurement on this row, whatever the status said.
      if (row.status != RowStatus::kInvalid) row.status = RowStatus::kLost;
    }
    track.rows.push_back(row);
  }
  return track;
}

io::CsvRowRule TrackRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.optional_numbers = {"x_px", "y_px", "sigma_x_px", "sigma_y_px"};
  rule.optional_integers = {"frame"};
  return rule;
}

}  // namespace rk::formats

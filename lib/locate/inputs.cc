// Input readers of rk-locate; formats in inputs.h.
#include "locate/inputs.h"

#include <cmath>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::locate {

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
      if (!ParseTrackStatus(std::string(table.Cell(r, c_status)), &row.status)) {
        throw table.CellError(r, c_status,
                              "unknown status '" + std::string(table.Cell(r, c_status)) +
                                  "' (expected ok, reacquired, predicted, lost or invalid)");
      }
    } else {
      row.status = TrackStatus::kOk;
    }
    const bool measured = row.status != TrackStatus::kLost && row.status != TrackStatus::kInvalid;
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
      if (row.status != TrackStatus::kInvalid) row.status = TrackStatus::kLost;
    }
    track.rows.push_back(row);
  }
  return track;
}

TurretLog ReadTurretLog(const io::CsvTable& table) {
  TurretLog log;
  log.source = table.name();
  const int c_t = table.RequireColumn("t_s");
  const int c_az = table.RequireColumn("az_deg");
  const int c_el = table.RequireColumn("el_deg");
  table.RequireNonDecreasing(c_t);
  log.t_s.reserve(table.rows());
  log.az_rad.reserve(table.rows());
  log.el_rad.reserve(table.rows());
  for (std::size_t r = 0; r < table.rows(); ++r) {
    log.t_s.push_back(table.Double(r, c_t));
    const auto az = table.OptionalDouble(r, c_az);
    const auto el = table.OptionalDouble(r, c_el);
    if (el && (*el < -90.0 || *el > 90.0))
      throw table.CellError(r, c_el, "elevation outside [-90, 90] degrees");
    if (!az || !el) ++log.empty_samples;
    log.az_rad.push_back(az ? geo::DegToRad(*az) : std::nan(""));
    log.el_rad.push_back(el ? geo::DegToRad(*el) : std::nan(""));
  }
  return log;
}

RangeLog ReadRangeLog(const io::CsvTable& table) {
  RangeLog log;
  log.source = table.name();
  const int c_t = table.RequireColumn("t_s");
  const int c_r = table.RequireColumn("range_m");
  const int c_status = table.Column("status");
  table.RequireNonDecreasing(c_t);
  for (std::size_t r = 0; r < table.rows(); ++r) {
    log.t_s.push_back(table.Double(r, c_t));
    std::int64_t code = 0;
    if (c_status >= 0 && !table.IsEmpty(r, c_status)) code = table.Int(r, c_status);
    const auto range = table.OptionalDouble(r, c_r);
    if (code != 0 || !range) {
      ++log.device_errors;
      log.range_m.push_back(std::nullopt);
      continue;
    }
    if (!(*range > 0.0)) throw table.CellError(r, c_r, "range must be > 0 m on a row with status 0");
    log.range_m.push_back(*range);
  }
  return log;
}

io::CsvRowRule TrackRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.optional_numbers = {"x_px", "y_px", "sigma_x_px", "sigma_y_px"};
  rule.optional_integers = {"frame"};
  return rule;
}

io::CsvRowRule TurretLogRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.optional_numbers = {"az_deg", "el_deg"};
  return rule;
}

io::CsvRowRule RangeLogRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.optional_numbers = {"range_m"};
  rule.optional_integers = {"status"};
  return rule;
}

}  // namespace rk::locate

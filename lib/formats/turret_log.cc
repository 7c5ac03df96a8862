// Turret log reader; format in turret_log.h.
#include "formats/turret_log.h"

#include <cmath>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::formats {

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

io::CsvRowRule TurretLogRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.optional_numbers = {"az_deg", "el_deg"};
  return rule;
}

}  // namespace rk::formats

// Range log reader; format in range_log.h.
#include "formats/range_log.h"

#include "io/error.h"

namespace rk::formats {

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

io::CsvRowRule RangeLogRowRule() {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.optional_numbers = {"range_m"};
  rule.optional_integers = {"status"};
  return rule;
}

}  // namespace rk::formats

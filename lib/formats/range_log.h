// Range log (SPEC.md §2.1 `t_s,range_m[,status]`): written by rk-capture (Dimetix) and rk-sim, read by
// rk-locate.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/csv.h"

namespace rk::formats {

// status 0 (or empty, or no column) = ok, anything else = device error code; an empty range_m is a device
// error too. Usable ranges must be > 0. t_s non-decreasing.
struct RangeLog {
  std::string source;
  std::vector<double> t_s;
  std::vector<std::optional<double>> range_m;  // nullopt = device error
  std::size_t device_errors = 0;
};
RangeLog ReadRangeLog(const io::CsvTable& table);
// The cells ReadRangeLog needs of every row.
io::CsvRowRule RangeLogRowRule();

}  // namespace rk::formats

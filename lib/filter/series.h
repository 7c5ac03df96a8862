// Time series read from a CSV for the filters of rk-smooth (SPEC.md §2): `t_s` plus value
// columns chosen by name. Values in radians for angle columns (names ending `_deg`), SI
// otherwise; a missing value (empty field) is NaN and means "no measurement in this row".
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "io/csv.h"

namespace rk::filter {

struct Series {
  std::string source;                // file name, for messages
  std::vector<std::string> columns;  // as named in the file
  std::vector<bool> is_angle;        // column ends with "_deg": radians inside, wrap-safe
  std::vector<double> t_s;           // strictly increasing
  Eigen::MatrixXd values;            // rows = samples, cols = columns (a column is contiguous); NaN = missing
  std::size_t rows() const { return t_s.size(); }
};

// Reads `t_s` and `columns` from `table`. Throws DataError (exit 3) naming file, line and
// column when a column is absent, a value is not a number, t_s is empty, repeats or goes
// backwards, or fewer than `min_samples` rows carry at least one value. Throws UsageError
// (exit 2) for an empty or repeated column list. Angle columns are converted to radians.
Series ReadSeries(const io::CsvTable& table, const std::vector<std::string>& columns, std::size_t min_samples = 3);
// The cells ReadSeries needs of every row (for io::CsvReadOptions::rule, --bad-rows skip):
// t_s increasing, each of `columns` empty or a number.
io::CsvRowRule SeriesRowRule(const std::vector<std::string>& columns);

// True if a column name is an angle in degrees (SPEC.md units: suffix `_deg`).
bool IsAngleColumn(const std::string& name);

// Splits "<base>_<unit>" at the last '_'; false (outputs untouched) for a name without '_', or one that
// starts or ends with it.
bool SplitUnit(const std::string& column, std::string* base, std::string* unit);

// The one naming rule of the columns the rk-smooth filters derive from value column `<base>_<unit>`
// (docs/rk-smooth-singer-resample.md): `order` 0 / 1 / 2 = the value / its rate / its acceleration,
// `sigma` = its 1σ instead of the estimate. `yaw_deg` → `yaw_rate_deg_s`, `yaw_accel_deg_s2`, and with
// sigma `yaw_sigma_deg`, `yaw_rate_sigma_deg_s`, `yaw_accel_sigma_deg_s2`; a name without a unit gets
// `_rate_per_s`, `_accel_per_s2`, `_sigma`, `_rate_sigma_per_s`, `_accel_sigma_per_s2`. Order 0 without
// sigma is the column itself.
std::string DerivedColumnName(const std::string& column, int order, bool sigma = false);

}  // namespace rk::filter

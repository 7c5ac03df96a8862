#include "filter/series.h"

#include <cmath>
#include <limits>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::filter {

bool IsAngleColumn(const std::string& name) {
  return name.size() > 4 && name.compare(name.size() - 4, 4, "_deg") == 0;
}

Series ReadSeries(const io::CsvTable& table, const std::vector<std::string>& columns, std::size_t min_samples) {
  if (columns.empty()) throw UsageError("--columns: no column given");
  for (std::size_t i = 0; i < columns.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (columns[i] == columns[j]) throw UsageError("--columns: '" + columns[i] + "' given twice");
    }
  }
  Series s;
  s.source = table.name();
  s.columns = columns;
  const int c_t = table.RequireColumn("t_s");
  std::vector<int> idx;
  for (const auto& c : columns) {
    if (c == "t_s") throw UsageError("--columns: t_s is the time column, not a value column");
    idx.push_back(table.RequireColumn(c));
    s.is_angle.push_back(IsAngleColumn(c));
  }
  const std::size_t n = table.rows();
  s.t_s.resize(n);
  s.values.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(columns.size()));
  std::size_t with_value = 0;
  for (std::size_t r = 0; r < n; ++r) {
    const double t = table.Double(r, c_t);
    if (r > 0 && !(t > s.t_s[r - 1])) {
      throw table.CellError(r, c_t,
                            t == s.t_s[r - 1] ? "time repeats the previous row's (" + std::string(table.Cell(r, c_t)) + ")"
                                              : "time goes backwards (" + std::string(table.Cell(r, c_t)) + " after " +
                                                    std::string(table.Cell(r - 1, c_t)) + ")");
    }
    s.t_s[r] = t;
    bool any = false;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      auto v = table.OptionalDouble(r, idx[k]);
      double x = std::numeric_limits<double>::quiet_NaN();
      if (v) {
        x = s.is_angle[k] ? geo::DegToRad(*v) : *v;
        any = true;
      }
      s.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = x;
    }
    if (any) ++with_value;
  }
  if (with_value < min_samples) {
    throw TooFewSamplesError(table.name(),
                    "needs at least " + std::to_string(min_samples) + " samples with values, has " +
                        std::to_string(with_value));
  }
  return s;
}

io::CsvRowRule SeriesRowRule(const std::vector<std::string>& columns) {
  io::CsvRowRule rule;
  rule.non_decreasing = "t_s";
  rule.increasing = true;
  rule.optional_numbers = columns;
  return rule;
}

bool SplitUnit(const std::string& column, std::string* base, std::string* unit) {
  const auto p = column.rfind('_');
  if (p == std::string::npos || p == 0 || p + 1 >= column.size()) return false;
  *base = column.substr(0, p);
  *unit = column.substr(p + 1);
  return true;
}

std::string DerivedColumnName(const std::string& column, int order, bool sigma) {
  RK_CHECK(order >= 0 && order <= 2, "derivative order " + std::to_string(order));
  static const char* const kWhat[3] = {"", "_rate", "_accel"};
  static const char* const kPer[3] = {"", "_s", "_s2"};
  const std::string what = std::string(kWhat[order]) + (sigma ? "_sigma" : "");
  std::string base, unit;
  if (!SplitUnit(column, &base, &unit))
    return column + what + (order ? "_per" + std::string(kPer[order]) : "");
  return base + what + "_" + unit + kPer[order];
}

}  // namespace rk::filter

// Shared by the filter tests: a one-column Series from times and values.
#pragma once

#include <string>
#include <vector>

#include "filter/series.h"

namespace rk::filter {

inline Series MakeSeries(const std::string& column, const std::vector<double>& t, const std::vector<double>& v) {
  Series s;
  s.source = "test";
  s.columns = {column};
  s.is_angle = {IsAngleColumn(column)};
  s.t_s = t;
  s.values.resize(static_cast<Eigen::Index>(t.size()), 1);
  for (std::size_t i = 0; i < t.size(); ++i) s.values(static_cast<Eigen::Index>(i), 0) = v[i];
  return s;
}

}  // namespace rk::filter

// Three cells of a CSV row read as one vector (an ENU position, its 1σ, a WGS-84 triple), shared by the
// readers of lib/formats: all three given, all three empty, or a DataError at the first empty one.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>

#include "io/csv.h"

namespace rk::formats::internal {

// nullopt when a column is missing (index < 0) or the three cells are empty.
inline std::optional<Eigen::Vector3d> VectorCells(const io::CsvTable& table, std::size_t i, const int (&cols)[3]) {
  if (cols[0] < 0 || cols[1] < 0 || cols[2] < 0) return std::nullopt;
  std::optional<double> v[3];
  for (int k = 0; k < 3; ++k) v[k] = table.OptionalDouble(i, cols[k]);
  if (!v[0] && !v[1] && !v[2]) return std::nullopt;
  for (int k = 0; k < 3; ++k) {
    if (!v[k]) throw table.CellError(i, cols[k], "empty where the row's other coordinates are given");
  }
  return Eigen::Vector3d(*v[0], *v[1], *v[2]);
}

}  // namespace rk::formats::internal

// target::FeatureModel, the target model of feature points (SPEC.md §3 "Target attitude"): a JSON object
//   {"points": {"<id>": [x, y, z], ...}}
// with coordinates in body metres (body frame x forward/nose, y right, z down). Other keys
// are allowed and ignored. Used by `rk-extract features` (which ids to look for, and the
// geometry that identifies them) and by `rk-attitude oi` (the 3-D points of the pose).
//
// Checks (DataError naming the file): "points" present and an object; at least 4 points; ids
// non-empty, printable, without ',' or '"' (they are written to CSV unquoted); every point an
// array of 3 finite numbers within 10 km of the origin (no point at infinity); no two points
// closer than 1 µm; not all on one line (the pose would be undetermined).
// Ids are kept in the JSON library's order (sorted by id).
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "io/json_util.h"

namespace rk::target {

struct FeatureModel {
  std::string source;                   // file name, for messages
  std::vector<std::string> ids;         // sorted
  std::vector<Eigen::Vector3d> p_body;  // same order (m)

  std::size_t size() const { return ids.size(); }
  // Index of an id, or -1.
  int Find(std::string_view id) const;
  // λ3/λ1 of the scatter of the points about their centroid: 0 = coplanar.
  double Planarity() const;
  // "a, b, c" (for messages).
  std::string IdList() const;
};

FeatureModel LoadFeatureModel(const std::string& path);
FeatureModel FeatureModelFromJson(const io::Json& j, const std::string& where);
io::Json FeatureModelToJson(const FeatureModel& model);

}  // namespace rk::target

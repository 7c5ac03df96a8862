// Target model JSON; format and checks in feature_model.h.
#include "target/feature_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "io/error.h"

namespace rk::target {

int FeatureModel::Find(std::string_view id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id, [](const std::string& a, std::string_view b) {
    return std::string_view(a) < b;
  });
  if (it == ids.end() || *it != id) return -1;
  return static_cast<int>(it - ids.begin());
}

double FeatureModel::Planarity() const {
  if (p_body.size() < 3) return 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : p_body) c += p;
  c /= static_cast<double>(p_body.size());
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const auto& p : p_body) S += (p - c) * (p - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(S);
  const double l1 = es.eigenvalues()(2);
  return l1 > 0 ? std::max(0.0, es.eigenvalues()(0)) / l1 : 0.0;
}

std::string FeatureModel::IdList() const {
  std::string s;
  for (const auto& id : ids) s += (s.empty() ? "" : ", ") + id;
  return s;
}

FeatureModel FeatureModelFromJson(const io::Json& j, const std::string& where) {
  if (!j.is_object()) throw DataError(where, 0, 0, "target model must be a JSON object");
  if (!j.contains("points")) {
    throw DataError(where, 0, 0, "missing field 'points' (expected {\"points\": {\"<id>\": [x, y, z], ...}})");
  }
  const io::Json& pts = j.at("points");
  if (!pts.is_object()) throw DataError(where, 0, 0, "field 'points' must be an object of id: [x, y, z]");
  FeatureModel m;
  m.source = where;
  constexpr double kMaxCoordM = 1e4;
  for (auto it = pts.begin(); it != pts.end(); ++it) {
    const std::string& id = it.key();
    const std::string at = "point '" + id + "'";
    if (id.empty()) throw DataError(where, 0, 0, "empty point id");
    for (unsigned char ch : id) {
      if (ch < 0x20 || ch == ',' || ch == '"' || ch == 0x7f) {
        throw DataError(where, 0, 0, at + ": ids must be printable and contain no ',' or '\"'");
      }
    }
    const io::Json& v = it.value();
    if (!v.is_array() || v.size() != 3) throw DataError(where, 0, 0, at + " must be an array [x, y, z] (m)");
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) {
      if (!v[static_cast<std::size_t>(k)].is_number()) {
        throw DataError(where, 0, 0, at + ": coordinates must be numbers (m)");
      }
      p(k) = v[static_cast<std::size_t>(k)].get<double>();
      if (!std::isfinite(p(k)) || std::abs(p(k)) > kMaxCoordM) {
        throw DataError(where, 0, 0, at + ": coordinates must be finite and within 10 km of the body origin");
      }
    }
    m.ids.push_back(id);
    m.p_body.push_back(p);
  }
  {  // keep ids sorted (Find uses binary search) whatever order the JSON library iterates in
    std::vector<std::size_t> order(m.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return m.ids[a] < m.ids[b]; });
    FeatureModel sorted;
    sorted.source = m.source;
    for (std::size_t i : order) {
      sorted.ids.push_back(m.ids[i]);
      sorted.p_body.push_back(m.p_body[i]);
    }
    m = std::move(sorted);
  }
  if (m.size() < 4) {
    throw DataError(where, 0, 0,
                    "the target model has " + std::to_string(m.size()) + " points; a pose needs at least 4");
  }
  for (std::size_t a = 0; a < m.size(); ++a) {
    for (std::size_t b = a + 1; b < m.size(); ++b) {
      if ((m.p_body[a] - m.p_body[b]).norm() < 1e-6) {
        throw DataError(where, 0, 0, "points '" + m.ids[a] + "' and '" + m.ids[b] + "' coincide");
      }
    }
  }
  // Collinear: the second-largest scatter eigenvalue vanishes.
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : m.p_body) c += p;
  c /= static_cast<double>(m.size());
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const auto& p : m.p_body) S += (p - c) * (p - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(S);
  if (!(es.eigenvalues()(1) > 1e-10 * es.eigenvalues()(2))) {
    throw DataError(where, 0, 0, "the target model's points are collinear: the attitude about that line is undetermined");
  }
  return m;
}

FeatureModel LoadFeatureModel(const std::string& path) { return FeatureModelFromJson(io::LoadJson(path), path); }

io::Json FeatureModelToJson(const FeatureModel& model) {
  io::Json pts = io::Json::object();
  for (std::size_t i = 0; i < model.size(); ++i) {
    pts[model.ids[i]] = {model.p_body[i].x(), model.p_body[i].y(), model.p_body[i].z()};
  }
  return io::Json{{"points", pts}};
}

}  // namespace rk::target

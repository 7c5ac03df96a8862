// Random PnP problems; geometries in attitude_problems.h.
#include "sim/attitude_problems.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace rk::sim {
namespace {

Eigen::Matrix3d UniformRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  return q.toRotationMatrix();
}

// Rotation whose z axis is tilted by `tilt` from the camera's z axis towards azimuth `phi`,
// then spun about its own z by `spin`.
Eigen::Matrix3d TiltedRotation(double tilt, double phi, double spin) {
  const Eigen::Vector3d axis(-std::sin(phi), std::cos(phi), 0.0);
  return Eigen::AngleAxisd(tilt, axis).toRotationMatrix() * Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ());
}

}  // namespace

bool ParsePnpGeometry(const std::string& name, PnpGeometry* g) {
  if (name == "box") {
    *g = PnpGeometry::kBox;
  } else if (name == "planar") {
    *g = PnpGeometry::kPlanar;
  } else if (name == "narrow") {
    *g = PnpGeometry::kNarrow;
  } else if (name == "narrow-planar") {
    *g = PnpGeometry::kNarrowPlanar;
  } else {
    return false;
  }
  return true;
}

std::string PnpGeometryName(PnpGeometry g) {
  switch (g) {
    case PnpGeometry::kBox:
      return "box";
    case PnpGeometry::kPlanar:
      return "planar";
    case PnpGeometry::kNarrow:
      return "narrow";
    case PnpGeometry::kNarrowPlanar:
      return "narrow-planar";
  }
  return "?";
}

bool PnpProblemOptions::Check(std::string* why) const {
  if (min_points < 3 || max_points < min_points || max_points > 1000) {
    *why = "points per problem must satisfy 3 <= min <= max <= 1000";
    return false;
  }
  if (!(noise_min_px >= 0.0) || !(noise_max_px >= noise_min_px) || !std::isfinite(noise_max_px)) {
    *why = "pixel noise range must satisfy 0 <= min <= max";
    return false;
  }
  if (!(min_tilt_rad >= 0.0 && max_tilt_rad >= min_tilt_rad && max_tilt_rad < 1.5)) {
    *why = "tilt range must satisfy 0 <= min <= max < 1.5 rad";
    return false;
  }
  return true;
}

Eigen::Matrix3d RandomRotation(std::uint64_t seed, std::uint64_t index) {
  std::seed_seq ss{seed, index, std::uint64_t{77}};
  std::mt19937_64 rng(ss);
  return UniformRotation(rng);
}

PnpProblem MakePnpProblem(const PnpProblemOptions& o, std::uint64_t index) {
  std::seed_seq ss{o.seed, index};
  std::mt19937_64 rng(ss);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  auto uni = [&](double a, double b) { return a + (b - a) * u01(rng); };
  std::normal_distribution<double> gauss(0.0, 1.0);

  PnpProblem pb;
  const bool narrow = o.geometry == PnpGeometry::kNarrow || o.geometry == PnpGeometry::kNarrowPlanar;
  if (narrow) {
    pb.width_px = 2448;
    pb.height_px = 2048;
    pb.fx = pb.fy = 100.0 / 0.00345;
    pb.cx = 1223.5;
    pb.cy = 1023.5;
  }
  const int n = o.min_points + static_cast<int>(std::floor(u01(rng) * (o.max_points - o.min_points + 1)));
  pb.noise_px = uni(o.noise_min_px, o.noise_max_px);

  for (int attempt = 0; attempt < 1000; ++attempt) {
    pb.p_body.clear();
    pb.px_true.clear();
    switch (o.geometry) {
      case PnpGeometry::kBox: {
        std::vector<Eigen::Vector3d> X(static_cast<std::size_t>(n));
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (auto& x : X) {
          x = Eigen::Vector3d(uni(-2, 2), uni(-2, 2), uni(4, 8));
          c += x;
        }
        c /= n;
        pb.R_cam_body = UniformRotation(rng);
        pb.t_cam = c;
        for (const auto& x : X) pb.p_body.push_back(pb.R_cam_body.transpose() * (x - c));
        break;
      }
      case PnpGeometry::kPlanar:
      case PnpGeometry::kNarrowPlanar: {
        const double half = narrow ? 0.35 : 2.0;
        for (int i = 0; i < n; ++i) pb.p_body.emplace_back(uni(-half, half), uni(-half, half), 0.0);
        pb.R_cam_body = TiltedRotation(uni(o.min_tilt_rad, o.max_tilt_rad), uni(0, 2 * M_PI), uni(0, 2 * M_PI));
        const double depth = narrow ? uni(15, 25) : uni(4, 8);
        const double off = narrow ? 0.005 : 0.1;
        pb.t_cam = depth * Eigen::Vector3d(uni(-off, off), uni(-off, off), 1.0);
        break;
      }
      case PnpGeometry::kNarrow: {
        for (int i = 0; i < n; ++i) pb.p_body.emplace_back(uni(-0.35, 0.35), uni(-0.35, 0.35), uni(-0.15, 0.15));
        pb.R_cam_body = UniformRotation(rng);
        pb.t_cam = uni(15, 25) * Eigen::Vector3d(uni(-0.005, 0.005), uni(-0.005, 0.005), 1.0);
        break;
      }
    }
    bool good = true;
    for (const auto& p : pb.p_body) {
      const Eigen::Vector3d X = pb.R_cam_body * p + pb.t_cam;
      if (!(X.z() > 0.1)) {
        good = false;
        break;
      }
      const Eigen::Vector2d uv(pb.fx * X.x() / X.z() + pb.cx, pb.fy * X.y() / X.z() + pb.cy);
      if (uv.x() < 0 || uv.y() < 0 || uv.x() > pb.width_px - 1 || uv.y() > pb.height_px - 1) {
        good = false;
        break;
      }
      pb.px_true.push_back(uv);
    }
    if (good) break;
  }
  pb.px.clear();
  for (const auto& uv : pb.px_true) {
    pb.px.emplace_back(uv.x() + pb.noise_px * gauss(rng), uv.y() + pb.noise_px * gauss(rng));
  }
  return pb;
}

}  // namespace rk::sim

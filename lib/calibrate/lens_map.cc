// The pixel map of a calibrated lens: its difference from another model over the image (absolute, and after the
// best common rotation of the rays), and its predicted error from the intrinsics' covariance.
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "calibrate/lens_calibration.h"

namespace rk::calibrate {
namespace {

// Grid pixels, every `step_px`, of a w × h image.
std::vector<Eigen::Vector2d> MapGrid(int w, int h, int step_px) {
  std::vector<Eigen::Vector2d> g;
  for (int y = 0; y < h; y += step_px) {
    for (int x = 0; x < w; x += step_px) g.emplace_back(x, y);
  }
  return g;
}

// Finite-difference steps: pixels for fx, fy, cx, cy; dimensionless for the distortion coefficients.
constexpr double kMapStepPx = 1e-3;
constexpr double kMapStepDistortion = 1e-6;
// Small-rotation step (rad) for the pixel displacement of a rotated ray.
constexpr double kMapStepRotation = 1e-6;

// `cam` with intrinsic j (fx, fy, cx, cy, k1, k2, p1, p2, k3) moved by h.
camera::CameraModel Perturbed(const camera::CameraModel& cam, int j, double h) {
  camera::CameraModel b = cam;
  if (j == 0) b.focal_length_mm = (cam.fx() + h) * cam.pixel_size_mm[0];
  if (j <= 1) b.pixel_size_mm[1] = b.focal_length_mm / (cam.fy() + (j == 1 ? h : 0.0));
  if (j == 2) b.principal_point_px.x() += h;
  if (j == 3) b.principal_point_px.y() += h;
  if (j >= 4) b.distortion[static_cast<std::size_t>(j - 4)] += h;
  return b;
}

// Pixel displacement d(pixel)/d(ω) of the grid's rays rotated by a small ω about the camera axes (2n × 3).
Eigen::MatrixXd RotationFields(const camera::CameraModel& cam, const std::vector<Eigen::Vector2d>& grid) {
  Eigen::MatrixXd R(2 * static_cast<Eigen::Index>(grid.size()), 3);
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const Eigen::Vector3d ray = cam.NormalisedRay(grid[g]);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d w = kMapStepRotation * Eigen::Vector3d::Unit(k);
      const Eigen::Vector2d d =
          (*cam.Project(ray + w.cross(ray)) - *cam.Project(ray - w.cross(ray))) / (2 * kMapStepRotation);
      R.block<2, 1>(2 * static_cast<Eigen::Index>(g), k) = d;
    }
  }
  return R;
}

// Removes from the columns of `G` (2n × m) their least-squares fit by the rotation fields `R`.
Eigen::MatrixXd WithoutRotation(const Eigen::MatrixXd& G, const Eigen::MatrixXd& R) {
  return G - R * (R.transpose() * R).ldlt().solve(R.transpose() * G);
}

}  // namespace

double MapDifferenceRmsPx(const camera::CameraModel& a, const camera::CameraModel& b, int step_px) {
  double ss = 0;
  std::size_t n = 0;
  for (const Eigen::Vector2d& px : MapGrid(a.width_px, a.height_px, step_px)) {
    const auto q = b.Project(a.NormalisedRay(px));
    if (!q) continue;
    ss += (*q - px).squaredNorm();
    ++n;
  }
  return n ? std::sqrt(ss / static_cast<double>(n)) : 0.0;
}

double MapDifferenceModuloRotationRmsPx(const camera::CameraModel& a, const camera::CameraModel& b, int step_px) {
  const std::vector<Eigen::Vector2d> grid = MapGrid(a.width_px, a.height_px, step_px);
  std::vector<Eigen::Vector3d> rays;
  for (const auto& px : grid) rays.push_back(a.NormalisedRay(px));
  Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
  double rms = 0;
  for (int it = 0; it < 4; ++it) {  // Gauss–Newton over the rotation; the misfit is nearly linear in it
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    double ss = 0;
    for (std::size_t g = 0; g < grid.size(); ++g) {
      const Eigen::Vector3d ray = rot * rays[g];
      const Eigen::Vector2d p = *b.Project(ray), e = p - grid[g];
      Eigen::Matrix<double, 2, 3> J;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d w = kMapStepRotation * Eigen::Vector3d::Unit(k);
        J.col(k) = (*b.Project(ray + w.cross(ray)) - *b.Project(ray - w.cross(ray))) / (2 * kMapStepRotation);
      }
      A += J.transpose() * J;
      rhs += J.transpose() * e;
      ss += e.squaredNorm();
    }
    rms = std::sqrt(ss / static_cast<double>(grid.size()));
    const Eigen::Vector3d w = -A.ldlt().solve(rhs);
    rot = Eigen::AngleAxisd(w.norm(), w.norm() > 0 ? Eigen::Vector3d(w.normalized()) : Eigen::Vector3d::UnitZ()) * rot;
  }
  return rms;
}

MapSigma PredictedMapSigma(const camera::CameraModel& cam, const Eigen::Matrix<double, 9, 9>& cov, int step_px) {
  const std::vector<Eigen::Vector2d> grid = MapGrid(cam.width_px, cam.height_px, step_px);
  std::vector<Eigen::Vector3d> rays;
  for (const auto& px : grid) rays.push_back(cam.NormalisedRay(px));
  const Eigen::Index n2 = 2 * static_cast<Eigen::Index>(grid.size());
  Eigen::MatrixXd G(n2, 9);  // d(pixel of the true ray under the estimated model)/d(intrinsic j)
  for (int j = 0; j < 9; ++j) {
    const double h = j < 4 ? kMapStepPx : kMapStepDistortion;
    const camera::CameraModel plus = Perturbed(cam, j, h), minus = Perturbed(cam, j, -h);
    for (std::size_t g = 0; g < grid.size(); ++g) {
      G.block<2, 1>(2 * static_cast<Eigen::Index>(g), j) = (*plus.Project(rays[g]) - *minus.Project(rays[g])) / (2 * h);
    }
  }
  const auto rms = [&](const Eigen::MatrixXd& M) {
    // trace(M C Mᵀ) without the 2n × 2n product
    return std::sqrt(std::max(0.0, (M * cov).cwiseProduct(M).sum()) / static_cast<double>(grid.size()));
  };
  MapSigma s;
  s.rms_px = rms(G);
  s.modulo_rotation_rms_px = rms(WithoutRotation(G, RotationFields(cam, grid)));
  return s;
}

}  // namespace rk::calibrate

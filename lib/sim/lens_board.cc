#include "sim/lens_board.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace rk::sim {
namespace {

double LensBoardClamp01(double v) { return std::clamp(v, 0.0, 1.0); }

}  // namespace

BoardTexture ChessboardTexture(int cols, int rows, double square_mm) {
  return [=](double x, double y) {
    const double u = x / square_mm, v = y / square_mm;
    if (u < -2 || v < -2 || u > cols + 1 || v > rows + 1) return 0.5;  // beyond the margin
    if (u < -1 || v < -1 || u > cols || v > rows) return 1.0;          // white margin
    const long s = static_cast<long>(std::floor(u)) + static_cast<long>(std::floor(v));
    return (s % 2 == 0) ? 0.0 : 1.0;
  };
}

BoardTexture CircleGridTexture(int cols, int rows, double square_mm) {
  return [=](double x, double y) {
    const double u = x / square_mm, v = y / square_mm;
    if (u < -2 || v < -2 || u > 2 * cols + 1 || v > rows + 1) return 0.5;
    const int i = static_cast<int>(std::lround(v));
    if (i < 0 || i >= rows) return 1.0;
    // Nearest circle centre in row i: u = 2j + i mod 2.
    const int j = static_cast<int>(std::lround((u - i % 2) / 2.0));
    if (j < 0 || j >= cols) return 1.0;
    const double du = u - (2 * j + i % 2), dv = v - i;
    return du * du + dv * dv <= 0.25 ? 0.0 : 1.0;
  };
}

BoardTexture ImageTexture(const cv::Mat& gray8, double mm_per_px) {
  cv::Mat img = gray8.clone();
  return [img, mm_per_px](double x, double y) {
    const double u = x / mm_per_px - 0.5, v = y / mm_per_px - 0.5;
    if (u < 0 || v < 0 || u > img.cols - 1 || v > img.rows - 1) return 0.5;
    const int u0 = std::min(static_cast<int>(u), img.cols - 2), v0 = std::min(static_cast<int>(v), img.rows - 2);
    const double a = u - u0, b = v - v0;
    const auto g = [&](int r, int c) { return img.at<std::uint8_t>(r, c) / 255.0; };
    return (1 - b) * ((1 - a) * g(v0, u0) + a * g(v0, u0 + 1)) + b * ((1 - a) * g(v0 + 1, u0) + a * g(v0 + 1, u0 + 1));
  };
}

BoardRenderer::BoardRenderer(const camera::CameraModel& cam) : cam_(cam) {
  const int W = cam.width_px + 1, H = cam.height_px + 1;
  corner_rays_.resize(static_cast<std::size_t>(W) * static_cast<std::size_t>(H));
  const camera::Intrinsics in = cam.ToIntrinsics();
  Eigen::Vector2d n(0.0, 0.0);  // Newton from the neighbouring corner's solution: 2–3 steps each
  for (int r = 0; r < H; ++r) {
    for (int c = 0; c < W; ++c) {
      n = camera::NormalisedFromPixel(in, Eigen::Vector2d(c - 0.5, r - 0.5), c == 0 ? nullptr : &n);
      corner_rays_[static_cast<std::size_t>(r) * static_cast<std::size_t>(W) + static_cast<std::size_t>(c)] = {n.x(), n.y()};
    }
  }
}

cv::Mat BoardRenderer::Render(const Eigen::Matrix3d& R_cam_board, const Eigen::Vector3d& t_cam_board_mm,
                              const BoardTexture& texture, const BoardViewOptions& opt) const {
  const int W = cam_.width_px + 1;
  // Board coordinates of every pixel corner (NaN where the ray misses the plane's front).
  const Eigen::Vector3d n = R_cam_board.col(2);
  const double nt = n.dot(t_cam_board_mm);
  std::vector<Eigen::Vector2d> board(corner_rays_.size());
  for (std::size_t k = 0; k < corner_rays_.size(); ++k) {
    const Eigen::Vector3d d(corner_rays_[k].x(), corner_rays_[k].y(), 1.0);
    const double lambda = nt / n.dot(d);
    if (!(lambda > 0)) {
      board[k] = Eigen::Vector2d::Constant(std::nan(""));
      continue;
    }
    board[k] = (R_cam_board.transpose() * (lambda * d - t_cam_board_mm)).head<2>();
  }
  std::mt19937_64 rng(opt.seed);
  std::normal_distribution<double> noise(0.0, opt.noise_dn);
  cv::Mat img(cam_.height_px, cam_.width_px, CV_8UC1);
  const int S = opt.supersample;
  for (int r = 0; r < cam_.height_px; ++r) {
    for (int c = 0; c < cam_.width_px; ++c) {
      const auto at = [&](int rr, int cc) -> const Eigen::Vector2d& {
        return board[static_cast<std::size_t>(rr) * static_cast<std::size_t>(W) + static_cast<std::size_t>(cc)];
      };
      const Eigen::Vector2d &p00 = at(r, c), &p01 = at(r, c + 1), &p10 = at(r + 1, c), &p11 = at(r + 1, c + 1);
      double refl = 0.5;
      if (std::isfinite(p00.x()) && std::isfinite(p01.x()) && std::isfinite(p10.x()) && std::isfinite(p11.x())) {
        // A pixel whose corners and centre see one reflectance is taken as uniform (board features span many
        // pixels); the others are supersampled.
        const double t00 = texture(p00.x(), p00.y());
        const Eigen::Vector2d mid = 0.25 * (p00 + p01 + p10 + p11);
        if (texture(p01.x(), p01.y()) == t00 && texture(p10.x(), p10.y()) == t00 &&
            texture(p11.x(), p11.y()) == t00 && texture(mid.x(), mid.y()) == t00) {
          refl = t00;
          const double dn = opt.dark_dn + (opt.bright_dn - opt.dark_dn) * refl + (opt.noise_dn > 0 ? noise(rng) : 0.0);
          img.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(std::clamp(std::lround(dn), 0L, 255L));
          continue;
        }
        double sum = 0;
        for (int a = 0; a < S; ++a) {
          const double fy = (a + 0.5) / S;
          for (int b = 0; b < S; ++b) {
            const double fx = (b + 0.5) / S;
            const Eigen::Vector2d p = (1 - fy) * ((1 - fx) * p00 + fx * p01) + fy * ((1 - fx) * p10 + fx * p11);
            sum += texture(p.x(), p.y());
          }
        }
        refl = LensBoardClamp01(sum / (S * S));
      }
      const double dn = opt.dark_dn + (opt.bright_dn - opt.dark_dn) * refl + (opt.noise_dn > 0 ? noise(rng) : 0.0);
      img.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(std::clamp(std::lround(dn), 0L, 255L));
    }
  }
  return img;
}

std::vector<BoardPose> VariedBoardPoses(const camera::CameraModel& cam, double x0, double y0, double x1, double y1,
                                        int n, std::uint64_t seed, const BoardPoseSpread& spread) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double pi = 3.14159265358979323846;
  const Eigen::Vector3d centre(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0);
  const Eigen::Vector3d outline[4] = {{x0, y0, 0}, {x1, y0, 0}, {x0, y1, 0}, {x1, y1, 0}};
  std::vector<BoardPose> poses;
  for (int tries = 0; static_cast<int>(poses.size()) < n && tries < 10000 * n; ++tries) {
    const double axis_angle = 2 * pi * u01(rng);
    const double tilt = (spread.tilt_min_deg + (spread.tilt_max_deg - spread.tilt_min_deg) * u01(rng)) * pi / 180;
    const double turn = (-spread.turn_deg + 2 * spread.turn_deg * u01(rng)) * pi / 180;
    const Eigen::Vector3d axis(std::cos(axis_angle), std::sin(axis_angle), 0.0);
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(tilt, axis) * Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    const double fill = spread.fill_min + (spread.fill_max - spread.fill_min) * u01(rng);
    const double dist = cam.fx() * (x1 - x0) / (fill * cam.width_px);
    const double a0 = 0.5 * (1 - spread.aim_fraction);
    const Eigen::Vector2d aim(cam.width_px * (a0 + spread.aim_fraction * u01(rng)),
                              cam.height_px * (a0 + spread.aim_fraction * u01(rng)));
    const Eigen::Vector3d ray = cam.NormalisedRay(aim);
    const Eigen::Vector3d t = ray.normalized() * dist - R * centre;
    bool inside = true;
    for (const auto& q : outline) {
      const auto px = cam.Project(R * q + t);
      inside = inside && px && px->x() > 2 && px->y() > 2 && px->x() < cam.width_px - 3 && px->y() < cam.height_px - 3;
    }
    if (inside) poses.push_back({R, t});
  }
  return poses;
}

}  // namespace rk::sim

// Synthetic images of a planar calibration board seen by a camera with distortion (the truth behind
// rk-calibrate lens's tests and benchmark).
//
// Each pixel is rendered by inverse mapping: the undistorted rays of the pixel's four corners
// (Newton inversion of SPEC.md §3's distortion to 1e-15) are
// intersected with the board plane p_cam = R_cam_board p_board + t_cam_board (board z = 0), and the
// board's reflectance is averaged over supersample² points of the pixel, bilinear between its corners
// (the mapping is smooth over one pixel: the error is second order, far below 0.01 px). Pixels are
// OpenCV's: (0, 0) is the centre of the top-left pixel, which covers [−0.5, 0.5]².
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "camera/camera_model.h"

namespace rk::sim {

// Reflectance in [0, 1] of the board at board coordinates (mm).
using BoardTexture = std::function<double(double x_mm, double y_mm)>;

// Chessboard with cols × rows inner corners at (c · square, r · square), c < cols, r < rows (OpenCV's
// patternSize and object points), a one-square white margin around the squares, grey (0.5) beyond.
BoardTexture ChessboardTexture(int cols, int rows, double square_mm);
// OpenCV's asymmetric circle grid: circle (row i, column j) centred at ((2j + i mod 2) s, i s), radius 0.5 s,
// black on white with a margin of 2 s, grey beyond.
BoardTexture CircleGridTexture(int cols, int rows, double square_mm);
// An 8-bit image laid on the board: pixel (u, v) (centre) at board (u + 0.5, v + 0.5) · mm_per_px (the
// image's top-left corner at the board origin), bilinear; grey outside.
BoardTexture ImageTexture(const cv::Mat& gray8, double mm_per_px);

struct BoardViewOptions {
  int supersample = 4;       // samples per pixel side
  double dark_dn = 30.0;     // grey value of reflectance 0
  double bright_dn = 220.0;  // grey value of reflectance 1
  double noise_dn = 1.0;     // Gaussian noise, 1σ (DN)
  std::uint64_t seed = 1;
};

class BoardRenderer {
 public:
  explicit BoardRenderer(const camera::CameraModel& cam);
  // An 8-bit image of the board at pose (R_cam_board, t_cam_board_mm).
  cv::Mat Render(const Eigen::Matrix3d& R_cam_board, const Eigen::Vector3d& t_cam_board_mm, const BoardTexture& texture,
                 const BoardViewOptions& opt) const;

 private:
  camera::CameraModel cam_;
  std::vector<Eigen::Vector2d> corner_rays_;  // (w + 1) × (h + 1) pixel-corner rays (xn, yn), row-major
};

struct BoardPose {
  Eigen::Matrix3d R_cam_board;
  Eigen::Vector3d t_cam_board_mm;
};

// The spread of VariedBoardPoses (defaults: its original, moderate set).
struct BoardPoseSpread {
  double tilt_min_deg = 10, tilt_max_deg = 40;  // tilt about a random in-plane axis
  double turn_deg = 30;                         // in-plane turn, ±
  double fill_min = 0.30, fill_max = 0.60;      // board outline width / image width (before the tilt)
  double aim_fraction = 0.8;                    // board centre aimed anywhere in this middle fraction of the image
};

// `n` varied views of a board spanning [x0, x1] × [y0, y1] mm (its outline, margin included): tilts about
// random in-plane axes, in-plane turns, the board filling part of the image width, aimed anywhere in the
// middle of the image as `spread` says, keeping the whole outline inside the image. Deterministic in `seed`.
std::vector<BoardPose> VariedBoardPoses(const camera::CameraModel& cam, double x0, double y0, double x1, double y1,
                                        int n, std::uint64_t seed, const BoardPoseSpread& spread = {});

}  // namespace rk::sim

// Lens calibration (rk-calibrate lens): intrinsics and OpenCV (k1, k2, p1, p2, k3) distortion from
// images of a planar board, with the 1σ of every estimated parameter.
//
// Model (SPEC.md §3, OpenCV's): a board point P_board = (X, Y, 0) seen in view i at
//   p_cam = R_i P_board + t_i,  m = (p_cam.x / p_cam.z, p_cam.y / p_cam.z),
//   pixel = (fx xd + cx, fy yd + cy),  (xd, yd) = distort(m; k1, k2, p1, p2, k3).
// Solved by Zhang's method (Z. Zhang, "A flexible new technique for camera calibration", PAMI 2000) as
// OpenCV's cv::calibrateCamera does it: closed-form initialisation from the board homographies, then
// Levenberg–Marquardt over intrinsics and every view's pose, minimising the sum of squared pixel
// residuals. The covariance of the intrinsics is s² (JᵀJ)⁻¹ with the poses marginalised, s² = Σr² / (2N −
// parameters) over the 2N residual components (OpenCV's own 1σ divide by N − parameters: √2 too large); it
// assumes independent corner errors of equal variance. From it, the predicted error of the pixel map.
//
// Robustness: views without a board are listed and skipped; a view whose RMS exceeds
// reject_ratio × the median view RMS (and kRejectFloorPx) is rejected and the solve repeated until none
// is; fewer than min_views usable views is a ProcessingError (exit 1) naming the reason.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "camera/camera_model.h"
#include "io/json_util.h"
#include "io/options.h"
#include "io/run_summary.h"

namespace rk::calibrate {

enum class BoardKind { kChessboard, kCircles, kCharuco };
std::string BoardKindName(BoardKind k);  // "chessboard", "circles", "charuco"

// ArUco dictionaries of a ChArUco board (cv::aruco::PREDEFINED_DICTIONARY_NAME).
enum class ArucoDictionary { k4x4_50, k5x5_100, k6x6_250, kOriginal };
std::string ArucoDictionaryName(ArucoDictionary d);  // "4x4_50", "5x5_100", "6x6_250", "original"

// A view whose RMS is above kRejectRatio × the median view RMS is rejected (default of --reject-ratio) ...
inline constexpr double kRejectRatio = 3.0;
// ... but never one below this RMS (px): with good corners (0.02–0.1 px) a 3× spread is noise, not a bad view.
inline constexpr double kRejectFloorPx = 0.1;
// Warnings: a focal length or principal point whose 1σ exceeds this fraction of its value ...
inline constexpr double kSigmaWarnRatio = 0.01;
// ... or a distortion coefficient within its 1σ of zero whose 1σ moves the image corner by more than this (px).
inline constexpr double kDistortionSigmaWarnPx = 0.5;
// ChArUco: a view needs this many interpolated corners (OpenCV needs ≥ 4 non-collinear for a homography).
inline constexpr int kMinCharucoCorners = 6;

struct LensOptions {
  BoardKind board = BoardKind::kChessboard;
  int cols = 9;                // chessboard: inner corners per row; circles: circles per row; charuco: squares
  int rows = 6;                // the same per column
  double square_mm = 25.0;     // chessboard/charuco square side; circles: OpenCV's squareSize (half the spacing in a row)
  double marker_mm = 0.0;      // charuco: ArUco marker side (0 = not given)
  ArucoDictionary dictionary = ArucoDictionary::k4x4_50;
  double pixel_size_mm = 0.00345;  // sensor pixel pitch in x (focal_length_mm = fx · this)
  bool fix_k3 = false;
  bool fix_aspect = false;           // fx = fy
  bool fix_principal_point = false;  // (cx, cy) = image centre ((w − 1) / 2, (h − 1) / 2)
  bool zero_tangent = false;         // p1 = p2 = 0
  bool subpix = false;               // chessboard: refine findChessboardCornersSB's corners with cv::cornerSubPix
  // Chessboard: search images larger than this (longer side, px) on a scaled copy, then find the corners at full
  // size in the board's box only (findChessboardCornersSB's cost grows with the pixel count: 5× less on the
  // 5 Mpx views of bench_lens_calibration, with a smaller residual, docs/benchmarks.md); 0 = full-size search.
  int detect_max_px = 1600;
  double reject_ratio = kRejectRatio;
  int min_views = 3;
  int threads = 0;  // board detection threads (0 = one per core)

  static const io::OptionTable<LensOptions>& Table();
  // The table's bounds, then: --marker-mm given and < --square-mm for charuco.
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
  int OpenCvFlags() const;  // cv::CALIB_* of the fix options
};

// One image: where it came from, what was found and what became of it.
struct LensView {
  std::string name;                     // image path (or "video.mkv#12": frame 12 of a video)
  bool found = false;                   // a board was detected
  bool used = false;                    // in the final solve
  std::string reason;                   // why not used: "no board", "rms 2.3 px > 3 x median 0.21 px"
  double rms_px = 0.0;                  // reprojection RMS under the final model (found views)
  std::vector<cv::Point2f> image_px;    // detected corners / circle centres
  std::vector<cv::Point3f> board_mm;    // their board coordinates (z = 0)
  std::vector<cv::Point2f> residual_px; // detected − reprojected, under the final model (found views)
};

// 1σ of the estimated parameters; 0 for a fixed one.
struct LensSigma {
  double fx_px = 0, fy_px = 0, cx_px = 0, cy_px = 0;
  std::array<double, 5> distortion{};  // k1, k2, p1, p2, k3
};

// Predicted error of the calibrated pixel map (from the intrinsics' covariance), RMS over the image (px).
struct MapSigma {
  double rms_px = 0.0;                  // as MapDifferenceRmsPx measures it against the truth
  double modulo_rotation_rms_px = 0.0;  // what is left after the best common rotation of the rays (a mount or
                                        // pointing calibration absorbs that rotation: most of a principal-point error)
};

struct LensResult {
  int width_px = 0, height_px = 0;
  camera::CameraModel camera;  // the calibrated model (SPEC.md §3)
  LensSigma sigma;
  // Covariance of (fx, fy, cx, cy, k1, k2, p1, p2, k3) (px, px, px, px, 1, ...), the views' poses marginalised;
  // rows and columns of fixed terms 0. The σ above are the roots of its diagonal.
  Eigen::Matrix<double, 9, 9> covariance = Eigen::Matrix<double, 9, 9>::Zero();
  MapSigma map_sigma;           // PredictedMapSigma of camera and covariance
  double rms_px = 0.0;          // over every corner of the used views
  int solves = 0;               // calibrateCamera runs (1 + rejection rounds)
  std::vector<LensView> views;  // in input order
  std::vector<std::string> warnings;
  double detect_s = 0.0, solve_s = 0.0;

  int ViewsUsed() const;
  int ViewsWithoutBoard() const;
  int ViewsRejected() const;  // found but not used
  // The camera JSON (SPEC.md §3) with its "calibration" object.
  io::Json CameraJson(const LensOptions& opt, const std::string& date_utc) const;
  // The report's "summary": rms_px, views, focal length and principal point with their 1σ.
  io::Json SummaryJson() const;
  // The run's summary (io/run_summary.h): the 1σ warnings (code "poorly_determined"), the RMS reprojection
  // error as headline, and the report's "summary". No rows_by_status: the product is a camera model.
  io::RunSummary Summary() const;
};

// Detects the board of `opt` in an 8-bit grey image; fills view->found, image_px, board_mm.
void DetectBoard(const cv::Mat& gray8, const LensOptions& opt, LensView* view);

// Calibrates from views already detected (image size w × h). Views not found stay unused ("no board").
// Throws ProcessingError when fewer than opt.min_views views are usable.
LensResult SolveLens(std::vector<LensView> views, int width_px, int height_px, const LensOptions& opt);

// Reads every frame of every `inputs` entry (a file, an image-sequence pattern, a video: video::FrameSource),
// detects the board in each (opt.threads at a time) and solves. `progress(n)` after each frame read.
LensResult CalibrateLens(const std::vector<std::string>& inputs, const LensOptions& opt,
                         const std::function<void(std::int64_t)>& progress = {});

// Difference of two models' pixel maps over the image: for a grid of pixels (every `step_px`) of `a`, the ray
// a sees there, projected by `b`; RMS of the pixel differences (px). Same image size assumed.
double MapDifferenceRmsPx(const camera::CameraModel& a, const camera::CameraModel& b, int step_px = 8);
// The same after rotating a's rays by the rotation that minimises it: the map error left once a mount or
// pointing calibration (which estimates the camera's orientation) has absorbed the common rotation.
double MapDifferenceModuloRotationRmsPx(const camera::CameraModel& a, const camera::CameraModel& b, int step_px = 8);
// The expected RMS (over a grid every `step_px`) of MapDifferenceRmsPx(truth, estimate) and of the modulo-rotation
// figure, for an estimate `cam` with the covariance `cov` of (fx, fy, cx, cy, k1, k2, p1, p2, k3), linearised
// (central differences of the map in every parameter).
MapSigma PredictedMapSigma(const camera::CameraModel& cam, const Eigen::Matrix<double, 9, 9>& cov, int step_px = 8);

// The PNG (encoded bytes) of residual vectors over the image, exaggerated (scale written on the image), and of
// the image's coverage by board corners (cells shaded by count).
std::string LensPlotPng(const LensResult& res);

}  // namespace rk::calibrate

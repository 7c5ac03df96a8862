// Board detection for lens calibration: chessboard corners (cv::findChessboardCornersSB, sub-pixel by
// construction), asymmetric circle-grid centres (cv::findCirclesGrid) and ChArUco corners (contrib aruco:
// markers, then the chessboard corners between them, interpolated and refined).
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "calibrate/lens_calibration.h"

namespace rk::calibrate {
namespace {

// Smallest spacing between neighbouring corners of a row (px).
double RowSpacing(const std::vector<cv::Point2f>& corners, int cols, int rows) {
  double spacing = 1e9;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      const std::size_t k = static_cast<std::size_t>(r * cols + c);
      spacing = std::min(spacing, static_cast<double>(cv::norm(corners[k + 1] - corners[k])));
    }
  }
  return spacing;
}

// cv::cornerSubPix with a half-window of `half_px` clamped to 2–7 px and a tight stop (1e-4 px).
void SubPixel(const cv::Mat& gray, double half_px, std::vector<cv::Point2f>* corners) {
  const int half = std::clamp(static_cast<int>(half_px), 2, 7);
  cv::cornerSubPix(gray, *corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
}

// Chessboard corners refined in a window of 0.3 × `spacing`, the smallest corner spacing.
void RefineCorners(const cv::Mat& gray, double spacing, std::vector<cv::Point2f>* corners) {
  SubPixel(gray, 0.3 * spacing, corners);
}

// findChessboardCornersSB on `gray`; or, for an image larger than opt.detect_max_px, the board searched on a copy
// scaled to that size and its corners then found at full resolution by findChessboardCornersSB on the board's
// box only (the inner corners' box grown by two corner spacings: the border squares and the quiet zone the
// search needs). The box is searched without CALIB_CB_NORMALIZE_IMAGE: the histogram equalisation of a crop
// depends on the crop (corners 0.1–0.2 px from the whole frame's with it, 0.02–0.03 px without), and without
// it the corners fit better (residual 0.039 px against the whole frame's 0.070 px on the views of
// bench_lens_calibration). A copy without a board, or a box where the search fails, falls back to the whole
// frame at full size.
bool FindChessboard(const cv::Mat& gray, const LensOptions& opt, std::vector<cv::Point2f>* corners) {
  const cv::Size pattern(opt.cols, opt.rows);
  const int flags = cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY;
  const auto full_size = [&] {
    if (!cv::findChessboardCornersSB(gray, pattern, *corners, flags)) return false;
    if (opt.subpix) RefineCorners(gray, RowSpacing(*corners, opt.cols, opt.rows), corners);
    return true;
  };
  const int longest = std::max(gray.cols, gray.rows);
  if (opt.detect_max_px == 0 || longest <= opt.detect_max_px) return full_size();
  const double scale = static_cast<double>(opt.detect_max_px) / longest;
  cv::Mat small;
  // An explicit size: OpenCV then scales by exactly small / full in each axis.
  cv::resize(gray, small, cv::Size(std::max(1, static_cast<int>(std::lround(gray.cols * scale))),
                                   std::max(1, static_cast<int>(std::lround(gray.rows * scale)))),
             0, 0, cv::INTER_AREA);
  std::vector<cv::Point2f> coarse;
  if (!cv::findChessboardCornersSB(small, pattern, coarse, cv::CALIB_CB_NORMALIZE_IMAGE)) return full_size();
  // INTER_AREA: small pixel i covers full pixels [i / s − 0.5, (i + 1) / s − 0.5], its centre at (i + 0.5) / s − 0.5.
  const double sx = static_cast<double>(small.cols) / gray.cols, sy = static_cast<double>(small.rows) / gray.rows;
  for (auto& p : coarse) {
    p = cv::Point2f(static_cast<float>((p.x + 0.5) / sx - 0.5), static_cast<float>((p.y + 0.5) / sy - 0.5));
  }
  double spacing = 0.0;  // the largest distance between neighbours along a row
  for (std::size_t k = 0; k + 1 < coarse.size(); ++k) {
    if ((k + 1) % static_cast<std::size_t>(opt.cols) != 0) {
      spacing = std::max(spacing, static_cast<double>(cv::norm(coarse[k + 1] - coarse[k])));
    }
  }
  const int margin = static_cast<int>(std::ceil(2.0 * spacing)) + 2;
  cv::Rect box = cv::boundingRect(coarse);
  box = cv::Rect(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin) &
        cv::Rect(0, 0, gray.cols, gray.rows);
  if (!cv::findChessboardCornersSB(gray(box), pattern, *corners, cv::CALIB_CB_ACCURACY)) return full_size();
  for (auto& p : *corners) p += cv::Point2f(static_cast<float>(box.x), static_cast<float>(box.y));
  if (opt.subpix) RefineCorners(gray, RowSpacing(*corners, opt.cols, opt.rows), corners);
  return true;
}

void DetectChessboard(const cv::Mat& gray, const LensOptions& opt, LensView* v) {
  std::vector<cv::Point2f> corners;
  if (!FindChessboard(gray, opt, &corners)) return;
  v->found = true;
  v->image_px = corners;
  for (int r = 0; r < opt.rows; ++r) {
    for (int c = 0; c < opt.cols; ++c) {
      v->board_mm.emplace_back(static_cast<float>(c * opt.square_mm), static_cast<float>(r * opt.square_mm), 0.f);
    }
  }
}

// OpenCV's asymmetric grid (samples/cpp/calibration.cpp): circle (row i, column j) at ((2j + i mod 2) s, i s).
void DetectCircles(const cv::Mat& gray, const LensOptions& opt, LensView* v) {
  cv::SimpleBlobDetector::Params p;
  p.minArea = 10;
  p.maxArea = static_cast<float>(gray.total()) / 8.f;  // the default (5000 px²) misses large circles
  const cv::Ptr<cv::FeatureDetector> blobs = cv::SimpleBlobDetector::create(p);
  std::vector<cv::Point2f> centres;
  if (!cv::findCirclesGrid(gray, cv::Size(opt.cols, opt.rows), centres, cv::CALIB_CB_ASYMMETRIC_GRID, blobs)) return;
  v->found = true;
  v->image_px = centres;
  for (int i = 0; i < opt.rows; ++i) {
    for (int j = 0; j < opt.cols; ++j) {
      v->board_mm.emplace_back(static_cast<float>((2 * j + i % 2) * opt.square_mm),
                               static_cast<float>(i * opt.square_mm), 0.f);
    }
  }
}

cv::aruco::PREDEFINED_DICTIONARY_NAME OpenCvDictionary(ArucoDictionary d) {
  switch (d) {
    case ArucoDictionary::k4x4_50:
      return cv::aruco::DICT_4X4_50;
    case ArucoDictionary::k5x5_100:
      return cv::aruco::DICT_5X5_100;
    case ArucoDictionary::k6x6_250:
      return cv::aruco::DICT_6X6_250;
    case ArucoDictionary::kOriginal:
      return cv::aruco::DICT_ARUCO_ORIGINAL;
  }
  return cv::aruco::DICT_4X4_50;
}

// True when the points span two dimensions (a homography needs them off one line).
bool SpansPlane(const std::vector<cv::Point3f>& p) {
  if (p.size() < 4) return false;
  cv::Mat m(static_cast<int>(p.size()), 2, CV_64F);
  cv::Point2d mean(0, 0);
  for (const auto& q : p) mean += cv::Point2d(q.x, q.y);
  mean *= 1.0 / static_cast<double>(p.size());
  for (int i = 0; i < m.rows; ++i) {
    m.at<double>(i, 0) = p[static_cast<std::size_t>(i)].x - mean.x;
    m.at<double>(i, 1) = p[static_cast<std::size_t>(i)].y - mean.y;
  }
  cv::Mat w;
  cv::SVD::compute(m, w, cv::SVD::NO_UV);
  return w.at<double>(1) > 1e-3 * w.at<double>(0);
}

// OpenCV 4.6's interpolated ChArUco corners lie ≈ 0.47 px right of and below the true corners in both axes
// (0.69 px RMS against the truth on rendered boards; findChessboardCornersSB's agree with the same renderer
// to 0.07 px), an offset the solve absorbs into the principal point. cv::cornerSubPix removes it, with a
// window that stays inside the gap between a corner and its neighbouring markers (a marker centred in its
// square leaves (square − marker) / 2 of the square on each side; the markers' own edges in the window pull
// the corners off: a 0.3 × spacing window did): half-size 0.9 × that gap in pixels, from the markers'
// mean side, 2–7 px. On rendered boards the corners come to 0.07–0.13 px from the truth, unbiased
// (docs/benchmarks.md, "ChArUco").
void RefineCharucoCorners(const cv::Mat& gray, const std::vector<std::vector<cv::Point2f>>& markers,
                          const LensOptions& opt, std::vector<cv::Point2f>* corners) {
  double side = 0.0;
  for (const auto& m : markers) side += 0.25 * cv::arcLength(m, true);
  side /= static_cast<double>(markers.size());
  const double gap_px = side * (opt.square_mm - opt.marker_mm) / (2.0 * opt.marker_mm);
  SubPixel(gray, 0.9 * gap_px, corners);
}

void DetectCharuco(const cv::Mat& gray, const LensOptions& opt, LensView* v) {
  const cv::Ptr<cv::aruco::Dictionary> dict = cv::aruco::getPredefinedDictionary(OpenCvDictionary(opt.dictionary));
  const cv::Ptr<cv::aruco::CharucoBoard> board = cv::aruco::CharucoBoard::create(
      opt.cols, opt.rows, static_cast<float>(opt.square_mm), static_cast<float>(opt.marker_mm), dict);
  std::vector<std::vector<cv::Point2f>> markers;
  std::vector<int> marker_ids;
  cv::aruco::detectMarkers(gray, dict, markers, marker_ids);
  if (marker_ids.empty()) return;
  std::vector<cv::Point2f> corners;
  std::vector<int> ids;
  cv::aruco::interpolateCornersCharuco(markers, marker_ids, gray, board, corners, ids);
  if (static_cast<int>(ids.size()) < kMinCharucoCorners) return;
  RefineCharucoCorners(gray, markers, opt, &corners);
  std::vector<cv::Point3f> obj;
  for (int id : ids) obj.push_back(board->chessboardCorners[static_cast<std::size_t>(id)]);
  if (!SpansPlane(obj)) return;
  v->found = true;
  v->image_px = corners;
  v->board_mm = obj;
}

}  // namespace

void DetectBoard(const cv::Mat& gray8, const LensOptions& opt, LensView* view) {
  view->found = false;
  view->image_px.clear();
  view->board_mm.clear();
  switch (opt.board) {
    case BoardKind::kChessboard:
      DetectChessboard(gray8, opt, view);
      break;
    case BoardKind::kCircles:
      DetectCircles(gray8, opt, view);
      break;
    case BoardKind::kCharuco:
      DetectCharuco(gray8, opt, view);
      break;
  }
  if (!view->found) view->reason = "no board";
}

}  // namespace rk::calibrate

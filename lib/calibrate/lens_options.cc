// LensOptions: the option table of rk-calibrate lens and the OpenCV flags it selects.
#include <opencv2/calib3d.hpp>

#include "calibrate/lens_calibration.h"

namespace rk::calibrate {

std::string BoardKindName(BoardKind k) {
  switch (k) {
    case BoardKind::kChessboard:
      return "chessboard";
    case BoardKind::kCircles:
      return "circles";
    case BoardKind::kCharuco:
      return "charuco";
  }
  return "?";
}

std::string ArucoDictionaryName(ArucoDictionary d) {
  switch (d) {
    case ArucoDictionary::k4x4_50:
      return "4x4_50";
    case ArucoDictionary::k5x5_100:
      return "5x5_100";
    case ArucoDictionary::k6x6_250:
      return "6x6_250";
    case ArucoDictionary::kOriginal:
      return "original";
  }
  return "?";
}

const io::OptionTable<LensOptions>& LensOptions::Table() {
  using B = io::Bounds;
  using O = LensOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Choice("--board", &O::board, {BoardKind::kChessboard, BoardKind::kCircles, BoardKind::kCharuco},
                  BoardKindName,
                  "Board: chessboard (findChessboardCornersSB), circles (asymmetric circle grid), charuco")
          .Integer("--cols", &O::cols, "", B::Closed(2, 1000),
                   "Chessboard: inner corners per row; circles: circles per row; charuco: squares per row")
          .Integer("--rows", &O::rows, "", B::Closed(2, 1000), "The same per column")
          .Real("--square-mm", &O::square_mm, "mm", B::Positive().Finite(),
                "Square side (mm); circles: OpenCV's squareSize = half the centre spacing along a row")
          .Real("--marker-mm", &O::marker_mm, "mm", B::AtLeast(0).Finite(),
                "ChArUco: ArUco marker side (mm), required with --board charuco")
          .Choice("--dictionary", &O::dictionary,
                  {ArucoDictionary::k4x4_50, ArucoDictionary::k5x5_100, ArucoDictionary::k6x6_250,
                   ArucoDictionary::kOriginal},
                  ArucoDictionaryName, "ChArUco: ArUco dictionary of the markers")
          .Real("--pixel-size-mm", &O::pixel_size_mm, "mm", B::Positive().Finite(),
                "Sensor pixel pitch in x (mm): focal_length_mm = fx * this; fx != fy goes into pixel_size_mm[1]")
          .Flag("--fix-k3", &O::fix_k3, "Keep k3 = 0 (narrow and moderate lenses)")
          .Flag("--fix-aspect", &O::fix_aspect, "Keep fx = fy (square pixels)")
          .Flag("--fix-principal-point", &O::fix_principal_point,
                "Keep the principal point at the image centre ((w-1)/2, (h-1)/2)")
          .Flag("--zero-tangent", &O::zero_tangent, "Keep p1 = p2 = 0 (no tangential distortion)")
          .Flag("--subpix", &O::subpix,
                "Chessboard: refine the corners with cornerSubPix (sharp images; window 0.3 x the corner spacing)")
          .Integer("--detect-max-px", &O::detect_max_px, "px", B::Closed(0, 100000),
                   "Chessboard: search larger images on a copy this size (longer side), then find the corners at "
                   "full size in the board's box only (0 = search the whole image at full size)")
          .Real("--reject-ratio", &O::reject_ratio, "", B::AtLeast(1).Finite(),
                "Reject a view whose RMS exceeds this times the median view RMS (and 0.1 px), then solve again")
          .Integer("--min-views", &O::min_views, "", B::Closed(1, 100000),
                   "Fewest usable views for a calibration (fewer: exit 1)")
          .Integer("--threads", &O::threads, "", B::Closed(0, 256), "Board detection threads (0 = one per core)");
  return table;
}

bool LensOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (board == BoardKind::kCharuco) {
    if (marker_mm <= 0) {
      if (why) *why = "--board charuco needs --marker-mm (the ArUco marker side)";
      return false;
    }
    if (marker_mm >= square_mm) {
      if (why) *why = "--marker-mm must be smaller than --square-mm";
      return false;
    }
  }
  return true;
}

int LensOptions::OpenCvFlags() const {
  int flags = 0;
  if (fix_k3) flags |= cv::CALIB_FIX_K3;
  if (fix_aspect) flags |= cv::CALIB_FIX_ASPECT_RATIO;
  if (fix_principal_point) flags |= cv::CALIB_FIX_PRINCIPAL_POINT;
  if (zero_tangent) flags |= cv::CALIB_ZERO_TANGENT_DIST;
  return flags;
}

}  // namespace rk::calibrate

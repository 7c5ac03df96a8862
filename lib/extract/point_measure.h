// The measurement of one user-seeded point in a frame (rk-extract points), one method per point
// (SPEC.md §2.1 seeds file). Each method looks only at a window around the point (a float copy of it is
// made per call), so its cost does not depend on the frame size.
//
//   correlation      Least-squares matching of the seed's own image patch (the anchor, taken on the seed
//                    frame's pixel grid around the seed) under an affine warp and a gain and offset
//                    (Gruen 1985): min Σ_q (I(c + A (q − seed)) − g T0(q) − o)², I interpolated by cubic
//                    convolution (Keys 1981, a = −0.5) with its analytic gradient. The coarse position is
//                    the NCC peak (ncc_search.h) of the anchor warped by the last A, so the template follows
//                    rotation and scale; the fit is always against the anchor itself, so it does not drift
//                    (the "template update problem", Matthews, Ishikawa & Baker 2004): the tracked point is
//                    exactly the seed's image point.
//   centroid-bright  Intensity-weighted centroid of the blob nearest the prediction. The window's threshold
//   centroid-dark    by Otsu (1979) on its own 256-bin histogram (any bit depth: OpenCV's is 8-bit only),
//                    the blob the connected component nearest the prediction, dilated by 2 px so that its
//                    wings are kept; background b the median of the window's other pixels; weights
//                    w = max(±(I − b), 0).
//   quadrant         The saddle point of a black-and-white quadrant (checkerboard) marker, fitted by
//                    Levenberg–Marquardt to the blurred two-edge model
//                      I(p) = b + a · erf(d1 / (√2 s)) · erf(d2 / (√2 s)),  d_i = n(θ_i) · (p − c)
//                    (two edge lines through c at angles θ1, θ2, not necessarily orthogonal; a Gaussian PSF
//                    of std s makes each edge an erf) over a window of ±h px; the model is even about c, so
//                    any symmetric blur leaves c unbiased. Start: the NCC peak of the model at the last
//                    angles (at a seed, the best of 8 angles).
//   circle           The blurred-disc model (disk_model.h, shared with rk-extract features) fitted only on
//                    the annulus ρ ± (3s + 2) px around the disc's edge: the rim decides the centre, and a
//                    highlight or a reflection inside the disc has no weight.
// σ: the fit's covariance σ_res² (JᵀJ)⁻¹ (σ_res² from the residuals, which includes what the model does not
// describe), for the centroid the propagated pixel noise (the background's scatter about its plane, plus the
// recording's shot noise for each blob pixel's difference from the background (ShotNoiseSlope), plus the
// background's error); each plus `sigma_floor_px` in quadrature (interpolation and pixel-locking biases).
// Pixel convention SPEC.md §3: (0, 0) is the centre of the top-left pixel.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "formats/seeds.h"

namespace rk::extract {

struct PointMeasureOptions {
  double ncc_min = 0.6;            // correlation (template, model) needed to accept a measurement
  double min_contrast_sigmas = 5;  // a fitted contrast below this many noise σ is refused
  int max_iterations = 30;         // least-squares fits
  double sigma_floor_px = 0.005;   // added in quadrature to every row's σ
};

struct PointMeasurement {
  bool ok = false;
  Eigen::Vector2d px{0, 0};
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();  // 2×2 covariance of px (px²)
  double score = 0.0;                             // the method's match quality in [0, 1] (SPEC `score`)
  double size_px = 0.0;                           // what the method measured of the marker's size
  const char* why = "";                           // when not ok
};

// A coarse position of a candidate (a correlation peak, a blob), strongest first.
struct PointCandidate {
  Eigen::Vector2d px{0, 0};
  double score = 0.0;
};

class PointMeasurer {
 public:
  virtual ~PointMeasurer() = default;
  // At a seed (the first frame of the point, or a re-seed): learns the point's appearance (template,
  // polarity, angles, radius, size) from `frame` near px (within ±search_px) and measures it.
  virtual PointMeasurement Seed(const cv::Mat& frame, const Eigen::Vector2d& px, double search_px) = 0;
  // Measures the point near `predicted`, searching ±search_px (the nearest good match to the prediction).
  virtual PointMeasurement Measure(const cv::Mat& frame, const Eigen::Vector2d& predicted, double search_px) = 0;
  // Up to max_n coarse candidates within ±search_px of `center`, strongest first (re-acquisition).
  virtual std::vector<PointCandidate> Candidates(const cv::Mat& frame, const Eigen::Vector2d& center,
                                                 double search_px, int max_n) = 0;
  // The tracker accepted m: follow the marker's slow changes (radius, angles, warp).
  virtual void Accept(const PointMeasurement& m) = 0;
  // While the point is hidden, the other points say the target's image has changed by the linear map L
  // (rotation and scale) since the measurement last accepted: the next search starts from that appearance.
  virtual void PredictChange(const Eigen::Matrix2d& /*L*/) {}
  // Half size of the image support the method looks at around the point (px).
  virtual int SupportHalfPx() const = 0;
  // The recording's shot noise (ShotNoiseSlope): a method whose σ propagates pixel noise (the centroid) adds
  // it for pixels brighter or darker than their background; the fitted methods' σ comes from their residuals.
  virtual void SetShotNoise(double /*dn2_per_dn*/) {}
};

// The measurer of a seeded point; size_px is the seeds file's (marker diameter or side, template side).
std::unique_ptr<PointMeasurer> MakePointMeasurer(formats::PointMethod method, std::optional<double> size_px,
                                                 const PointMeasureOptions& options);

// Helpers shared by the measurers and the tracker.
// Copies frame(rect) as CV_32FC1 into *roi; false (nothing copied) when rect is not inside the frame.
bool CopyFloatRoi(const cv::Mat& frame, const cv::Rect& rect, cv::Mat* roi);
// Noise σ of a float window: MAD of horizontal neighbour differences / √2 (robust to edges), ≥ 0.3 DN.
double WindowNoise(const cv::Mat& roi);
// The photon-transfer slope of a frame (DN² of pixel variance per DN of level, 1/gain for a shot-noise
// limited sensor): the variance of horizontal neighbour differences (within 4 robust σ), halved, in 32 bins of level,
// every 4th row (fewer in a large frame: about 300 000 pairs), fitted by a line over the bins with enough
// pairs (levels within 2 % of the frame's extremes, where it clips, left out); at least 0. −1 when the frame
// has too few levels to tell.
double ShotNoiseSlope(const cv::Mat& frame);
// Otsu's threshold of a float window (256 bins over its range) and its separability η ∈ [0, 1].
double OtsuThreshold(const cv::Mat& roi, double* separability);
// Cubic-convolution (Keys, a = −0.5) value and gradient of a float image at (x, y); false when the 4×4
// neighbourhood is not inside the image.
bool CubicSample(const cv::Mat& img, double x, double y, double* v, double* gx, double* gy);

}  // namespace rk::extract

// Target feature markers in attitude-camera frames (rk-extract features; seed 001 §2.3: "≥ 4
// target feature points found by correlation"): full-frame candidate detection, and the
// correlation measurement of one marker near a predicted position.
//
// Marker model: a round blob (a lamp, a retro-reflective or painted disc or sphere) brighter
// than its surroundings (or darker, polarity dark), of radius ρ (≥ 0) with a blurred edge of
// scale s, on a locally planar background:
//   I(x) = b0 + bx (x − x0) + by (y − y0) + a · Φ((ρ − ‖x − c‖) / s),  Φ = normal CDF.
// For ρ ≫ s this is a disc convolved with a Gaussian PSF of std s; for ρ → 0 a smooth spot.
// Measurement of one marker:
//   1. correlation search: normalised cross-correlation (cv::matchTemplate, TM_CCOEFF_NORMED)
//      of a synthetic template of the current (ρ, s) over a search window around the predicted
//      position; the best peak (the nearest to the prediction among peaks within 0.05 of the
//      best, so that a neighbour cannot steal the track) gives the integer position and the
//      correlation score;
//   2. least-squares correlation (adaptive least-squares matching, Gruen 1985): Levenberg–
//      Marquardt fit of the 8 parameters (c, ρ, s, a, b0, bx, by) over a window of half size
//      ⌈ρ + 3s + 3⌉ around it. For any centrally symmetric marker image (disc, sphere, spot,
//      obliquely seen disc = ellipse) the fitted centre is unbiased, whatever the exact profile;
//      its 1σ is from the fit (σ_res² (JᵀJ)⁻¹).
// Full-frame detection: the frame is averaged down by `downsample`, a morphological top-hat
// (opening with a square larger than the largest marker) removes the background and the
// target body, pixels above k_detect · noise form blobs (connected components) whose size and
// shape must fit a marker; each blob is then measured as above.
// Pixel convention: SPEC.md §3 ((0, 0) = centre of the top-left pixel).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/options.h"

namespace rk::extract {

struct MarkerDetectOptions {
  bool dark = false;               // markers darker than their surroundings
  double min_radius_px = 1.0;      // expected marker image radius range (px)
  double max_radius_px = 60.0;
  int downsample = 4;              // full-frame detection works on frames averaged down by this, [1, 8]
  double k_detect = 6.0;           // blob threshold in noise sigmas of the top-hat image
  double min_contrast_dn = 0.0;    // smallest fitted amplitude |a| accepted (DN); 0: 5 noise sigmas
  double ncc_min = 0.6;            // correlation score needed to accept a measurement
  int max_candidates = 40;         // full-frame: strongest blobs kept
  int max_iterations = 20;         // least-squares fit
  double sigma_floor_px = 0.005;   // added in quadrature to the fit's centre σ (unmodelled effects)

  // The command-line options of rk-extract features' detector (io/options.h).
  static const io::OptionTable<MarkerDetectOptions>& Table();
  bool Check(std::string* why) const;
};

struct MarkerMeasurement {
  bool ok = false;
  Eigen::Vector2d px{0, 0};       // fitted centre
  double sigma_px = 0.0;          // 1σ of each coordinate (mean of x and y)
  double radius_px = 0.0;         // ρ
  double edge_px = 0.0;           // s
  double amplitude_dn = 0.0;      // a (positive for the chosen polarity)
  double ncc = 0.0;               // correlation score of the search
  double rms_dn = 0.0;            // fit residual RMS
  int iterations = 0;
  std::string why;                // when not ok
};

class MarkerDetector {
 public:
  explicit MarkerDetector(const MarkerDetectOptions& opt = {});
  const MarkerDetectOptions& options() const { return opt_; }

  // Prepares a frame (8- or 16-bit mono): float copy in the chosen polarity and the noise
  // level (median / MAD of a sparse grid). Call once per frame before the other methods.
  void SetFrame(const cv::Mat& frame);
  double noise_dn() const { return noise_dn_; }
  double level_dn() const { return level_dn_; }

  // Candidates anywhere in the frame, measured; strongest first.
  std::vector<MarkerMeasurement> DetectAll();

  // Measures the marker nearest `predicted` within ±search_px, assuming radius ≈ radius_px and
  // edge ≈ edge_px (from earlier frames).
  MarkerMeasurement Measure(const Eigen::Vector2d& predicted, double search_px, double radius_px, double edge_px);

 private:
  MarkerMeasurement Fit(const Eigen::Vector2d& start, double radius_px, double edge_px, double ncc);
  void MakeTemplate(double radius_px, double edge_px, int half);

  MarkerDetectOptions opt_;
  cv::Mat image_;       // CV_32FC1, polarity applied (markers bright)
  double level_dn_ = 0.0, noise_dn_ = 1.0;
  cv::Mat templ_;
  cv::Mat ncc_map_;
};

}  // namespace rk::extract

// Beacon (IR lamp cluster) detection and sub-pixel location in one frame,
// seed 001 §2.1 (Guan et al. 2014): grey projection → region growing →
// grey-weighted centroid, with template matching (NCC) for identity.
//
// 1. Grey projection (eqs. 1–4): row sums G_hor(i) = Σ_j G(i, j) and column sums
//    G_ver(j) = Σ_i G(i, j) in one pass. The paper takes the argmax of each; with
//    distractors (glints) in the scene one argmax pair may mix two objects, so we
//    take the top-K peaks of each projection (after removing the background
//    baseline by a morphological top-hat) and test every row/column
//    intersection as a rough position.
// 2. Region growing from each seed (a local maximum ≥ b + k_det σ) over pixels
//    ≥ b + k_grow σ with a gap tolerance of g pixels (neighbours within Chebyshev
//    distance g + 1), so the separate lamps of a cluster merge into one region.
//    b, σ: local background level and noise (median and 1.4826·MAD), so the
//    thresholds scale with 8- and 16-bit data alike.
// 3. Grey-weighted centroid over a fixed window around the region, after
//    subtracting the local background (clipped mean, or optionally a least-squares
//    plane) of a ring of pixels around the window; no threshold inside the
//    window. A first centroid over the region box + margin fixes the centre of
//    the final window: a disk centred on the rounded first centroid whose radius
//    reaches the farthest region-box edge + margin, with an annulus as ring. Its expectation is
//    the flux-weighted mean of the lamp positions (the truth definition of
//    rk::sim::FluxWeightedCentre) up to the PSF mass outside the window (< 1e-3
//    px for margin ≥ 2.5 PSF σ). A single-Gaussian fit would lock onto one lamp.
// 4. Template matching: normalised cross-correlation (NCC) of the
//    background-subtracted patch with the template saved at acquisition / the
//    last good frame, best of the 3×3 integer shifts. Used to validate identity
//    and to re-acquire after occlusion. (A sub-pixel NCC peak refinement was not
//    kept: the windowed centroid is the unbiased estimator of the truth above.)
// Pixel convention: SPEC.md §3 (pixel (i, j) centre at x = j, y = i).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/options.h"

namespace rk::extract {

struct DetectOptions {
  double k_detect = 8.0;        // seed threshold: b + k_detect σ (σ = pixel noise)
  double k_grow = 4.0;          // region-growing threshold: b + k_grow σ
  int gap_px = 1;               // gap tolerance of region growing (pixels), [0, 4]
  int cluster_gap_px = 12;      // regions whose boxes are this close merge into one cluster (lamps
                                // far apart at short range), [0, 64]
  int max_extent_px = 48;       // region may extend this far from its seed (pixels)
  int max_area_px = 6000;       // larger regions are rejected (sun glint, saturated blob)
  int margin_px = 2;            // centroid window = region box + margin (pixels)
  int ring_px = 3;              // width of the background ring around the window (pixels)
  bool background_plane = false;  // fit a plane (level + gradient) to the ring instead of a level:
                                  // removes gradient bias, but adds ~0.02 px noise
  int projection_peaks = 6;     // K: peaks taken from each grey projection
  double min_noise_dn = 0.5;    // floor of σ (quantisation)
  int max_candidates = 24;      // per search area
  // The command-line options (rk-extract beacon): flag, member, unit, valid range, help; Check() and
  // the report's "options" block come from it (io/options.h).
  static const io::OptionTable<DetectOptions>& Table();
  bool Check(std::string* why) const;
};

// Value of pixel (x, y) of a CV_8UC1 or CV_16UC1 frame (no bounds check).
inline double PixelValue(const cv::Mat& f, int x, int y) {
  return f.depth() == CV_8U ? static_cast<double>(f.ptr<std::uint8_t>(y)[x])
                            : static_cast<double>(f.ptr<std::uint16_t>(y)[x]);
}

// Background level and noise of a set of samples: median and 1.4826·MAD.
struct NoiseStats {
  double level_dn = 0.0;
  double sigma_dn = 1.0;
};

// A rectangle of pixels, inclusive bounds.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x1 < x0 || y1 < y0; }
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
  bool Contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

struct SpotMeasurement {
  double x_px = 0.0, y_px = 0.0;       // grey-weighted centroid
  double sigma_x_px = 0.0, sigma_y_px = 0.0;  // its standard deviation from background noise
  double flux_dn = 0.0;                // Σ (I − b) over the window (DN·pixel)
  double background_dn = 0.0;          // background plane at the centroid
  double bg_dx = 0.0, bg_dy = 0.0;     // background plane gradient (DN/pixel)
  double size_px = 0.0;                // sqrt of the trace of the signal-weighted second moment
  double peak_dn = 0.0;                // highest pixel of the region (raw DN)
  int area_px = 0;                     // pixels of the grown region
  PixelBox region;                     // bounding box of the grown region
  double noise_dn = 0.0;               // pixel noise σ used for the thresholds and sigma_x/y (DN)
  bool clipped = false;                // window or ring cut by the image border
};

// Template for NCC: background-subtracted, zero-mean, unit-norm patch of
// (2h+1)² pixels centred on the rounded centroid.
struct SpotTemplate {
  int half = 0;
  std::vector<float> values;
  double size_px = 0.0;
  double flux_dn = 0.0;
  bool valid() const { return half > 0 && !values.empty(); }
};

// Reusable workspace: no heap allocation once warmed up.
class SpotDetector {
 public:
  explicit SpotDetector(const DetectOptions& opt = {});
  const DetectOptions& options() const { return opt_; }

  // Median / MAD of the pixels on the border of `box` (clipped to the frame).
  NoiseStats BorderStats(const cv::Mat& frame, PixelBox box);
  // Median / MAD of a sparse grid of the whole frame (stride pixels).
  NoiseStats FrameStats(const cv::Mat& frame, int stride);

  // Finds regions whose seed lies in `search` (clipped to the frame), grows and
  // measures them. Appends to `out` (not cleared), at most max_candidates.
  void FindInBox(const cv::Mat& frame, PixelBox search, const NoiseStats& noise,
                 std::vector<SpotMeasurement>* out);

  // Grey projection of the whole frame and candidate positions at the
  // intersections of the top-K row and column peaks; then FindInBox around
  // each. `out` is cleared first; duplicates removed.
  void FindInFrame(const cv::Mat& frame, std::vector<SpotMeasurement>* out);
  const NoiseStats& last_frame_stats() const { return frame_stats_; }

  // Centroid over region box + margin (see header comment). False if the
  // window has no positive flux.
  bool MeasureCentroid(const cv::Mat& frame, const PixelBox& region, double noise_sigma, SpotMeasurement* m);

  // Template around a measured spot; half size from the region (clamped).
  void MakeTemplate(const cv::Mat& frame, const SpotMeasurement& m, SpotTemplate* tpl);
  // Best NCC over ±1 pixel shifts of the patch at the spot, in [-1, 1].
  double Ncc(const cv::Mat& frame, const SpotMeasurement& m, const SpotTemplate& tpl);

  // Row and column projections of the last FindInFrame (for tests).
  const std::vector<std::uint32_t>& row_projection() const { return row_sum_; }
  const std::vector<std::uint32_t>& col_projection() const { return col_sum_; }

 private:
  void FindSeeds(const cv::Mat& frame, const PixelBox& search, const NoiseStats& noise, double thr_det,
                 double thr_grow, std::vector<SpotMeasurement>* out);
  void MergeClusters(const cv::Mat& frame, const NoiseStats& noise, std::size_t first, std::vector<SpotMeasurement>* v);
  bool Grow(const cv::Mat& frame, int sx, int sy, double thr_grow, SpotMeasurement* m);
  bool FitSamples(double noise_sigma, double* b0, double* bx, double* by);
  void PatchValues(const cv::Mat& frame, int cx, int cy, int half, const SpotMeasurement& m, std::vector<float>* v);

  DetectOptions opt_;
  NoiseStats frame_stats_;
  std::vector<double> samples_;
  std::vector<std::uint8_t> visited_;
  std::vector<int> stack_;
  std::vector<std::uint32_t> row_sum_, col_sum_;
  std::vector<double> prof_, work_, work2_;
  std::vector<float> patch_;
  std::vector<float> tmp_;
  std::vector<SpotMeasurement> found_;
};

}  // namespace rk::extract

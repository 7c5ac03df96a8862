// Per-lamp centroid estimator for a lamp cluster whose lamps resolve (sparse
// cluster, e.g. 0.1 m span at 80 m: five separate spots 18 px across).
//
// Why. The cluster centroid (beacon_detect.h) sums one window around the whole
// cluster: most of its pixels are background, whose noise enters with lever
// arms up to the cluster radius, and the per-lamp photon noise moves the flux
// weights of lamps that are several pixels from the centre. Both vanish when
//   x̂ = Σ_i s̄_i x_i,   s̄_i = F̄_i / Σ_j F̄_j
// with x_i the grey-weighted centroid of lamp i over its own small disk and F̄_i
// the time average of the lamp's flux F_i (its flux share is a property of the
// beacon, constant over seconds). The expectation is that of the cluster
// centroid: with E[x_i] = E[M_i]/E[F_i] (M = first moment) and s̄_i → E[F_i]/ΣE[F],
// E[x̂] = Σ E[M_i] / Σ E[F_i], the flux-weighted lamp centre (the truth of
// rk::sim::FluxWeightedCentre), up to PSF mass outside the lamp disks.
//
// Resolving (Measure). Inside the cluster window (region box + margin), pixels
// ≥ b + k_grow σ are labelled into 8-connected components (not with the
// region-growing gap tolerance, which lets one noise pixel bridge two lamps a
// few pixels apart at the edge of resolving); a component whose peak reaches
// b + k_detect σ is a lamp (b: the cluster's background plane, σ: pixel noise).
// The lamps resolve when there are at least two, at most kMaxLamps, and no lamp
// centre lies inside another lamp's disk. Lamp i's disk: centre at its rounded
// component centroid, radius = farthest component-box edge + margin; a pixel
// in two disks belongs to the nearer centre (the partition keeps Σ M_i and
// Σ F_i those of the union, so the shares stay consistent).
// Noise per lamp (background/read noise σ only; photon noise of the lamps is
// not modelled, ≈ 1 % of σ at the rk-sim default sensor):
//   var(x_i) = σ² Σ_{p∈i} (x_p − x_i)² / F_i²,  var(F_i) = σ² n_i.
//
// Combining (Combine, stateful). Lamps are matched to the previous frame's by
// their offsets from the cluster centroid (within a third of the smallest lamp
// spacing); a frame whose lamps do not all match restarts the averages. F̄_i is
// the running mean over the last ≤ kShareFrames frames (exponential weights
// once more frames have been seen).
//   var(x̂) = Σ s̄_i² var(x_i) + Σ var(s̄_i) (x_i − x̂)²,
//   var(s̄_i) ≈ var(F_i) / (Σ F̄)² / n_eff  (n_eff frames in the average).
// Pixel convention: SPEC.md §3 (pixel (i, j) centre at x = j, y = i).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "extract/beacon_detect.h"

namespace rk::extract {

// At most this many lamps are resolved (rk-sim beacon allows 64).
inline constexpr int kMaxLamps = 64;
// Flux shares are averaged over about this many frames.
inline constexpr int kShareFrames = 100;

struct LampMeasurement {
  double x_px = 0.0, y_px = 0.0;          // grey-weighted centroid over the lamp's disk (px)
  double flux_dn = 0.0;                   // F_i = Σ (I − b) over the disk (DN·px)
  double var_x_px2 = 0.0, var_y_px2 = 0.0;  // centroid variance from pixel noise (px²)
  double var_flux_dn2 = 0.0;              // variance of F_i (DN²·px²)
};

struct LampEstimate {
  double x_px = 0.0, y_px = 0.0;
  double sigma_x_px = 0.0, sigma_y_px = 0.0;
  int lamps = 0;
};

class LampEstimator {
 public:
  explicit LampEstimator(const DetectOptions& opt = {});

  // Measures the lamps of `cluster` (a SpotDetector measurement of `frame`).
  // False when the lamps do not resolve (or a lamp disk leaves the frame).
  bool Measure(const cv::Mat& frame, const SpotMeasurement& cluster, std::vector<LampMeasurement>* lamps);

  // Combines `lamps` (measured around cluster centroid (cx, cy)) with the
  // time-averaged flux shares, updating the averages.
  LampEstimate Combine(const std::vector<LampMeasurement>& lamps, double cx_px, double cy_px);

  // Measure + Combine; false (and the averages reset) when the lamps do not resolve.
  bool Estimate(const cv::Mat& frame, const SpotMeasurement& cluster, LampEstimate* out);

  // Forgets the averaged shares (a new track).
  void Reset() { shares_.clear(); }

 private:
  // Measure's stages: the window's components above k_grow σ (comp_), then the lamp disks' pixel sums.
  bool LabelComponents(const cv::Mat& frame, const SpotMeasurement& cl, int x0, int y0, int x1, int y1,
                       double thr_grow);
  bool PartitionDisks(const cv::Mat& frame, const SpotMeasurement& cl);

  struct Share {
    double dx_px = 0.0, dy_px = 0.0;  // offset of the lamp from the cluster centroid, last frame
    double flux_mean_dn = 0.0;        // F̄_i
  };
  DetectOptions opt_;
  std::vector<int> label_;            // component label per window pixel (−1: none)
  std::vector<int> stack_;
  struct Component {
    double sw = 0, swx = 0, swy = 0, peak = 0;
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  };
  std::vector<Component> comp_;
  std::vector<LampMeasurement> lamps_;
  struct Disk {
    int cx = 0, cy = 0, r2 = 0;
    double s = 0, sx = 0, sy = 0, gx = 0, gy = 0, gxx = 0, gyy = 0;  // signal moments, pixel geometry
    int n = 0;
  };
  std::vector<Disk> disk_;
  std::vector<Share> shares_, reordered_;
  std::vector<int> match_;
  double frames_ = 0.0;               // n_eff of the share averages
};

}  // namespace rk::extract

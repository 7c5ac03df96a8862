// Silhouette points of a cylindrical target (rocket) against the sky, seed 004 §3.1 (Tang et al. 2004):
// the nose tip and the two ends of the tail-rim diameter seen edge-on (ids nose, tail1, tail2; SPEC.md §3),
// sub-pixel, from one frame.
//
// The paper reads three points off the outline to the nearest pixel. Here each point comes from fits over
// the whole outline, in the image frame (u along the target's image axis, tail → nose; v across, positive to
// the LEFT of the tail → nose direction as seen on the screen):
//   1. Sky: a plane a + b x + c y fitted to a border band of the frame (3σ-clipped least squares), noise σ
//      from the MAD of its residuals; target = the largest 8-connected region with |I − sky| > k_detect σ.
//      A region touching the frame border is refused (a cut outline has no tip or tail).
//   2. Coverage: a second sky plane fitted to a ring around the region; contrast c = median of (I − sky) over
//      the region's stronger half; α = (I − sky)/c, the fraction of each pixel covered by the target
//      (exact for area-sampled images, and any symmetric PSF only redistributes it).
//   3. Profiles across the axis (bilinear samples of α every 0.5 px in u and v): width S(u) = ∫ α dv and
//      centre C(u) = ∫ v α dv / S. For a straight outline these integrals are unbiased at any sub-pixel
//      phase and any symmetric blur (blur moves coverage, it does not create or destroy it).
//   4. The nose end is the narrower one. Side lines v = C ± S/2 over the cylindrical body (S ≥ 0.97 of the
//      body width, away from the tail and the nose by 3 PSF σ + 2 px) are fitted by clipped least squares;
//      their mid-line re-defines the axis and the profiles are sampled again (twice).
//   5. Tail: along lines of constant v (|v| ≤ min(0.8 w, w − 3 s)), the edge position e(v) = u_in − ∫ α du (same
//      unbiased integral). The tail outline is the outer half of the rim ellipse, whose major axis is the
//      diameter seen edge-on, perpendicular to the image axis: e(v) = u0 − b sqrt(1 − (v/w)²), linear in
//      (u0, b) (b ≥ 0 enforced), with the blur's curvature bias e += (s²/2) e'' modelled (s = the effective
//      blur σ, measured on the side edges). tail1 / tail2 = the left / right side line at u0: the tangent points of the
//      rim ellipse, i.e. the ends of the edge-on diameter. (Orthographic within the target's own depth: the
//      error is ~ w·r/range, < 0.002 px at seed 004 scales.)
//   6. Nose: over the cone, S(u) and C(u) are straight lines; fitted where 0.15 W ≤ S ≤ 0.7 W (clear of
//      the blurred tip and cone base), the tip is where S reaches 0 and C there. A conical nose is assumed;
//      an ogive gives the tip of the tangent cone at mid-nose (bias towards the outside).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "io/options.h"

namespace rk::extract {

struct SilhouetteOptions {
  double k_detect = 6.0;         // detection threshold in sky-noise σ, [2, 100]
  int min_area_px = 30;          // smallest target region (px), [4, 1e7]
  int border_px = 8;             // width of the frame border band used for the sky plane, [2, 200]
  double psf_sigma_px = 1.0;     // assumed optics blur σ (px): sets the margins kept from kinks, [0, 10]
  double min_width_px = 3.0;     // a body narrower than this (px) is not measured, [1, 1e4]
  double min_length_ratio = 3.0; // image length / width below this (near tail chase) is not measured, >= 1
  // The command-line options of rk-extract silhouette (io/options.h).
  static const io::OptionTable<SilhouetteOptions>& Table();
  bool Check(std::string* why) const { return Table().Check(*this, why); }
  io::Json ToJson() const { return Table().ToJson(*this); }
};

enum class SilhouetteStatus {
  kOk,
  kNotFound,       // no region above threshold
  kTouchesBorder,  // the region reaches the frame border
  kTooSmall,       // too narrow or too short to measure (or too foreshortened)
  kBadFit,         // the outline does not fit the cylinder + cone model
};
const char* SilhouetteStatusName(SilhouetteStatus s);

struct SilhouetteResult {
  SilhouetteStatus status = SilhouetteStatus::kNotFound;
  std::array<Eigen::Vector2d, 3> px{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  // Diagnostics.
  double sky_sigma_dn = 0.0;     // sky noise
  double contrast_dn = 0.0;      // target − sky (signed)
  double width_px = 0.0;         // body width at the tail
  double length_px = 0.0;        // nose tip to tail centre
  double side_rms_px = 0.0;      // RMS residual of the side-line fits
  double tail_b_px = 0.0;        // semi-minor axis of the tail-rim ellipse
  double edge_blur_px = 0.0;     // effective blur σ of the side edges (PSF, pixel, resampling)
  int region_area_px = 0;
};

// Frame: CV_8UC1 or CV_16UC1.
SilhouetteResult ExtractSilhouette(const cv::Mat& frame, const SilhouetteOptions& options);

}  // namespace rk::extract

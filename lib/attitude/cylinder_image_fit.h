// Image-based refinement of a cylinder's pose (seed 004 set-up): the projected 3-D target is fitted to the
// frame itself by least squares, starting from the three-point solution (cylinder_solve.h).
//
// Why. Three points carry only part of what the outline says about the pose: the tail-rim ellipse's minor
// axis (fixed by the view angle), the perspective convergence of the side lines and the whole nose cone are
// lost, and each point inherits the error of an extrapolation (the tail rim sits where two side lines meet a
// blurred ellipse). The Cramér–Rao bound of yaw and pitch from the image (bench/cylinder_crlb) is 4–20× below
// what the three-point route achieves on rendered frames; this fit uses every pixel near the outline.
//
// Model of the frame at the pixels within a margin of the initial outline (inside the outline's bounding box
// + the margin; the box's far corners carry nothing about the pose and are left out):
//   I(x, y) = sky(x, y) · (1 − α(x, y)) + body(x, y) · α(x, y) + noise
//   sky = s0 + s1 x̃ + s2 ỹ (a plane; x̃, ỹ window coordinates scaled to [−1, 1]),
//   body = b0 + b1 v (v: signed distance from the image axis over the tail half-width, clamped to [−1, 1]: a
//   target lit from one side),
//   α = G_σ ∗ coverage: the exact area of each pixel covered by the projected solid (the convex hull of the
//   tail rim, the nose-cone base rim and the tip; target::SilhouettePolygon / target::RasterizeConvexPolygon, the
//   same geometry as rk-sim theodolite's renderer) blurred by a Gaussian PSF of σ px.
// Unknowns: the tail-rim centre (3: two offsets across the line of sight and one along it, which the image
// sees only through its scale), yaw, pitch, the nose-cone length (the target file gives only length and
// diameter: the cone length is a nuisance, started from the best of a coarse scan) and σ (7 nonlinear);
// s0..s2, b0, b1 (5 linear, eliminated in closed form at every evaluation: variable projection).
// Levenberg–Marquardt with Marquardt's diagonal scaling, Jacobian by forward differences of the reduced
// residual, no step turning the axis by more than 1° (near side-on a mirror minimum of equal cost lies a few
// degrees away: the fit stays in the basin of the solution it starts from). The lines of sight come from
// camera::CameraModel::ProjectEnu (SPEC.md §3 exactly: distortion, mount, boresight).
//
// Noise: a first pass is unweighted; the per-pixel noise variance is then modelled as c0 + c1 · signal (read
// + shot noise, so sky and body pixels differ) by regressing the squared residuals on the model, and a second
// pass is weighted by it — maximum likelihood for Gaussian noise of that variance. Covariance: σ̂² (JᵀJ)⁻¹ of
// the weighted problem (σ̂² ≈ 1 when the noise model holds) — the yaw/pitch σ columns of the fit. Limits: a
// conical nose is assumed (an ogive biases the tip); the target must be wholly in the frame.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>

#include "attitude/cylinder_geometry.h"
#include "camera/camera_model.h"
#include "io/options.h"

namespace rk::attitude {

struct CylinderImageFitOptions {
  double initial_psf_sigma_px = 0.8;  // start of the PSF σ (px), (0, 5]
  int max_iterations = 30;            // Levenberg–Marquardt iterations, >= 1
  int rim_samples = 512;              // points per rim in the projected outline, >= 16
  double margin_px = 6.0;             // window margin around the outline beyond 4σ (px), >= 1
  // The command-line options of the image fit (rk-attitude cylinder --fit-*; io/options.h).
  static const io::OptionTable<CylinderImageFitOptions>& Table();
  bool Check(std::string* why) const;
};

// A start carried over from the previous frame's fit: the nuisance parameters (nose-cone length, blur, the
// noise model) change little from frame to frame. With it the fit leaves out the nose-cone scan and the
// unweighted first pass: one weighted pass, weighted by the previous frame's noise model at the start's model
// values (65-90 % of a cold fit's model evaluations from a 0.2° start; most of the saving in rk-attitude
// cylinder comes from fitting one solution and starting from the predicted axis). rk-attitude cylinder uses it
// after the first converged frame.
struct CylinderImageFitStart {
  double nose_cone_length_m = 0.0;  // > 0
  double psf_sigma_px = 0.0;        // > 0
  double noise_c0 = 0.0;            // pixel noise variance c0 + c1 · signal (DN², DN), c0 > 0
  double noise_c1 = 0.0;
};

enum class CylinderImageFitStatus {
  kConverged,
  kNotConverged,  // iteration limit reached: the result is the last accepted iterate
  kFailed,        // outline outside the frame or behind the camera, or a singular system: no result
};
const char* CylinderImageFitStatusName(CylinderImageFitStatus s);

struct CylinderImageFitResult {
  CylinderImageFitStatus status = CylinderImageFitStatus::kFailed;
  Eigen::Vector3d tail_centre_enu{0, 0, 0};
  Eigen::Vector3d axis_enu{0, 1, 0};
  double yaw_rad = 0.0, pitch_rad = 0.0;
  double nose_cone_length_m = 0.0;
  double psf_sigma_px = 0.0;
  double sigma_yaw_rad = 0.0, sigma_pitch_rad = 0.0;  // from σ̂² (JᵀJ)⁻¹
  double rms_dn = 0.0;                                // residual RMS over the window
  double contrast_dn = 0.0;                           // body − sky at the window centre
  int iterations = 0;
  int evaluations = 0;  // model renderings
  int pixels = 0;       // pixels fitted
  double noise_c0 = 0.0, noise_c1 = 0.0;  // noise model fitted to the final residuals
  // The start this result gives the next frame's fit.
  CylinderImageFitStart NextStart() const { return {nose_cone_length_m, psf_sigma_px, noise_c0, noise_c1}; }
};

// Refines the pose (tail_centre_enu, yaw, pitch) of `target` seen in `frame` (CV_8UC1 or CV_16UC1; 16-bit
// values are fitted as they are) with the camera boresight at (az, el); `start` (may be null: a cold fit) is
// the previous frame's CylinderImageFitResult::NextStart().
CylinderImageFitResult FitCylinderImage(const cv::Mat& frame, const camera::CameraModel& camera,
                                        double az_rad, double el_rad, const target::CylinderShape& target,
                                        const Eigen::Vector3d& tail_centre_enu, double yaw_rad,
                                        double pitch_rad, const CylinderImageFitOptions& options,
                                        const CylinderImageFitStart* start = nullptr);

}  // namespace rk::attitude

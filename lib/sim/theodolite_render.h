// Images of the cylindrical target against the sky for rk-sim theodolite (silhouette extraction, seed 004).
//
// Geometry: the solid (cylinder from the tail plane to the nose-cone base, cone to the tip) is convex, so its
// image is the convex hull of the projections of the tail rim, the cone-base rim (2048 points each) and the
// tip, each projected exactly (camera::CameraModel::ProjectEnu with distortion and mount; the rim sampling
// puts the outline within 4e-5 px of the true one for a 30-px radius). Rendering is exact area sampling:
// each pixel's coverage α ∈ [0, 1] is the area of the hull inside the pixel square (Sutherland–Hodgman
// clipping of the convex polygon to the pixel), so the expected image is unbiased at any sub-pixel phase.
// Then optics and sensor: α is blurred by a Gaussian PSF (σ psf_sigma_px), the signal is
//   I = sky(x, y) + α · (body(x, y) − sky(x, y)),
//   sky(x, y) = sky_dn + sky_gradient_dn · (y/(H − 1) − 1/2)     (brighter towards the horizon, image bottom)
//   body(x, y) = body_dn + shading_dn · clamp(v / w, −1, 1)    (v: signed distance from the image axis,
//                                                                 w: half the tail width; sun from one side)
// and digitised by sim::Digitise (shot noise, read noise, rounding, clipping; 8 or 16 bit, DN values on the
// 8-bit scale are ×256 for 16 bit).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "camera/camera_model.h"
#include "sim/render.h"
#include "sim/theodolite_scene.h"

namespace rk::sim {

// Outline of the target in the image for boresight (az, el): convex polygon, counter-clockwise in pixel
// coordinates (x right, y down). Empty if a point is behind the camera.
std::vector<Eigen::Vector2d> SilhouettePolygon(const camera::CameraModel& camera, const CylinderPose& pose,
                                               const CylinderShape& shape, double az_rad, double el_rad,
                                               int rim_samples = 2048);

// Whole-pixel window holding the polygon's bounding box grown by `margin` px on each side (not clipped to any
// image); empty for an empty polygon.
cv::Rect PolygonWindow(const std::vector<Eigen::Vector2d>& poly, int margin);

// Area of a polygon (shoelace; positive for counter-clockwise in x-right/y-up, so negative for CCW
// in image coordinates: the absolute value is returned).
double PolygonArea(const std::vector<Eigen::Vector2d>& poly);

// Exact pixel coverage of a convex polygon over the rectangle `roi` of the image: CV_32FC1 of roi.size();
// element (i, j) is the area of the polygon inside the pixel (roi.x + j, roi.y + i) (square of side 1 centred
// on integer coordinates, SPEC.md §3).
cv::Mat RasterizeConvexPolygon(const std::vector<Eigen::Vector2d>& poly, const cv::Rect& roi);

struct SilhouetteRenderOptions {
  double sky_dn = 180.0;          // sky level at the image centre (8-bit DN)
  double sky_gradient_dn = 30.0;  // top-to-bottom increase of the sky level
  double body_dn = 60.0;          // target level; above sky_dn for a sunlit target
  double shading_dn = 0.0;        // ± change of the body level across its width
  double psf_sigma_px = 0.8;      // Gaussian PSF std (px), [0, 10]; 0 = none
  // Background (unused: the sky is the signal), read noise 1 DN, 100 e-/DN, 8 bit: seed 004's 11 µm pixels
  // hold ~25 000 e- over the 8-bit range, so the shot noise of a 180-DN sky is 1.3 DN (total 1.7 DN).
  SensorOptions sensor{0.0, 1.0, 100.0, 8};
  bool Check(std::string* why) const;
};

// Expected (noise-free) frame before the sensor: CV_32FC1 (depth CV_32F, what the renderer digitises) or
// CV_64FC1 (computed in double: for derivatives), DN on the 8-bit scale (×256 for bit_depth 16).
cv::Mat SilhouetteSignal(const camera::CameraModel& camera, const TheodoliteFrameTruth& frame,
                         const CylinderShape& shape, const SilhouetteRenderOptions& options, int depth = CV_32F);

// Frame of a TheodoliteSimulator at its true boresight, with noise from `rng`: SilhouetteSignal digitised by
// sim::Digitise.
cv::Mat RenderSilhouetteFrame(const camera::CameraModel& camera, const TheodoliteFrameTruth& frame,
                              const CylinderShape& shape, const SilhouetteRenderOptions& options,
                              std::mt19937_64& rng);

}  // namespace rk::sim

// Image of the cylindrical target (target/cylinder.h) against the sky: the forward model shared by rk-sim
// theodolite's renderer and rk-attitude cylinder's image fit (and the Cramér–Rao bound of
// bench/cylinder_crlb).
//
// Geometry: the solid (cylinder from the tail plane to the nose-cone base, cone to the tip) is convex, so its
// image is the convex hull of the projections of the tail rim, the cone-base rim (2048 points each) and the
// tip, each projected exactly (camera::CameraModel::ProjectEnu with distortion and mount; the rim sampling
// puts the outline within 4e-5 px of the true one for a 30-px radius). Rasterising is exact area sampling:
// each pixel's coverage α ∈ [0, 1] is the area of the hull inside the pixel square (Sutherland–Hodgman
// clipping of the convex polygon to the pixel), so the expected image is unbiased at any sub-pixel phase.
// Signal (before any sensor): α is blurred by a Gaussian PSF (σ psf_sigma_px), then
//   I = sky(x, y) + α · (body(x, y) − sky(x, y)),
//   sky(x, y) = sky_dn + sky_gradient_dn · (y/(H − 1) − 1/2)     (brighter towards the horizon, image bottom)
//   body(x, y) = body_dn + shading_dn · clamp(v / w, −1, 1)    (v: signed distance from the image axis,
//                                                                 w: half the tail width; sun from one side)
// The image axis runs from the mid-point of the projected tail1/tail2 to the projected nose (SPEC.md §3
// points).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "camera/camera_model.h"
#include "target/cylinder.h"

namespace rk::target {

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

// Radiometry of the scene (DN on the 8-bit scale; the defaults are rk-sim theodolite's).
struct SilhouetteScene {
  double sky_dn = 180.0;          // sky level at the image centre (8-bit DN)
  double sky_gradient_dn = 30.0;  // top-to-bottom increase of the sky level
  double body_dn = 60.0;          // target level; above sky_dn for a sunlit target
  double shading_dn = 0.0;        // ± change of the body level across its width
  double psf_sigma_px = 0.8;      // Gaussian PSF std (px), [0, 10]; 0 = none
};

// Expected (noise-free) frame of the whole image at boresight (az, el), before any sensor: CV_32FC1 (depth
// CV_32F, what rk-sim theodolite digitises) or CV_64FC1 (computed in double: for derivatives); the scene's DN
// values times dn_scale (1 for an 8-bit sensor, 256 for 16 bit).
cv::Mat SilhouetteSignal(const camera::CameraModel& camera, const CylinderPose& pose,
                         const CylinderShape& shape, double az_rad, double el_rad,
                         const SilhouetteScene& scene, double dn_scale, int depth = CV_32F);

}  // namespace rk::target

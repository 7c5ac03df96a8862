// Rendering of target markers for the attitude camera (rk-sim attitude): each marker is a
// bright sphere (an active lamp or retro-reflector ball) whose image is a uniform disc of
// radius ρ = f·r/d (r sphere radius, d distance), blurred by a Gaussian PSF of std σ and
// integrated over the pixel area (4×4 sub-samples per pixel of the blurred-edge profile
// Φ((ρ − |x − c|)/σ), Φ = standard normal CDF, which is the disc ⊗ PSF to O(σ²/ρ²)).
// The image is radially symmetric about c, so c (the projection of the sphere's centre) is the
// truth for any unbiased centre estimator; the perspective offset of a sphere's elliptical
// image from c is ρ²/f · tan(off-axis angle) < 0.001 px for the simulated geometry.
// The target body (optional) is a uniform polygon, drawn without anti-aliasing.
// Pixel convention (SPEC.md §3): pixel (i, j) covers x in [j − 0.5, j + 0.5), y likewise.
#pragma once

#include <opencv2/core.hpp>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace rk::sim {

struct Disc {
  double x_px = 0.0, y_px = 0.0;  // centre
  double radius_px = 10.0;        // ρ > 0
  double psf_sigma_px = 0.8;      // σ > 0
  double amplitude_dn = 150.0;    // level inside the disc above the background (DN)
};

// Adds the discs to a CV_32FC1 signal image (DN).
void AddDiscs(cv::Mat* signal_dn, std::span<const Disc> discs);

// Adds a filled convex polygon of level `dn` (vertices in pixels, any order: the convex hull is
// drawn) to a CV_32FC1 signal image.
void AddConvexHull(cv::Mat* signal_dn, std::span<const Eigen::Vector2d> points_px, double dn);

}  // namespace rk::sim

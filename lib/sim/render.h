// Rendering of point sources on a sensor: each lamp is a Gaussian point-spread
// function integrated over the pixel area (not point-sampled, so the expected
// grey-weighted centroid of an isolated spot equals its true position), then
// digitised with shot noise, read noise and quantisation.
//
// Pixel convention (SPEC.md §3): pixel (i, j) covers x in [j-0.5, j+0.5),
// y in [i-0.5, i+0.5).
#pragma once

#include <opencv2/core.hpp>
#include <random>
#include <span>
#include <string>

#include "io/options.h"

namespace rk::sim {

struct Spot {
  double x_px = 0.0;
  double y_px = 0.0;
  double sigma_px = 1.2;      // PSF standard deviation
  double amplitude_dn = 200;  // peak of the continuous Gaussian above background (DN)
};

// Adds pixel-integrated Gaussians to a CV_32FC1 signal image (DN), out to 5 sigma.
void AddSpots(cv::Mat* signal_dn, std::span<const Spot> spots);

struct SensorOptions {
  double background_dn = 10.0;    // sky / dark level
  double read_noise_dn = 2.0;     // Gaussian read noise, std (DN)
  double gain_e_per_dn = 40.0;    // photo-electrons per DN; shot noise std = sqrt(signal / gain) DN; 0 = no shot noise
  int bit_depth = 8;              // 8 or 16

  // --bit-depth, --background-dn, --read-noise-dn, --gain-e-per-dn (8-bit DN scale).
  static const io::OptionTable<SensorOptions>& Table();
  // Table().Check, and a bit depth of 8 or 16 (the CLI refuses other values when it parses them).
  bool Check(std::string* why) const;
};

// Signal (DN, CV_32FC1, background not included) → CV_8UC1 / CV_16UC1 frame with
// background, shot and read noise, rounding and clipping.
cv::Mat Digitise(const cv::Mat& signal_dn, const SensorOptions& opt, std::mt19937_64& rng);

// Expected grey-weighted centroid of a set of spots: the flux-weighted mean of
// their positions (flux = 2 pi sigma² amplitude). This is the definition of
// the "true cluster centre" in the simulator's truth files.
cv::Point2d FluxWeightedCentre(std::span<const Spot> spots);

}  // namespace rk::sim

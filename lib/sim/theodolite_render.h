// Frames of rk-sim theodolite (silhouette extraction, seed 004): the noise-free image of the cylindrical
// target against the sky (target::SilhouetteSignal, target/silhouette_image.h: exact outline, area-sampled
// coverage, Gaussian PSF, sky gradient and body shading), digitised by sim::Digitise (shot noise, read noise,
// rounding, clipping; 8 or 16 bit, DN values on the 8-bit scale are ×256 for 16 bit).
#pragma once

#include <opencv2/core.hpp>
#include <random>

#include "camera/camera_model.h"
#include "sim/render.h"
#include "sim/theodolite_scene.h"
#include "target/silhouette_image.h"

namespace rk::sim {

// The scene's radiometry (sky, body, shading, PSF: target::SilhouetteScene) and the sensor.
struct SilhouetteRenderOptions : target::SilhouetteScene {
  // Background (unused: the sky is the signal), read noise 1 DN, 100 e-/DN, 8 bit: seed 004's 11 µm pixels
  // hold ~25 000 e- over the 8-bit range, so the shot noise of a 180-DN sky is 1.3 DN (total 1.7 DN).
  SensorOptions sensor{0.0, 1.0, 100.0, 8};

  // rk-sim theodolite's image options (the sensor's under their own names: --gain, no background).
  static const io::OptionTable<SilhouetteRenderOptions>& Table();
  // Table().Check, the sky/body contrast, finite levels and the bit depth.
  bool Check(std::string* why) const;
};

// Frame of a TheodoliteSimulator at its true boresight, with noise from `rng`: target::SilhouetteSignal
// digitised by sim::Digitise.
cv::Mat RenderSilhouetteFrame(const camera::CameraModel& camera, const TheodoliteFrameTruth& frame,
                              const target::CylinderShape& shape, const SilhouetteRenderOptions& options,
                              std::mt19937_64& rng);

}  // namespace rk::sim

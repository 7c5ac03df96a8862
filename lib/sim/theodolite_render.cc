// Silhouette rendering for rk-sim theodolite; model in theodolite_render.h.
#include "sim/theodolite_render.h"

#include <cmath>

namespace rk::sim {

const io::OptionTable<SilhouetteRenderOptions>& SilhouetteRenderOptions::Table() {
  using O = SilhouetteRenderOptions;
  using io::Bounds;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--sky-dn", &O::sky_dn, "DN", Bounds::Closed(0, 255), "Images: sky level (8-bit DN)")
          .Real("--sky-gradient-dn", &O::sky_gradient_dn, "DN", Bounds::Any(),
                "Images: sky brightening top to bottom (DN)")
          .Real("--body-dn", &O::body_dn, "DN", Bounds::Closed(0, 255),
                "Images: target level (DN); above --sky-dn for a sunlit target")
          .Real("--shading-dn", &O::shading_dn, "DN", Bounds::Any(),
                "Images: +- change of the target level across its width (DN)")
          .Real("--psf-sigma-px", &O::psf_sigma_px, "px", Bounds::Closed(0, 10), "Images: Gaussian PSF std (px)")
          .Real("--read-noise-dn", [](O& o) -> double& { return o.sensor.read_noise_dn; }, "DN", Bounds::AtLeast(0),
                "Images: read noise std (DN)")
          .Real("--gain", [](O& o) -> double& { return o.sensor.gain_e_per_dn; }, "e-/DN", Bounds::AtLeast(0),
                "Images: electrons per DN for shot noise; 0 = none")
          .Integer("--bit-depth", [](O& o) -> int& { return o.sensor.bit_depth; }, "", Bounds::Any(),
                   "Images: 8 or 16");  // the values: Check()
  return table;
}

bool SilhouetteRenderOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (!(std::abs(sky_dn - body_dn) >= 5.0)) {
    *why = "--sky-dn and --body-dn must differ by at least 5 DN (no contrast, no silhouette)";
    return false;
  }
  if (!std::isfinite(sky_gradient_dn) || !std::isfinite(shading_dn)) {
    *why = "--sky-gradient-dn and --shading-dn must be finite";
    return false;
  }
  if (sensor.bit_depth != 8 && sensor.bit_depth != 16) {
    *why = "--bit-depth must be 8 or 16";
    return false;
  }
  return true;
}

cv::Mat RenderSilhouetteFrame(const camera::CameraModel& cam, const TheodoliteFrameTruth& f,
                              const target::CylinderShape& shape, const SilhouetteRenderOptions& o,
                              std::mt19937_64& rng) {
  const double scale = o.sensor.bit_depth == 16 ? 256.0 : 1.0;
  const cv::Mat signal =
      target::SilhouetteSignal(cam, f.pose, shape, f.boresight_az_rad, f.boresight_el_rad, o, scale);
  SensorOptions sensor = o.sensor;
  sensor.background_dn = 0.0;
  sensor.read_noise_dn *= scale;
  if (sensor.gain_e_per_dn > 0) sensor.gain_e_per_dn /= scale;
  return Digitise(signal, sensor, rng);
}

}  // namespace rk::sim

// Silhouette rendering for rk-sim theodolite; model in theodolite_render.h.
#include "sim/theodolite_render.h"

#include <cmath>

namespace rk::sim {

bool SilhouetteRenderOptions::Check(std::string* why) const {
  for (double v : {sky_dn, body_dn}) {
    if (!(v >= 0.0 && v <= 255.0)) {
      *why = "--sky-dn and --body-dn must be in [0, 255]";
      return false;
    }
  }
  if (!(std::abs(sky_dn - body_dn) >= 5.0)) {
    *why = "--sky-dn and --body-dn must differ by at least 5 DN (no contrast, no silhouette)";
    return false;
  }
  if (!std::isfinite(sky_gradient_dn) || !std::isfinite(shading_dn)) {
    *why = "--sky-gradient-dn and --shading-dn must be finite";
    return false;
  }
  if (!(psf_sigma_px >= 0.0 && psf_sigma_px <= 10.0)) {
    *why = "--psf-sigma-px must be in [0, 10]";
    return false;
  }
  if (!(sensor.read_noise_dn >= 0.0) || !(sensor.gain_e_per_dn >= 0.0)) {
    *why = "--read-noise-dn and --gain must be >= 0";
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

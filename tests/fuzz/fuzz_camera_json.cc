// Camera model JSON (SPEC §3): io::ParseJson → CameraModelFromJson, then the pixel ↔ ray geometry the
// tools run on a model that passed the checks.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <string>

#include "camera/camera_model.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const std::string text(rk::fuzz::AsText(data, size));
    const rk::camera::CameraModel cam =
        rk::camera::CameraModelFromJson(rk::io::ParseJson(text, "camera.json"), "camera.json");
    for (const Eigen::Vector2d& px : {Eigen::Vector2d(0, 0), cam.principal_point_px,
                                     Eigen::Vector2d(cam.width_px - 1, cam.height_px - 1)}) {
      const Eigen::Vector3d ray = cam.RayEnu(px, 0.3, 0.1);
      (void)cam.NormalisedRayJacobian(px);
      (void)cam.ProjectEnu(ray, 0.3, 0.1);
    }
    // The model written back must read back the same.
    const rk::camera::CameraModel again = rk::camera::CameraModelFromJson(rk::camera::CameraModelToJson(cam), "again");
    if (again.width_px != cam.width_px || again.height_px != cam.height_px) std::abort();
  });
  return 0;
}

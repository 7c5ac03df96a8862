// Target model JSON (SPEC §3 "Target attitude"): the feature-point model (extract::TargetModelFromJson)
// and the cylinder model (attitude::LoadCylinderTarget, which reads a path) on the same bytes.
#include <cstdint>
#include <string>

#include "attitude/cylinder_geometry.h"
#include "extract/features_model.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(rk::fuzz::AsText(data, size));
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::extract::TargetModel m = rk::extract::TargetModelFromJson(rk::io::ParseJson(text, "target.json"),
                                                                        "target.json");
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (m.Find(m.ids[i]) != static_cast<int>(i)) std::abort();  // ids sorted and unique
    }
    (void)m.Planarity();
    (void)m.IdList();
    // Written back, the model reads back with the same ids.
    if (rk::extract::TargetModelFromJson(rk::extract::TargetModelToJson(m), "again").ids != m.ids) std::abort();
  });
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::attitude::CylinderTarget t = rk::attitude::LoadCylinderTarget(rk::fuzz::WriteScratch("target.json", text));
    (void)t.SlantM();
  });
  return 0;
}

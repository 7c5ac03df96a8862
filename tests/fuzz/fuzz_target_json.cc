// Target model JSON (SPEC §3 "Target attitude"): the feature-point model (target::FeatureModelFromJson)
// and the cylinder model (target::LoadCylinderShape, which reads a path) on the same bytes.
#include <cstdint>
#include <string>

#include "fuzz_util.h"
#include "target/cylinder.h"
#include "target/feature_model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(rk::fuzz::AsText(data, size));
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::target::FeatureModel m = rk::target::FeatureModelFromJson(rk::io::ParseJson(text, "target.json"),
                                                                        "target.json");
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (m.Find(m.ids[i]) != static_cast<int>(i)) std::abort();  // ids sorted and unique
    }
    (void)m.Planarity();
    (void)m.IdList();
    // Written back, the model reads back with the same ids.
    if (rk::target::FeatureModelFromJson(rk::target::FeatureModelToJson(m), "again").ids != m.ids) std::abort();
  });
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::target::CylinderShape t = rk::target::LoadCylinderShape(rk::fuzz::WriteScratch("target.json", text));
    (void)t.SlantM();
  });
  return 0;
}

// Station config JSON of rk-capture (docs/rk-capture.md): capture::StationConfigFromJson on io::ParseJson.
// Relative paths in it resolve next to the config, in an empty scratch folder.
#include <cstdint>
#include <string>

#include "capture/station_config.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rk::fuzz::ScratchDir() + "/station.json";
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const std::string text(rk::fuzz::AsText(data, size));
    const rk::capture::StationConfig c = rk::capture::StationConfigFromJson(rk::io::ParseJson(text, path), path);
    (void)c.warnings.size();
  });
  return 0;
}

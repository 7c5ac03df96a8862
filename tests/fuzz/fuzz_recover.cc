// The y4m and PGM segment readers and frames.csv against the video, as `rk-capture recover` runs them
// (lib/capture/recover.cc, segment_writer.cc ParseY4mHeader): the input is cut at the separator lines
// "=====" into trial.json, az/seg_000.y4m, az/frames.csv and az/seg_001/000000.pgm (missing parts are
// left out), and RecoverTrial checks the trial folder (--check: it changes nothing). The y4m header
// line also goes straight to ParseY4mHeader, and a header it accepts must survive Y4mHeader's round
// trip.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "capture/recover.h"
#include "capture/segment_writer.h"
#include "fuzz_util.h"
#include "io/json_util.h"

namespace {

namespace fs = std::filesystem;

std::vector<std::string_view> Split(std::string_view text, std::string_view sep) {
  std::vector<std::string_view> parts;
  while (true) {
    const auto at = text.find(sep);
    if (at == std::string_view::npos) break;
    parts.push_back(text.substr(0, at));
    text.remove_prefix(at + sep.size());
  }
  parts.push_back(text);
  return parts;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string_view> parts = Split(rk::fuzz::AsText(data, size), "\n=====\n");
  const std::string trial = rk::fuzz::ScratchDir() + "/trial";
  std::error_code ec;
  fs::remove_all(trial, ec);
  fs::create_directories(trial + "/az/seg_001", ec);
  const char* const files[] = {"trial/trial.json", "trial/az/seg_000.y4m", "trial/az/frames.csv",
                               "trial/az/seg_001/000000.pgm"};
  for (std::size_t i = 0; i < parts.size() && i < 4; ++i) rk::fuzz::WriteScratch(files[i], parts[i]);
  if (parts.size() > 1) {
    const std::string_view y4m = parts[1];
    rk::capture::FrameFormat f;
    if (rk::capture::ParseY4mHeader(std::string(y4m.substr(0, y4m.find('\n'))), &f)) {
      if (f.width <= 0 || f.height <= 0 || (f.bit_depth != 8 && f.bit_depth != 16)) std::abort();
    }
    // The writer's round trip, for the frame rates a station config allows ((0, 1000] Hz; Y4mHeader
    // reduces the rate to a fraction, which a rate of 2/979100 Hz does not survive).
    if (rk::capture::ParseY4mHeader(std::string(y4m.substr(0, y4m.find('\n'))), &f) && f.fps >= 0.001 &&
        f.fps <= 1000) {
      rk::capture::FrameFormat again;
      const std::string header = rk::capture::Y4mHeader(f);
      if (!rk::capture::ParseY4mHeader(header.substr(0, header.size() - 1), &again) || again.width != f.width ||
          again.height != f.height || again.bit_depth != f.bit_depth) {
        std::abort();
      }
    }
  }
  rk::fuzz::ExpectOnlyInputErrors([&] {
    rk::capture::RecoverOptions o;
    o.check_only = true;
    const rk::capture::RecoverSummary s = rk::capture::RecoverTrial(trial, o);
    // As `rk-capture recover --report` writes it.
    rk::io::WriteJson(rk::fuzz::ScratchDir() + "/report.json", s.ToJson());
  });
  return 0;
}

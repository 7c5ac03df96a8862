// Shared by the recorder and recovery tests: a synthetic station recorded into a trial folder, and the check
// of a recorded camera. The synthetic camera writes each frame's sequence number into its first pixels, so
// every frame read back can be matched to its frames.csv row.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "capture/recorder.h"
#include "capture/station_config.h"
#include "io/csv.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "trial/layout.h"
#include "video/frame_source.h"

namespace rk::capture {

inline std::string WriteConfig(const std::string& dir, const io::Json& j) {
  const std::string path = dir + "/station.json";
  io::WriteJson(path, j);
  return path;
}

inline io::Json SyntheticStation(const std::string& format = "y4m") {
  return {{"cameras", {{{"name", "az"}, {"source", "synthetic:64x48"}, {"fps", 20}, {"format", format}}}},
          {"segment_s", 0.5},
          {"station", {{"lat_deg", 45.0}, {"lon_deg", 7.0}, {"h_m", 300.0}}}};
}

// Reads every frame of a camera as the manifest lists it and checks it against frames.csv.
// Returns the number of frames.
inline std::int64_t CheckCamera(const std::string& trial, const std::string& cam) {
  const io::Json m = io::LoadJson(trial + "/" + trial::kManifestFile);
  std::vector<std::string> segs;
  for (const auto& v : m["cameras"][cam]["video"]) segs.push_back(trial + "/" + v.get<std::string>());
  const io::CsvTable t = io::CsvTable::Read(trial + "/" + m["cameras"][cam]["frames"].get<std::string>());
  const int cf = t.RequireColumn("frame"), cs = t.RequireColumn("seq"), ct = t.RequireColumn("t_s");
  t.RequireIncreasing(ct);
  if (segs.empty()) {
    EXPECT_EQ(t.rows(), 0u);
    return 0;
  }
  video::FrameSource src(segs);
  cv::Mat f;
  std::size_t n = 0;
  while (src.Read(&f)) {
    EXPECT_LT(n, t.rows()) << "more frames than frames.csv rows";
    if (n >= t.rows()) break;
    EXPECT_EQ(t.Int(n, cf), static_cast<std::int64_t>(n));
    EXPECT_EQ(SyntheticFrameSeq(f), t.Int(n, cs)) << "frame " << n << " is not the frame its row names";
    ++n;
  }
  EXPECT_EQ(n, t.rows()) << "frames.csv names frames that cannot be read";
  return static_cast<std::int64_t>(n);
}

inline CaptureSummary Record(const std::string& dir, const io::Json& station, double duration_s,
                      std::function<std::int64_t()> probe = nullptr) {
  const StationConfig cfg = StationConfigFromJson(station, dir + "/station.json");
  CaptureOptions o;
  o.out_dir = dir + "/trial";
  o.duration_s = duration_s;
  o.free_space_probe = std::move(probe);
  return RunCapture(cfg, o);
}

}  // namespace rk::capture

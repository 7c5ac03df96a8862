// A beacon trial's manifest (SPEC.md trial.json) and helpers shared by the manifest and plan tests.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "io/error.h"
#include "run/manifest.h"

namespace rk::run::testing {

inline constexpr const char* kBeaconManifest = R"({"name": "t0001", "epoch_utc": "2026-11-21T08:00:00Z",
 "station": {"lat_deg": 10, "lon_deg": 20, "h_m": 5},
 "cameras": {"az":  {"video": ["az/seg_000.mkv", "az/seg_001.mkv"], "frames": "az/frames.csv",
                     "model": "az/camera.json", "role": "beacon"}},
 "turret": "turret.csv", "range": "range.csv",
 "theodolite": null, "radar": null,
 "steps": {}, "operator": "kept"})";

inline std::string WithSteps(const std::string& steps) {
  std::string m = kBeaconManifest;
  const std::string from = "\"steps\": {}";
  m.replace(m.find(from), from.size(), "\"steps\": " + steps);
  return m;
}

// The error of ParseManifest, or "" if it accepts the text.
inline std::string ManifestError(const std::string& text) {
  try {
    ParseManifest(text, "/trials/t1/trial.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    return e.what();
  }
  return "";
}

}  // namespace rk::run::testing

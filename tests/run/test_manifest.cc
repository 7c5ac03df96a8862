// Unit tests of run/manifest: the manifest's checks (errors at trial.json:LINE:COL), settings, overrides.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/error.h"
#include "manifest_examples.h"
#include "run/manifest.h"
#include "run/plan.h"

namespace rk::run {
namespace {
using testing::kBeaconManifest;
using testing::ManifestError;
using testing::WithSteps;

TEST(Manifest, ReadsTheSpecExample) {
  const TrialManifest m = ParseManifest(kBeaconManifest, "/trials/t1/trial.json");
  EXPECT_EQ(m.dir, "/trials/t1");
  EXPECT_EQ(m.name, "t0001");
  ASSERT_EQ(m.Single().cameras.size(), 1u);
  EXPECT_EQ(m.Single().cameras[0].video.size(), 2u);
  EXPECT_EQ(m.Single().cameras[0].role, CameraRole::kBeacon);
  EXPECT_EQ(m.Single().turret, "turret.csv");
  EXPECT_TRUE(m.Single().theodolite.empty());
  EXPECT_FALSE(m.radar.has_value());
  EXPECT_EQ(m.json["operator"], "kept");  // extra keys are kept
}

TEST(Manifest, ErrorsNameLineAndColumn) {
  std::string bad = kBeaconManifest;
  bad.replace(bad.find("\"beacon\""), 8, "\"beakon\"");
  EXPECT_EQ(ManifestError(bad).rfind("/trials/t1/trial.json:4:57: cameras.az.role: 'beakon' is not one of", 0), 0u)
      << ManifestError(bad);
  EXPECT_NE(ManifestError(WithSteps(R"({"locat": {}})")).find("trial.json:7:12: steps.locat: unknown step"),
            std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"locate": {"range": "r2.csv"}})")).find("cannot be overridden"),
            std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"az/attitude-oi": {}})")).find("does not apply to 'az'"), std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"cam9/locate": {}})")).find("no camera named 'cam9'"), std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"locate": {"x": {"y": 1}}})")).find("option values must be"),
            std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"locate": 3})")).find("true or false"), std::string::npos);
  std::string no_target = kBeaconManifest;
  no_target.replace(no_target.find("\"beacon\""), 8, "\"features\"");
  EXPECT_NE(ManifestError(no_target).find("needs 'target'"), std::string::npos);
  std::string epoch = kBeaconManifest;
  epoch.replace(epoch.find("2026-11-21T08:00:00Z"), 20, "21/11/2026 08:00");
  EXPECT_NE(ManifestError(epoch).find("is not an ISO-8601 UTC time"), std::string::npos);
  // One UTC reader everywhere (io::ParseUtcIso): a month 13, an hour 25 and an offset are refused too.
  for (const char* bad : {"2026-13-21T08:00:00Z", "2026-11-21T25:00:00Z", "2026-11-21T08:00:60Z",
                          "2026-11-21T08:00:00+02:00"}) {
    std::string e = kBeaconManifest;
    e.replace(e.find("2026-11-21T08:00:00Z"), 20, bad);
    EXPECT_NE(ManifestError(e).find("is not an ISO-8601 UTC time"), std::string::npos) << bad;
  }
  EXPECT_NE(ManifestError("{\"cameras\": [}").find("invalid JSON"), std::string::npos);
  EXPECT_EQ(ManifestError(WithSteps(R"({"locate": {"range-interp": "linear"}, "az/plot": false})")), "");
}

TEST(Manifest, SettingsMergeUnitOverKind) {
  const TrialManifest m = ParseManifest(
      WithSteps(R"({"locate": {"range-interp": "linear", "turret-max-gap": 0.5},
                    "az/locate": {"range-interp": "cubic"}, "resample-range": false})"),
      "/t/trial.json");
  const StepSettings s = m.Settings("az", "locate");
  EXPECT_TRUE(s.enabled);
  ASSERT_EQ(s.options.size(), 2u);
  EXPECT_EQ(s.options[0].second, "cubic");
  EXPECT_FALSE(m.Settings("az", "resample-range").enabled);
  EXPECT_TRUE(m.Settings("az", "smooth").enabled);
}

TEST(Manifest, OverrideArgs) {
  StepSettings s;
  s.options = {{"range-interp", "linear"}, {"lead", 0.5}, {"window", 4}, {"smooth", true}, {"bg-plane", false},
               {"accel-sigma", io::Json::array({1.5, 2})}};
  EXPECT_EQ(OverrideArgs(s), (std::vector<std::string>{"--range-interp", "linear", "--lead", "0.5", "--window", "4",
                                                       "--smooth", "--accel-sigma", "1.5,2"}));
}

}  // namespace
}  // namespace rk::run

// Unit tests of trial/manifest.h: the writer's form (keys, nulls) and that the reader reads back what it
// wrote.
#include <gtest/gtest.h>

#include <string>

#include "io/json_util.h"
#include "trial/layout.h"
#include "trial/manifest.h"

namespace rk::trial {
namespace {

Manifest BeaconTrial() {
  Manifest m;
  m.name = "t0001";
  m.epoch_utc = "2026-11-21T08:00:00Z";
  m.station = {{"lat_deg", 10.5}, {"lon_deg", 20}, {"h_m", 5.0}};
  const CameraEntry az = CameraInItsFolder("az", CameraRole::kBeacon, {"az/seg_000.mkv", "az/seg_001.mkv"});
  CameraEntry theo;
  theo.name = "theo";
  theo.video = {"theo/%06d.png"};
  theo.fps = 20.0;
  theo.t0_s = 1.5;
  theo.model = "theo/camera.json";
  theo.role = CameraRole::kSilhouette;
  theo.target = kTargetModelFile;
  theo.boresight_deg = std::make_pair(326.25, 16.5);
  m.cameras = {az, theo};
  m.turret = kTurretFile;
  m.theodolite = kTheodoliteFile;
  m.radar = RadarEntry{"plots.csv", "nav.csv"};
  m.steps = {{"plot", false}};
  m.extra = {{"sim", {{"generator", "test"}}}};
  return m;
}

TEST(ManifestWriter, EveryKeyOfTheSpecAndNullsForAbsentFiles) {
  Manifest m = BeaconTrial();
  m.cameras[0].model.clear();  // rk-capture without a camera model: null
  m.radar.reset();
  const io::Json j = ManifestToJson(m);
  for (const char* key : {"name", "epoch_utc", "station", "cameras", "turret", "range", "theodolite", "radar",
                          "steps", "sim"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j.size(), 10u);
  EXPECT_TRUE(j["range"].is_null());
  EXPECT_TRUE(j["radar"].is_null());
  EXPECT_TRUE(j["cameras"]["az"]["model"].is_null());
  EXPECT_FALSE(j["cameras"]["az"].contains("target"));
  EXPECT_FALSE(j["cameras"]["az"].contains("fps"));
  EXPECT_EQ(j["cameras"]["az"]["role"], "beacon");
  EXPECT_EQ(j["cameras"]["az"]["frames"], "az/frames.csv");
  EXPECT_EQ(j["cameras"]["theo"]["boresight_deg"], io::Json::array({326.25, 16.5}));
  // The station is written as given (an integer stays an integer).
  EXPECT_EQ(j["station"].dump(), R"({"h_m":5.0,"lat_deg":10.5,"lon_deg":20})");
}

TEST(ManifestWriter, ReaderReadsBackWhatTheWriterWrote) {
  const Manifest w = BeaconTrial();
  const Manifest r = ParseManifest(ManifestToJson(w).dump(2), "/trials/t0001/trial.json");
  EXPECT_EQ(r.dir, "/trials/t0001");
  EXPECT_EQ(r.name, w.name);
  EXPECT_EQ(r.epoch_utc, w.epoch_utc);
  EXPECT_EQ(r.station, w.station);
  ASSERT_EQ(r.cameras.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const CameraEntry &a = w.cameras[i], &b = r.cameras[i];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.video, a.video);
    EXPECT_EQ(b.frames, a.frames);
    EXPECT_EQ(b.fps, a.fps);
    EXPECT_EQ(b.t0_s, a.t0_s);
    EXPECT_EQ(b.model, a.model);
    EXPECT_EQ(b.role, a.role);
    EXPECT_EQ(b.target, a.target);
    EXPECT_EQ(b.boresight_deg, a.boresight_deg);
  }
  EXPECT_EQ(r.turret, w.turret);
  EXPECT_TRUE(r.range.empty());
  EXPECT_EQ(r.theodolite, w.theodolite);
  ASSERT_TRUE(r.radar.has_value());
  EXPECT_EQ(r.radar->plots, "plots.csv");
  EXPECT_EQ(r.radar->nav, "nav.csv");
  EXPECT_EQ(r.steps, w.steps);
  EXPECT_EQ(r.json["sim"]["generator"], "test");
  EXPECT_EQ(r.AllPaths().size(),
            11u);  // 3 videos, 1 frames, 2 models, 1 target, turret, theodolite, plots, nav
}

}  // namespace
}  // namespace rk::trial

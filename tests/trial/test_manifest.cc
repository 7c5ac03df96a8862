// Unit tests of trial/manifest.h: the writer's form (keys, nulls) and that the reader reads back what it
// wrote.
#include <gtest/gtest.h>

#include <string>

#include "io/error.h"
#include "io/json_util.h"
#include "trial/layout.h"
#include "trial/manifest.h"

namespace rk::trial {
namespace {

Manifest BeaconTrial() {
  Manifest m;
  m.name = "t0001";
  m.epoch_utc = "2026-11-21T08:00:00Z";
  m.Single().station = {{"lat_deg", 10.5}, {"lon_deg", 20}, {"h_m", 5.0}};
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
  m.Single().cameras = {az, theo};
  m.Single().turret = kTurretFile;
  m.Single().theodolite = kTheodoliteFile;
  m.radar = RadarEntry{"plots.csv", "nav.csv"};
  m.steps = {{"plot", false}};
  m.extra = {{"sim", {{"generator", "test"}}}};
  return m;
}

TEST(ManifestWriter, EveryKeyOfTheSpecAndNullsForAbsentFiles) {
  Manifest m = BeaconTrial();
  m.Single().cameras[0].model.clear();  // rk-capture without a camera model: null
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
  ASSERT_FALSE(r.multi_station());
  ASSERT_EQ(r.stations.size(), 1u);
  EXPECT_EQ(r.Single().station, w.Single().station);
  ASSERT_EQ(r.Single().cameras.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const CameraEntry &a = w.Single().cameras[i], &b = r.Single().cameras[i];
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
  EXPECT_EQ(r.Single().turret, w.Single().turret);
  EXPECT_TRUE(r.Single().range.empty());
  EXPECT_EQ(r.Single().theodolite, w.Single().theodolite);
  ASSERT_TRUE(r.radar.has_value());
  EXPECT_EQ(r.radar->plots, "plots.csv");
  EXPECT_EQ(r.radar->nav, "nav.csv");
  EXPECT_EQ(r.steps, w.steps);
  EXPECT_EQ(r.json["sim"]["generator"], "test");
  EXPECT_EQ(r.AllPaths().size(),
            11u);  // 3 videos, 1 frames, 2 models, 1 target, turret, theodolite, plots, nav
}


// A single-station manifest is written byte for byte as before the multi-station form existed (issue 18): the
// text below is what ManifestToJson(BeaconTrial()).dump(1) gave at 7b68eb7.
TEST(ManifestWriter, SingleStationFormUnchanged) {
  Manifest m = BeaconTrial();
  m.Single().cameras.resize(1);
  m.radar.reset();
  const io::Json j = ManifestToJson(m);
  EXPECT_FALSE(j.contains("stations"));
  EXPECT_FALSE(j.contains("origin"));
  EXPECT_EQ(j.dump(),
            R"({"cameras":{"az":{"frames":"az/frames.csv","model":"az/camera.json","role":"beacon","video":)"
            R"(["az/seg_000.mkv","az/seg_001.mkv"]}},"epoch_utc":"2026-11-21T08:00:00Z","name":"t0001",)"
            R"("radar":null,"range":null,"sim":{"generator":"test"},"station":{"h_m":5.0,"lat_deg":10.5,)"
            R"("lon_deg":20},"steps":{"plot":false},"theodolite":"theodolite.csv","turret":"turret.csv"})");
}

// Several stations: written with "origin" and "stations" (each station's keys in the single-station form), read
// back the same; `stations` holds them, or the top level as one unnamed station (Single() refuses the first).
TEST(ManifestWriter, SeveralStationsRoundTrip) {
  Manifest w;
  w.name = "ms";
  w.epoch_utc = "2026-01-01T00:00:00Z";
  w.origin = {{"lat_deg", 47.0}, {"lon_deg", 8.0}, {"h_m", 400.0}};
  for (const char* name : {"s1", "s2"}) {
    StationEntry st;
    st.name = name;
    st.station = {{"lat_deg", 47.0}, {"lon_deg", name[1] == '1' ? 8.0 : 8.1}, {"h_m", 400.0}};
    CameraEntry az = CameraInItsFolder("az", CameraRole::kBeacon, {std::string(name) + "/az/video.mkv"});
    az.frames = std::string(name) + "/" + az.frames;
    az.model = std::string(name) + "/" + az.model;
    st.cameras = {az};
    st.turret = std::string(name) + "/turret.csv";
    w.stations.push_back(st);
  }
  w.stations[0].range = "s1/range.csv";
  const io::Json j = ManifestToJson(w);
  for (const char* key : {"station", "cameras", "turret", "range", "theodolite"}) EXPECT_FALSE(j.contains(key)) << key;
  EXPECT_EQ(j["stations"]["s2"]["turret"], "s2/turret.csv");
  EXPECT_TRUE(j["stations"]["s2"]["range"].is_null());
  const Manifest r = ParseManifest(j.dump(1), "/trials/ms/trial.json");
  ASSERT_TRUE(r.multi_station());
  ASSERT_EQ(r.stations.size(), 2u);
  EXPECT_EQ(r.origin, w.origin);
  EXPECT_THROW(r.Single(), Error);
  EXPECT_EQ(r.stations[1].name, "s2");
  EXPECT_EQ(r.stations[1].station, w.stations[1].station);
  EXPECT_EQ(r.stations[1].Unit(r.stations[1].cameras[0]), "s2/az");
  EXPECT_EQ(r.stations[0].range, "s1/range.csv");
  EXPECT_EQ(r.AllPaths().size(), 9u);  // per station video, frames, model, turret; s1's range
  EXPECT_EQ(ManifestToJson(r), j);
  const Manifest single = ParseManifest(ManifestToJson(BeaconTrial()).dump(), "/trials/t0001/trial.json");
  ASSERT_EQ(single.stations.size(), 1u);
  EXPECT_EQ(single.stations[0].name, "");
  EXPECT_EQ(single.stations[0].Unit(single.Single().cameras[0]), "az");
}

// Errors of the multi-station form name the field and its line and column.
TEST(ManifestReader, SeveralStationsErrors) {
  const auto error = [](const std::string& text) -> std::string {
    try {
      ParseManifest(text, "/trials/ms/trial.json");
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kInvalidData);
      return e.what();
    }
    return "";
  };
  const std::string st = R"({"station": {"lat_deg": 1, "lon_deg": 2, "h_m": 3}})";
  EXPECT_NE(error(R"({"stations": {"a": )" + st + "}}").find("trial.json:1:14: stations: a multi-station trial needs at least two stations"),
            std::string::npos)
      << error(R"({"stations": {"a": )" + st + "}}");
  EXPECT_NE(error(R"({"stations": {"a": )" + st + R"(,
 "b": {"turret": "b.csv"}}})").find("trial.json:2:7: stations.b: missing field 'station'"),
            std::string::npos);
  EXPECT_NE(error(R"({"cameras": {}, "stations": {"a": )" + st + R"(, "b": )" + st + "}}")
                .find("trial.json:1:2: cameras: a manifest with 'stations' gives 'cameras' per station"),
            std::string::npos);
  EXPECT_NE(error(R"({"stations": {"a": )" + st + R"(, "b": )" + st + R"(}, "origin": {"lat_deg": 91, "lon_deg": 0, "h_m": 0}})")
                .find("origin.lat_deg: latitude must be in"),
            std::string::npos);
  EXPECT_NE(error(R"({"stations": {"a": )" + st + R"(, "b.c": )" + st + "}}").find("station name 'b.c'"),
            std::string::npos);
  EXPECT_NE(error(R"({"stations": {"a": )" + st + R"(, "b": {"station": {"lat_deg": 1, "lon_deg": 2, "h_m": 3},
 "cameras": {"az": {"video": "v.mkv", "fps": 10, "model": "m.json", "role": "beakon"}}}}})")
                .find("trial.json:2:77: stations.b.cameras.az.role: 'beakon' is not one of"),
            std::string::npos);
}

}  // namespace
}  // namespace rk::trial

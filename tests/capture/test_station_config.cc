// The station configuration (capture/station_config.h): paths relative to the file, keys checked.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "capture/station_config.h"
#include "io/error.h"
#include "io/json_util.h"
#include "test_station.h"
#include "rk_test/temp_dir.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

TEST(StationConfig, PathsAreRelativeToTheFileAndKeysAreChecked) {
  const rk::test::TempDir dir_tmp("capture_cfg");
  const std::string dir = dir_tmp.path();
  fs::create_directories(dir + "/models");
  io::WriteJson(dir + "/models/az.json", {{"width_px", 64}, {"height_px", 48}, {"pixel_size_mm", {0.005, 0.005}},
                                          {"focal_length_mm", 50.0}, {"principal_point_px", {31.5, 23.5}}});
  io::Json j = {{"cameras",
                 {{{"name", "az"}, {"source", "file:video/a.mkv"}, {"fps", 20}, {"model", "models/az.json"},
                   {"rate", 3}}}},
                {"rangefinder", {{"port", "dls"}, {"baud", 115200}, {"parity", "even"}, {"mode", "single"}}},
                {"turret", {{"port", "/dev/ttyUSB1"}, {"pan_zero_deg", 12.5}, {"tilt_sign", -1}}},
                {"segment_s", 10}};
  const StationConfig c = StationConfigFromJson(j, WriteConfig(dir, j));
  ASSERT_EQ(c.cameras.size(), 1u);
  EXPECT_EQ(c.cameras[0].source.source, "file:" + dir + "/video/a.mkv");
  EXPECT_EQ(c.cameras[0].model_path, dir + "/models/az.json");
  ASSERT_TRUE(c.rangefinder);
  EXPECT_EQ(c.rangefinder->serial.port, dir + "/dls");
  EXPECT_EQ(c.rangefinder->serial.parity, "even");
  EXPECT_EQ(c.rangefinder->mode, DimetixMode::kSingle);
  ASSERT_TRUE(c.turret);
  EXPECT_EQ(c.turret->serial.port, "/dev/ttyUSB1");
  EXPECT_EQ(c.turret->map.tilt_sign, -1.0);
  bool warned = false;
  for (const auto& w : c.warnings) warned = warned || w.find("unknown key 'rate'") != std::string::npos;
  EXPECT_TRUE(warned);

  auto bad = [&](io::Json broken, const std::string& expect) {
    try {
      StationConfigFromJson(broken, dir + "/station.json");
      ADD_FAILURE() << "accepted: " << broken.dump();
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  };
  io::Json b = j;
  b["rangefinder"]["parity"] = "mark";
  bad(b, "rangefinder: 'parity'");
  b = j;
  b["turret"]["pan_sign"] = 2;
  bad(b, "pan_sign");
  b = j;
  b["cameras"].push_back(j["cameras"][0]);
  bad(b, "two cameras are named 'az'");
  b = j;
  b["cameras"][0]["queue_frames"] = 100;
  bad(b, "at most one second");
  b = j;
  b["cameras"][0]["source"] = "synthetic:axb";
  bad(b, "synthetic:WIDTHxHEIGHT");
  b = j;
  b["sync_s"] = 5;
  bad(b, "sync_s");
  b = j;
  b["cameras"][0]["name"] = "../x";
  bad(b, "letters, digits");
  b = j;
  b["rangefinder"]["port"] = dir + "/ptu";
  b["turret"]["port"] = dir + "/ptu";
  bad(b, "same port");
  io::Json empty = io::Json::object();
  bad(empty, "no cameras, rangefinder or turret");
  b = j;
  b["cameras"][0]["model"] = "models/missing.json";
  try {
    StationConfigFromJson(b, dir + "/station.json");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kIo);
  }
  fs::remove_all(dir);
}

// SPEC.md §3.1: the station's pointing model, named as station.pointing relative to the file, is checked when
// read and named in the trial's manifest as its own copy, pointing.json.
TEST(StationConfig, PointingModelIsCheckedAndRenamedForTheTrial) {
  const rk::test::TempDir dir_tmp("capture_cfg_pointing");
  const std::string dir = dir_tmp.path();
  fs::create_directories(dir + "/cal");
  io::WriteJson(dir + "/cal/pm.json", {{"az_offset_deg", 12.5}, {"tilt_north_deg", 0.01}});
  io::Json j = {{"turret", {{"port", "/dev/ttyUSB1"}}},
                {"station", {{"lat_deg", 39.9}, {"lon_deg", 116.3}, {"h_m", 50.0}, {"pointing", "cal/pm.json"}}}};
  const StationConfig c = StationConfigFromJson(j, WriteConfig(dir, j));
  EXPECT_EQ(c.pointing_path, dir + "/cal/pm.json");
  EXPECT_EQ(c.station.at("pointing"), "pointing.json");
  EXPECT_EQ(c.station.at("lat_deg"), 39.9);
  io::WriteJson(dir + "/cal/bad.json", {{"tilt_east_deg", 45}});
  j["station"]["pointing"] = "cal/bad.json";
  try {
    StationConfigFromJson(j, dir + "/station.json");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("tilt_east_deg"), std::string::npos) << e.what();
  }
  j["station"]["pointing"] = "cal/missing.json";
  try {
    StationConfigFromJson(j, dir + "/station.json");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kIo);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rk::capture

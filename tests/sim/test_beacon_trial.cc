// Tests of the trial directory writer (sim/beacon_trial.h): layout, columns,
// error rows, atomic replacement rules.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/json_util.h"
#include "sim/beacon_trial.h"
#include "rk_test/temp_dir.h"

namespace rk::sim {
namespace {
namespace fs = std::filesystem;

class BeaconTrialTest : public ::testing::Test {
 protected:
  void SetUp() override {
    tmp_ = std::make_unique<rk::test::TempDir>("sim_beacon_trial");
    dir_ = tmp_->path();
  }
  std::unique_ptr<rk::test::TempDir> tmp_;

  static BeaconSimOptions Options() {
    BeaconSimOptions o;
    CameraPreset("small", &o.camera);
    o.duration_s = 1.0;
    o.range_error_rate = 0.3;  // plenty of error rows in a short log
    o.distractors = 1;
    o.occlusions.push_back({0.5, 0.25});
    return o;
  }

  std::string dir_;
};

TEST_F(BeaconTrialTest, WritesTheSpecLayout) {
  const BeaconSimulator sim(Options());
  TrialWriteOptions w;
  w.out_dir = dir_ + "/trial";
  w.format = "png";
  const TrialSummary sum = WriteBeaconTrial(sim, w);
  EXPECT_EQ(sum.frames, 20);
  EXPECT_EQ(sum.visible_frames, 15);
  for (const char* f : {"trial.json", "az/camera.json", "az/frames.csv", "az/000000.png", "az/000019.png",
                        "turret.csv", "range.csv", "truth/beacon.csv", "truth/target.csv", "truth/turret.csv",
                        "truth/range.csv"}) {
    EXPECT_TRUE(fs::exists(fs::path(w.out_dir) / f)) << f;
  }
  EXPECT_FALSE(fs::exists(fs::path(w.out_dir) / "az/000020.png"));
  // Nothing left beside the trial.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) entries += e.path().filename() != "trial";
  EXPECT_EQ(entries, 0);

  const io::Json m = io::LoadJson(w.out_dir + "/trial.json");
  EXPECT_EQ(m.at("cameras").at("az").at("role"), "beacon");
  EXPECT_EQ(m.at("cameras").at("az").at("video").at(0), "az/%06d.png");
  EXPECT_EQ(m.at("cameras").at("az").at("frames"), "az/frames.csv");
  EXPECT_EQ(m.at("cameras").at("az").at("model"), "az/camera.json");
  EXPECT_EQ(m.at("turret"), "turret.csv");
  EXPECT_EQ(m.at("range"), "range.csv");
  EXPECT_TRUE(m.at("theodolite").is_null());
  EXPECT_TRUE(m.at("radar").is_null());
  EXPECT_TRUE(m.at("steps").is_object());
  EXPECT_EQ(m.at("sim").at("seed"), 1);
  EXPECT_EQ(m.at("name"), "trial");

  const cv::Mat img = cv::imread(w.out_dir + "/az/000000.png", cv::IMREAD_UNCHANGED);
  EXPECT_EQ(cv::norm(img, sim.RenderFrame(0), cv::NORM_INF), 0.0);

  const auto frames = io::CsvTable::Read(w.out_dir + "/az/frames.csv");
  ASSERT_EQ(frames.rows(), 20u);
  EXPECT_EQ(frames.Int(19, frames.RequireColumn("frame")), 19);
  EXPECT_NEAR(frames.Double(19, frames.RequireColumn("t_s")), sim.frame(19).t_s, 1e-9);

  const auto range = io::CsvTable::Read(w.out_dir + "/range.csv");
  const int rc = range.RequireColumn("range_m"), sc = range.RequireColumn("status");
  range.RequireIncreasing(range.RequireColumn("t_s"));
  int errors = 0;
  for (std::size_t i = 0; i < range.rows(); ++i) {
    const auto status = range.Int(i, sc);
    if (status == 255) {
      EXPECT_TRUE(range.IsEmpty(i, rc));
      ++errors;
    } else {
      EXPECT_EQ(status, 0);
      EXPECT_FALSE(range.IsEmpty(i, rc));
    }
  }
  EXPECT_GT(errors, 0);
  EXPECT_EQ(errors, sum.range_error_rows);

  const auto beacon = io::CsvTable::Read(w.out_dir + "/truth/beacon.csv");
  const int xc = beacon.RequireColumn("x_px"), vc = beacon.RequireColumn("visible");
  beacon.RequireColumn("distractor_min_dist_px");
  for (std::size_t i = 0; i < beacon.rows(); ++i) {
    EXPECT_EQ(beacon.Int(i, vc) == 1, sim.frame(i).visible);
    EXPECT_EQ(beacon.IsEmpty(i, xc), !sim.frame(i).visible);
    if (sim.frame(i).visible) {
      EXPECT_NEAR(beacon.Double(i, xc), sim.frame(i).centre_px.x(), 5e-5);
    }
  }
  const auto target = io::CsvTable::Read(w.out_dir + "/truth/target.csv");
  for (const char* c : {"frame", "t_s", "az_deg", "el_deg", "range_m", "e_m", "n_m", "u_m"}) target.RequireColumn(c);
  EXPECT_NEAR(target.Double(3, target.RequireColumn("az_deg")), geo::RadToDeg(sim.frame(3).az_rad), 1e-9);
  const auto turret = io::CsvTable::Read(w.out_dir + "/turret.csv");
  const auto turret_truth = io::CsvTable::Read(w.out_dir + "/truth/turret.csv");
  EXPECT_EQ(turret.rows(), turret_truth.rows());
  EXPECT_EQ(static_cast<std::int64_t>(turret.rows()), sum.turret_rows);
}

TEST_F(BeaconTrialTest, RefusesANonEmptyFolderUnlessForced) {
  const BeaconSimulator sim(Options());
  TrialWriteOptions w;
  w.out_dir = dir_ + "/trial";
  w.format = "png";
  fs::create_directories(w.out_dir);
  { std::ofstream(w.out_dir + "/keep.txt") << "precious"; }
  try {
    WriteBeaconTrial(sim, w);
    ADD_FAILURE() << "expected a usage error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
  }
  EXPECT_TRUE(fs::exists(w.out_dir + "/keep.txt"));
  EXPECT_FALSE(fs::exists(w.out_dir + "/trial.json"));
  w.force = true;
  WriteBeaconTrial(sim, w);
  EXPECT_FALSE(fs::exists(w.out_dir + "/keep.txt"));
  EXPECT_TRUE(fs::exists(w.out_dir + "/trial.json"));
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) entries += e.path().filename() != "trial";
  EXPECT_EQ(entries, 0);  // old trial and temporary folders removed
}

TEST_F(BeaconTrialTest, AcceptsAnEmptyFolderAndRejectsBadWriteOptions) {
  const BeaconSimulator sim(Options());
  TrialWriteOptions w;
  w.out_dir = dir_ + "/empty/";
  w.format = "png";
  fs::create_directories(w.out_dir);
  WriteBeaconTrial(sim, w);
  EXPECT_TRUE(fs::exists(dir_ + "/empty/trial.json"));
  std::string why;
  w.format = "avi";
  EXPECT_FALSE(w.Check(&why));
  w.format = "mkv";
  w.epoch_utc = "yesterday";
  EXPECT_FALSE(w.Check(&why));
}

}  // namespace
}  // namespace rk::sim

// Recording a station into a trial directory (capture/recorder.h). Truth: the synthetic camera writes each
// frame's sequence number into its first pixels, so every frame read back can be matched to its frames.csv
// row.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "capture/recorder.h"
#include "capture/recover.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "test_station.h"
#include "rk_test/temp_dir.h"
#include "trial/layout.h"
#include "video/frame_sink.h"
#include "video/frame_source.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

TEST(Recorder, SyntheticCameraTrialReadsBack) {
  const rk::test::TempDir dir_tmp("capture_basic");
  const std::string dir = dir_tmp.path();
  const CaptureSummary s = Record(dir, SyntheticStation(), 0.8);
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.stop_reason, "duration");
  EXPECT_EQ(s.write_failures, 0);
  EXPECT_EQ(s.cameras[0].dropped_queue, 0);
  // 0.8 s at 20 fps: 16 or 17 frames (the first frame is due at once); allow one late frame.
  EXPECT_GE(s.cameras[0].written, 15);
  EXPECT_LE(s.cameras[0].written, 17);
  EXPECT_EQ(s.cameras[0].segments, 2);  // 10 frames per 0.5-s segment
  const std::string trial = dir + "/trial";
  EXPECT_EQ(CheckCamera(trial, "az"), s.cameras[0].written);
  const io::Json m = io::LoadJson(trial + "/trial.json");
  EXPECT_EQ(m["capture"]["state"], "complete");
  EXPECT_EQ(m["station"]["lat_deg"], 45.0);
  EXPECT_TRUE(m["turret"].is_null());
  EXPECT_TRUE(m["range"].is_null());
  EXPECT_EQ(m["cameras"]["az"]["video"].size(), 2u);
  EXPECT_EQ(m["cameras"]["az"]["role"], "beacon");
  EXPECT_TRUE(m["capture"]["clocks"].contains("kernel_clocksource"));
  EXPECT_EQ(m["capture"]["config"]["segment_s"], 0.5);  // the configuration, kept as given
  // The epoch is a whole UTC second and the first frame comes within the first seconds.
  const std::string epoch = m["epoch_utc"];
  EXPECT_EQ(epoch.size(), 20u);
  const io::CsvTable t = io::CsvTable::Read(trial + "/az/frames.csv");
  const double t0 = t.Double(0, t.RequireColumn("t_s"));
  EXPECT_GE(t0, 0.0);
  EXPECT_LT(t0, 5.0);
  // A clean recording needs no repair.
  const RecoverSummary r = RecoverTrial(trial, {});
  EXPECT_TRUE(r.readable());
  EXPECT_TRUE(r.repairs.empty()) << r.repairs.front();
  EXPECT_EQ(r.state_after, "complete");
  fs::remove_all(dir);
}

TEST(Recorder, PgmSequenceSegments) {
  const rk::test::TempDir dir_tmp("capture_pgm");
  const std::string dir = dir_tmp.path();
  const CaptureSummary s = Record(dir, SyntheticStation("pgm"), 0.7);
  EXPECT_EQ(s.write_failures, 0);
  const std::string trial = dir + "/trial";
  const io::Json m = io::LoadJson(trial + "/trial.json");
  EXPECT_EQ(m["cameras"]["az"]["video"][0], "az/seg_000/%06d.pgm");
  EXPECT_EQ(CheckCamera(trial, "az"), s.cameras[0].written);
  fs::remove_all(dir);
}

// The OpenCV VideoCapture path (V4L2 and GStreamer cameras use it) on a file: every frame of an FFV1
// grey video recorded bit-exact (grey → BGR → grey is exact in OpenCV's integer conversion).
TEST(Recorder, OpenCvSourceRecordsEveryFrameOfAFile) {
  const rk::test::TempDir dir_tmp("capture_cvfile");
  const std::string dir = dir_tmp.path();
  std::vector<cv::Mat> src;
  {
    video::FrameSink sink(dir + "/src.mkv", 64, 48, 8, 40.0);
    for (int k = 0; k < 12; ++k) {
      cv::Mat m(48, 64, CV_8UC1);
      cv::RNG rng(static_cast<std::uint64_t>(k) + 7);
      rng.fill(m, cv::RNG::UNIFORM, 0, 256);
      sink.Write(m);
      src.push_back(m);
    }
    sink.Close();
  }
  io::Json j = {{"cameras", {{{"name", "az"}, {"source", "cvfile:src.mkv"}, {"fps", 40}}}}};
  const CaptureSummary s = Record(dir, j, 5.0);
  EXPECT_EQ(s.stop_reason, "sources ended");  // the file's 12 frames at 40 fps, long before 5 s
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].source_kind, "opencv-file");
  EXPECT_NEAR(s.cameras[0].fps, 40.0, 1e-9);
  EXPECT_TRUE(s.cameras[0].ended);
  ASSERT_EQ(s.cameras[0].written, 12);
  const io::Json m = io::LoadJson(dir + "/trial/trial.json");
  std::vector<std::string> segs;
  for (const auto& v : m["cameras"]["az"]["video"]) segs.push_back(dir + "/trial/" + v.get<std::string>());
  video::FrameSource rec(segs);
  cv::Mat f;
  for (int k = 0; k < 12; ++k) {
    ASSERT_TRUE(rec.Read(&f));
    EXPECT_EQ(cv::norm(f, src[static_cast<std::size_t>(k)], cv::NORM_INF), 0.0) << "frame " << k;
  }
  fs::remove_all(dir);
}

TEST(Recorder, DiskAlmostFullDropsVideoAsAGap) {
  const rk::test::TempDir dir_tmp("capture_full");
  const std::string dir = dir_tmp.path();
  // The probe says 1 MB free: below the default 512 MB reserve, every frame is dropped.
  const CaptureSummary s = Record(dir, SyntheticStation(), 0.4, [] { return std::int64_t{1000000}; });
  EXPECT_EQ(s.cameras[0].written, 0);
  EXPECT_GT(s.cameras[0].dropped_disk, 0);
  EXPECT_GT(s.write_failures, 0);
  EXPECT_EQ(s.gaps, 1);
  const std::string trial = dir + "/trial";
  const io::Json m = io::LoadJson(trial + "/trial.json");
  ASSERT_EQ(m["capture"]["gaps"].size(), 1u);
  EXPECT_EQ(m["capture"]["gaps"][0]["stream"], "camera:az");
  EXPECT_NE(m["capture"]["gaps"][0]["reason"].get<std::string>().find("disk almost full"), std::string::npos);
  EXPECT_EQ(CheckCamera(trial, "az"), 0);
  const std::string frames = io::ReadFile(trial + "/az/frames.csv");
  EXPECT_NE(frames.find("# gap begins at t_s="), std::string::npos);
  EXPECT_TRUE(RecoverTrial(trial, {}).readable());
  fs::remove_all(dir);
}

TEST(Recorder, RefusesANonEmptyFolderAndLeavesItAlone) {
  const rk::test::TempDir dir_tmp("capture_refuse");
  const std::string dir = dir_tmp.path();
  fs::create_directories(dir + "/trial");
  std::ofstream(dir + "/trial/keep.txt") << "precious";
  EXPECT_THROW(Record(dir, SyntheticStation(), 0.2), Error);
  EXPECT_EQ(io::ReadFile(dir + "/trial/keep.txt"), "precious");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir + "/trial"), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(Recorder, ADeviceThatIsNotThereLeavesNothingBehind) {
  const rk::test::TempDir dir_tmp("capture_nodev");
  const std::string dir = dir_tmp.path();
  io::Json j = SyntheticStation();
  j["rangefinder"] = {{"port", dir + "/no-such-tty"}, {"baud", 115200}};
  try {
    Record(dir, j, 0.2);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kIo);
    EXPECT_NE(std::string(e.what()).find("no-such-tty"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(dir + "/trial"));
  fs::remove_all(dir);
}

// Issue 16 item 1: --duration's bound and report key come from CaptureOptions::Table(); the folder rule
// stays hand-written after it.
TEST(CaptureOptions, TableCheckAndReportKey) {
  CaptureOptions o;
  o.out_dir = "trial";
  std::string why;
  EXPECT_TRUE(o.Check(&why)) << why;
  o.duration_s = -1.0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--duration must be finite and >= 0 s");
  o.duration_s = 2.5;
  EXPECT_EQ(CaptureOptions::Table().ToJson(o).at("duration_s"), 2.5);
  o.out_dir = "-";
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--out must name a folder");
}

}  // namespace
}  // namespace rk::capture

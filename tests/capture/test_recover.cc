// Recovery of a trial folder (capture/recover.h) after the damage a crash or a power cut leaves.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "capture/recover.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "test_station.h"
#include "rk_test/temp_dir.h"
#include "trial/layout.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

class Recover : public ::testing::Test {
 protected:
  const rk::test::TempDir tmp_{"capture_recover"};
  void SetUp() override {
    dir_ = tmp_.path();
    const CaptureSummary s = Record(dir_, SyntheticStation(), 0.8);
    frames_ = s.cameras[0].written;
    trial_ = dir_ + "/trial";
    seg1_ = trial_ + "/az/seg_001.y4m";
    frame_bytes_ = 6 + 64 * 48;
  }
  void Append(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::app | std::ios::binary) << bytes;
  }
  void SetState(const std::string& state) {
    io::Json m = io::LoadJson(trial_ + "/trial.json");
    m["capture"]["state"] = state;
    m["cameras"]["az"]["video"] = io::Json::array({"az/seg_000.y4m"});  // as if the last update was lost
    io::WriteJson(trial_ + "/trial.json", m);
  }
  std::string dir_, trial_, seg1_;
  std::int64_t frames_ = 0, frame_bytes_ = 0;
};

TEST_F(Recover, RepairsTornTailsAndTheManifestAndIsIdempotent) {
  SetState("recording");
  Append(seg1_, "FRAME\n" + std::string(100, 'x'));                      // torn frame
  Append(trial_ + "/az/frames.csv", "999,12.5");                         // torn row
  Append(trial_ + "/events.log", "12.0 2026-01-01T00:00:00.000Z info x: half");  // torn event
  RecoverOptions check;
  check.check_only = true;
  const std::string before = io::ReadFile(trial_ + "/az/frames.csv");
  const RecoverSummary c = RecoverTrial(trial_, check);
  EXPECT_GE(c.repairs.size(), 4u);
  EXPECT_EQ(io::ReadFile(trial_ + "/az/frames.csv"), before);  // --check changes nothing
  const RecoverSummary r = RecoverTrial(trial_, {});
  EXPECT_TRUE(r.readable()) << r.problems.front();
  EXPECT_EQ(r.state_before, "recording");
  EXPECT_EQ(r.state_after, "recovered");
  EXPECT_EQ(r.frames.at("az"), frames_);
  EXPECT_EQ(CheckCamera(trial_, "az"), frames_);
  const io::Json m = io::LoadJson(trial_ + "/trial.json");
  EXPECT_EQ(m["cameras"]["az"]["video"].size(), 2u);
  EXPECT_EQ(m["capture"]["state"], "recovered");
  EXPECT_FALSE(m["capture"]["recover"]["repairs"].empty());
  const RecoverSummary again = RecoverTrial(trial_, {});
  EXPECT_TRUE(again.readable());
  EXPECT_TRUE(again.repairs.empty()) << again.repairs.front();
}

TEST_F(Recover, RowsWithoutFramesAndFramesWithoutRowsAtTheEnd) {
  // A power cut: the last frame did not reach the disk but its row did.
  fs::resize_file(seg1_, fs::file_size(seg1_) - static_cast<std::uintmax_t>(frame_bytes_));
  RecoverSummary r = RecoverTrial(trial_, {});
  EXPECT_TRUE(r.readable());
  EXPECT_EQ(r.frames.at("az"), frames_ - 1);
  EXPECT_EQ(io::CsvTable::Read(trial_ + "/az/frames.csv").rows(), static_cast<std::size_t>(frames_ - 1));
  // A kill -9 between a frame and its row: a frame without a time.
  std::string last_frame;
  {
    std::ifstream in(seg1_, std::ios::binary);
    in.seekg(-frame_bytes_, std::ios::end);
    last_frame.resize(static_cast<std::size_t>(frame_bytes_));
    in.read(last_frame.data(), frame_bytes_);
  }
  Append(seg1_, last_frame);
  r = RecoverTrial(trial_, {});
  EXPECT_TRUE(r.readable());
  EXPECT_EQ(r.frames.at("az"), frames_ - 1);
  EXPECT_EQ(CheckCamera(trial_, "az"), frames_ - 1);
}

TEST_F(Recover, CorruptionInsideIsReportedNotHidden) {
  // A frame marker destroyed inside the first segment.
  {
    std::fstream f(trial_ + "/az/seg_000.y4m", std::ios::in | std::ios::out | std::ios::binary);
    std::string header;
    std::getline(f, header);
    f.seekp(static_cast<std::streamoff>(header.size() + 1 + 3 * frame_bytes_));
    f.write("XXXXXX", 6);
  }
  const std::string frames_before = io::ReadFile(trial_ + "/az/frames.csv");
  RecoverSummary r = RecoverTrial(trial_, {});
  EXPECT_FALSE(r.readable());
  ASSERT_FALSE(r.problems.empty());
  EXPECT_NE(r.problems.front().find("seg_000.y4m: frame 3"), std::string::npos) << r.problems.front();
  EXPECT_EQ(io::ReadFile(trial_ + "/az/frames.csv"), frames_before);  // nothing "repaired" away
  const io::Json m = io::LoadJson(trial_ + "/trial.json");
  EXPECT_FALSE(m["capture"]["recover"]["readable"].get<bool>());
  EXPECT_EQ(m["cameras"]["az"]["video"].size(), 2u);  // the list is left as it was
}

TEST_F(Recover, ABadRowInsideALogIsReported) {
  std::string text = io::ReadFile(trial_ + "/az/frames.csv");
  const auto third = text.find('\n', text.find('\n', text.find("frame,t_s")) + 1);
  text.insert(third + 1, "garbage-without-commas\n");
  io::WriteFileAtomic(trial_ + "/az/frames.csv", text);
  const RecoverSummary r = RecoverTrial(trial_, {});
  EXPECT_FALSE(r.readable());
  EXPECT_NE(r.problems.front().find("frames.csv:"), std::string::npos) << r.problems.front();
}

TEST(RecoverErrors, RefusesARecordingInProgress) {
  const rk::test::TempDir dir_tmp("capture_busy");
  const std::string dir = dir_tmp.path();
  const StationConfig cfg = StationConfigFromJson(SyntheticStation(), dir + "/station.json");
  CaptureOptions o;
  o.out_dir = dir + "/trial";
  o.duration_s = 1.5;
  std::thread t([&] { RunCapture(cfg, o); });
  for (int i = 0; i < 100 && !fs::exists(dir + "/trial/trial.json"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  try {
    RecoverTrial(dir + "/trial", {});
    ADD_FAILURE() << "recover ran on a recording in progress";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    EXPECT_NE(std::string(e.what()).find("still recording"), std::string::npos);
  }
  t.join();
  EXPECT_TRUE(RecoverTrial(dir + "/trial", {}).readable());  // the lock went with the recording
  fs::remove_all(dir);
}

TEST(RecoverErrors, NotATrial) {
  const rk::test::TempDir dir_tmp("capture_nottrial");
  const std::string dir = dir_tmp.path();
  try {
    RecoverTrial(dir, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kIo);
  }
  std::ofstream(dir + "/trial.json") << "{\"x\": 1}";
  try {
    RecoverTrial(dir, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rk::capture

// Recording a station into a trial directory, the station configuration, and recovery after the
// damage a crash or a power cut leaves. Truth: the synthetic camera writes each frame's sequence
// number into its first pixels, so every frame read back can be matched to its frames.csv row.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "capture/camera_source.h"
#include "capture/recorder.h"
#include "capture/recover.h"
#include "capture/station_config.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "test_temp_dir.h"
#include "trial/layout.h"
#include "video/frame_sink.h"
#include "video/frame_source.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

std::string WriteConfig(const std::string& dir, const io::Json& j) {
  const std::string path = dir + "/station.json";
  io::WriteJson(path, j);
  return path;
}

io::Json SyntheticStation(const std::string& format = "y4m") {
  return {{"cameras", {{{"name", "az"}, {"source", "synthetic:64x48"}, {"fps", 20}, {"format", format}}}},
          {"segment_s", 0.5},
          {"station", {{"lat_deg", 45.0}, {"lon_deg", 7.0}, {"h_m", 300.0}}}};
}

// Reads every frame of a camera as the manifest lists it and checks it against frames.csv.
// Returns the number of frames.
std::int64_t CheckCamera(const std::string& trial, const std::string& cam) {
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

CaptureSummary Record(const std::string& dir, const io::Json& station, double duration_s,
                      std::function<std::int64_t()> probe = nullptr) {
  const StationConfig cfg = StationConfigFromJson(station, dir + "/station.json");
  CaptureOptions o;
  o.out_dir = dir + "/trial";
  o.duration_s = duration_s;
  o.free_space_probe = std::move(probe);
  return RunCapture(cfg, o);
}

TEST(Recorder, SyntheticCameraTrialReadsBack) {
  const std::string dir = TempDir("basic");
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
  const std::string dir = TempDir("pgm");
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
  const std::string dir = TempDir("cvfile");
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
  const std::string dir = TempDir("full");
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
  const std::string dir = TempDir("refuse");
  fs::create_directories(dir + "/trial");
  std::ofstream(dir + "/trial/keep.txt") << "precious";
  EXPECT_THROW(Record(dir, SyntheticStation(), 0.2), Error);
  EXPECT_EQ(io::ReadFile(dir + "/trial/keep.txt"), "precious");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir + "/trial"), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(Recorder, ADeviceThatIsNotThereLeavesNothingBehind) {
  const std::string dir = TempDir("nodev");
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

// --- recovery ---

class Recover : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = TempDir("recover");
    const CaptureSummary s = Record(dir_, SyntheticStation(), 0.8);
    frames_ = s.cameras[0].written;
    trial_ = dir_ + "/trial";
    seg1_ = trial_ + "/az/seg_001.y4m";
    frame_bytes_ = 6 + 64 * 48;
  }
  void TearDown() override { fs::remove_all(dir_); }
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
  const std::string dir = TempDir("busy");
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
  const std::string dir = TempDir("nottrial");
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

// --- station configuration ---

TEST(StationConfig, PathsAreRelativeToTheFileAndKeysAreChecked) {
  const std::string dir = TempDir("cfg");
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

// Issue 16 item 1: --duration's bound and report key come from CaptureOptions::Table(); the folder rule
// stays hand-written after it.
TEST(CaptureOptions, TableCheckAndReportKey) {
  CaptureOptions o;
  o.out_dir = "trial";
  std::string why;
  EXPECT_TRUE(o.Check(&why)) << why;
  o.duration_s = -1.0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--duration must be >= 0 s");
  o.duration_s = 2.5;
  EXPECT_EQ(CaptureOptions::Table().ToJson(o).at("duration_s"), 2.5);
  o.out_dir = "-";
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--out must name a folder");
}

}  // namespace
}  // namespace rk::capture

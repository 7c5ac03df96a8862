// The Dimetix DLS rangefinder (capture/dimetix.h): reply parsing against hand-made replies of the manual's
// forms, and the driver against the pty emulator, in process. Truth: the emulator's log of every reply it
// sent (host_mono_s on the same CLOCK_MONOTONIC the driver stamps with). Every measurement the device sent
// must come out of the driver as a sample, in order, with the same value, stamped at arrival; faults must
// become gaps and counters, never wrong data.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "capture/dimetix.h"
#include "capture/emulator_dimetix.h"
#include "test_serial_device.h"
#include "rk_test/temp_dir.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

TEST(Dimetix, ParsesDistanceReplies) {
  DimetixReply r = ParseDimetixReply("g0g+00123456", 0);
  EXPECT_EQ(r.kind, DimetixReplyKind::kDistance);
  EXPECT_EQ(r.value, 123456);  // 12.3456 m in 0.1 mm
  r = ParseDimetixReply("g0h+00000001", 0);
  EXPECT_EQ(r.kind, DimetixReplyKind::kDistance);
  EXPECT_EQ(r.command, "h");
  EXPECT_EQ(r.value, 1);
  r = ParseDimetixReply("g3g-00000100", 3);  // a negative user offset can make it negative
  EXPECT_EQ(r.kind, DimetixReplyKind::kDistance);
  EXPECT_EQ(r.value, -100);
  r = ParseDimetixReply("g0q+00012345+1", 0);  // buffered read-out with its new-measurement flag
  EXPECT_EQ(r.kind, DimetixReplyKind::kDistance);
  EXPECT_EQ(r.value, 12345);
}

TEST(Dimetix, ParsesErrorsAcksAndTemperature) {
  DimetixReply r = ParseDimetixReply("g0@E255", 0);
  EXPECT_EQ(r.kind, DimetixReplyKind::kError);
  EXPECT_EQ(r.value, 255);
  r = ParseDimetixReply("g0@E212+0", 0);
  EXPECT_EQ(r.kind, DimetixReplyKind::kError);
  EXPECT_EQ(r.value, 212);
  EXPECT_EQ(ParseDimetixReply("g0?", 0).kind, DimetixReplyKind::kAck);
  r = ParseDimetixReply("g0t+00000245", 0);
  EXPECT_EQ(r.kind, DimetixReplyKind::kTemperature);
  EXPECT_EQ(r.value, 245);  // 24.5 °C
}

TEST(Dimetix, RejectsGarbageAndOtherDevices) {
  for (const char* bad : {"", "g", "g0", "g1g+00000001", "x0g+00000001", "g0g+12a4", "g0g+", "g0@E", "g0@Exyz",
                          "g0zz+00000001", "g0g00000001", "g0g+00000001\x07", "\xff\xfe"}) {
    EXPECT_EQ(ParseDimetixReply(bad, 0).kind, DimetixReplyKind::kInvalid) << bad;
  }
  EXPECT_EQ(DimetixCommand(0, "h"), "s0h\r\n");
  EXPECT_EQ(DimetixCommand(7, "h+200"), "s7h+200\r\n");
}

// A reply is stamped after the driver's read returns; the emulator logs just before writing. On a
// loaded 2-core machine a thread can wait tens of ms for the CPU; 100 ms bounds that with margin
// and is still far below the 200 ms between two 5 Hz range samples.
constexpr double kArrivalTolS = 0.1;

// The measurement replies the emulator sent (distances and errors), in order.
std::vector<TruthLine> SentMeasurements(const std::vector<TruthLine>& truth, double before_mono_s) {
  std::vector<TruthLine> out;
  for (const auto& t : truth) {
    if (t.event != "sent" || t.mono_s >= before_mono_s) continue;
    const DimetixReply r = ParseDimetixReply(t.data, 0);
    if (r.kind == DimetixReplyKind::kDistance || r.kind == DimetixReplyKind::kError) out.push_back(t);
  }
  return out;
}

void ExpectSamplesMatchTruth(const std::vector<RangeSample>& samples, const std::vector<TruthLine>& sent) {
  ASSERT_GE(samples.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const DimetixReply r = ParseDimetixReply(sent[i].data, 0);
    const RangeSample& s = samples[i];
    if (r.kind == DimetixReplyKind::kDistance) {
      ASSERT_TRUE(s.distance_01mm) << "sample " << i << " truth " << sent[i].data;
      EXPECT_EQ(*s.distance_01mm, r.value) << "sample " << i;
      EXPECT_EQ(s.status, 0);
    } else {
      EXPECT_FALSE(s.distance_01mm) << "sample " << i;
      EXPECT_EQ(s.status, r.value) << "sample " << i;
    }
    const double arrival = static_cast<double>(s.stamp.mono_ns) * 1e-9;
    EXPECT_GE(arrival, sent[i].mono_s) << "sample " << i << " stamped before it was sent";
    EXPECT_LE(arrival - sent[i].mono_s, kArrivalTolS) << "sample " << i;
    if (i > 0) {
      EXPECT_GT(s.stamp.mono_ns, samples[i - 1].stamp.mono_ns);
    }
  }
}

TEST(DimetixDriver, TrackingWithErrorSilenceAndGarbage) {
  const rk::test::TempDir dir_tmp("capture_dls");
  const std::string dir = dir_tmp.path();
  DimetixEmulatorOptions e;
  e.common.link = dir + "/dls";
  e.common.truth_path = dir + "/truth.csv";
  e.rate_hz = 20;
  std::string why;
  for (const char* f : {"error:0.4:0.25:255", "silence:0.8:0.5", "garbage:1.6:0.1"}) {
    Fault fault;
    ASSERT_TRUE(ParseFault(f, &fault, &why));
    e.common.faults.push_back(fault);
  }
  Running<DimetixEmulator> emu(e);
  DimetixOptions o;
  o.serial = Serial(emu.port());
  o.rate_hz = 20;
  o.timeout_s = 0.25;
  o.reconnect_s = 0.2;
  Recorded rec;
  std::vector<RangeSample> samples;
  DimetixDriver d(o, rec.Reporter(), [&](const RangeSample& s) { samples.push_back(s); });
  ASSERT_TRUE(d.Connect(&why)) << why;
  std::atomic<bool> stop{false};
  std::thread t([&] { d.Run(stop); });
  std::this_thread::sleep_for(std::chrono::milliseconds(2100));
  const double stop_mono = static_cast<double>(MonoNowNs()) * 1e-9;
  stop = true;
  t.join();
  emu.Stop();
  const auto truth = ReadTruth(e.common.truth_path);
  const auto sent = SentMeasurements(truth, stop_mono - 0.05);
  ExpectSamplesMatchTruth(samples, sent);
  const DimetixStats st = d.stats();
  EXPECT_GE(st.error_codes.count(255) ? st.error_codes.at(255) : 0, 3);  // 0.25 s at 20 Hz: 5 replies (jitter: >= 3)
  EXPECT_GE(st.garbage_lines, 1);
  EXPECT_EQ(st.timeouts, 1);  // the 0.5 s silence, and only it
  EXPECT_EQ(rec.gaps_begun, 1);
  EXPECT_EQ(rec.gaps_ended, 1);
  ASSERT_TRUE(st.temperature_start_c);
  EXPECT_DOUBLE_EQ(*st.temperature_start_c, 24.5);
  ASSERT_TRUE(st.temperature_end_c);
  // The clean stop: stop/clear, temperature, laser off, all received by the device.
  std::vector<std::string> received;
  for (const auto& l : truth) {
    if (l.event == "received") received.push_back(l.data);
  }
  ASSERT_GE(received.size(), 3u);
  EXPECT_EQ(received.back(), "s0p");
  EXPECT_EQ(received[received.size() - 2], "s0t");
  fs::remove_all(dir);
}

TEST(DimetixDriver, SingleModeAtItsRate) {
  const rk::test::TempDir dir_tmp("capture_dls1");
  const std::string dir = dir_tmp.path();
  DimetixEmulatorOptions e;
  e.common.link = dir + "/dls";
  e.common.truth_path = dir + "/truth.csv";
  e.measure_s = 0.02;
  e.device_id = 3;
  Running<DimetixEmulator> emu(e);
  DimetixOptions o;
  o.serial = Serial(emu.port());
  o.mode = DimetixMode::kSingle;
  o.device_id = 3;
  o.rate_hz = 10;
  std::vector<RangeSample> samples;
  DimetixDriver d(o, DeviceReporter{}, [&](const RangeSample& s) { samples.push_back(s); });
  std::string why;
  ASSERT_TRUE(d.Connect(&why)) << why;
  std::atomic<bool> stop{false};
  std::thread t([&] { d.Run(stop); });
  std::this_thread::sleep_for(std::chrono::milliseconds(650));
  stop = true;
  t.join();
  // 0.65 s at 10 Hz: 7 requests; allow one less for scheduling on a busy machine.
  EXPECT_GE(samples.size(), 6u);
  EXPECT_LE(samples.size(), 7u);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const double dt = static_cast<double>(samples[i].stamp.mono_ns - samples[i - 1].stamp.mono_ns) * 1e-9;
    EXPECT_NEAR(dt, 0.1, 0.05) << i;  // requests on a fixed 10 Hz schedule
  }
  fs::remove_all(dir);
}

TEST(DimetixDriver, ReconnectsAfterAHangUp) {
  const rk::test::TempDir dir_tmp("capture_dls2");
  const std::string dir = dir_tmp.path();
  DimetixEmulatorOptions e;
  e.common.link = dir + "/dls";
  e.common.truth_path = dir + "/truth.csv";
  e.rate_hz = 20;
  Fault f;
  std::string why;
  ASSERT_TRUE(ParseFault("disconnect:0.4:0.3", &f, &why));
  e.common.faults.push_back(f);
  Running<DimetixEmulator> emu(e);
  DimetixOptions o;
  o.serial = Serial(emu.port());
  o.rate_hz = 20;
  o.timeout_s = 0.5;
  o.reconnect_s = 0.1;
  Recorded rec;
  std::vector<RangeSample> samples;
  DimetixDriver d(o, rec.Reporter(), [&](const RangeSample& s) { samples.push_back(s); });
  ASSERT_TRUE(d.Connect(&why)) << why;
  std::atomic<bool> stop{false};
  std::thread t([&] { d.Run(stop); });
  std::this_thread::sleep_for(std::chrono::milliseconds(1300));
  const double stop_mono = static_cast<double>(MonoNowNs()) * 1e-9;
  stop = true;
  t.join();
  emu.Stop();
  const DimetixStats st = d.stats();
  EXPECT_EQ(st.disconnects, 1);
  EXPECT_EQ(st.reconnects, 1);
  EXPECT_EQ(rec.gaps_begun, 1);
  EXPECT_EQ(rec.gaps_ended, 1);
  // Every measurement sent over both connections arrived.
  ExpectSamplesMatchTruth(samples, SentMeasurements(ReadTruth(e.common.truth_path), stop_mono - 0.05));
  fs::remove_all(dir);
}

TEST(DimetixDriver, ConnectFailsCleanlyWithoutADevice) {
  DimetixOptions o;
  o.serial = Serial("/nonexistent/ttyUSB9");
  DimetixDriver d(o, DeviceReporter{}, nullptr);
  std::string why;
  EXPECT_FALSE(d.Connect(&why));
  EXPECT_NE(why.find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace rk::capture

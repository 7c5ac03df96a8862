// The FLIR PTU turret (capture/ptu.h): reply parsing and the counts-to-angles mapping against hand-made
// replies of the manual's forms, and the driver against the pty emulator, in process (truth: the emulator's
// log of every reply it sent). Faults must become gaps and counters, never mispaired replies.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "capture/emulator_ptu.h"
#include "capture/ptu.h"
#include "geo/angles.h"
#include "test_serial_device.h"
#include "rk_test/temp_dir.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

// Angles from counts: a product of a count (exact integer) and a resolution; 1e-9 deg is far below
// the 0.003 deg step and only covers floating-point rounding.
constexpr double kAngleTolDeg = 1e-9;

TEST(Ptu, ParsesTerseVerboseAndEchoedReplies) {
  PtuReply r = ParsePtuReply("* 1234");
  EXPECT_EQ(r.kind, PtuReplyKind::kOk);
  ASSERT_TRUE(r.value);
  EXPECT_EQ(*r.value, 1234);
  r = ParsePtuReply("* Current Pan position is -500");
  ASSERT_TRUE(r.value);
  EXPECT_EQ(*r.value, -500);
  r = ParsePtuReply("PP * Current Pan position is 1000");  // echo on
  ASSERT_TRUE(r.value);
  EXPECT_EQ(*r.value, 1000);
  r = ParsePtuReply("PR * 92.5714 seconds arc per position");
  ASSERT_TRUE(r.value);
  EXPECT_DOUBLE_EQ(*r.value, 92.5714);
  r = ParsePtuReply("*");
  EXPECT_EQ(r.kind, PtuReplyKind::kOk);
  EXPECT_FALSE(r.value);
  r = ParsePtuReply("* ASCII terse mode");
  EXPECT_EQ(r.kind, PtuReplyKind::kOk);
  EXPECT_FALSE(r.value);
}

TEST(Ptu, ParsesErrorsLimitsAndRejectsGarbage) {
  PtuReply r = ParsePtuReply("! Maximum allowable Pan position exceeded");
  EXPECT_EQ(r.kind, PtuReplyKind::kError);
  EXPECT_EQ(r.text, "Maximum allowable Pan position exceeded");
  EXPECT_EQ(ParsePtuReply("!P").kind, PtuReplyKind::kLimit);
  EXPECT_EQ(ParsePtuReply("!T").kind, PtuReplyKind::kLimit);
  for (const char* bad : {"", "1234", "#$% * 12", "garbage", "\x01* 12"}) {
    EXPECT_EQ(ParsePtuReply(bad).kind, PtuReplyKind::kInvalid) << bad;
  }
}

TEST(Ptu, CountsToAnglesWrapAcrossNorth) {
  const double res = 14.4;  // 0.004 deg per position: 20 deg = 5000 positions exactly
  PtuAngleMap m;
  m.pan_zero_deg = 350.0;
  // +20 deg of pan from 350 deg crosses north: 10 deg.
  const std::int64_t p20 = std::llround(20.0 * 3600.0 / res);
  EXPECT_NEAR(m.AzimuthDeg(p20, res), 10.0, kAngleTolDeg);
  EXPECT_NEAR(m.AzimuthDeg(-p20, res), 330.0, kAngleTolDeg);
  EXPECT_NEAR(m.AzimuthDeg(0, res), 350.0, kAngleTolDeg);
  // A counter-clockwise unit (pan_sign -1).
  m.pan_sign = -1.0;
  EXPECT_NEAR(m.AzimuthDeg(p20, res), 330.0, kAngleTolDeg);
  // Result always in [0, 360).
  for (std::int64_t p = -60000; p <= 60000; p += 777) {
    const double az = m.AzimuthDeg(p, res);
    EXPECT_GE(az, 0.0);
    EXPECT_LT(az, 360.0);
  }
  // Inverse: the position for an azimuth, through north both ways.
  m.pan_sign = 1.0;
  EXPECT_EQ(m.PanPosition(10.0, res), p20);
  EXPECT_EQ(m.PanPosition(330.0, res), -p20);
  m.pan_sign = -1.0;
  EXPECT_EQ(m.PanPosition(330.0, res), p20);
  // Tilt: zero offset and sign.
  PtuAngleMap t;
  t.tilt_zero_deg = 2.0;
  t.tilt_sign = -1.0;
  EXPECT_NEAR(t.ElevationDeg(1000, res), 2.0 - 4.0, kAngleTolDeg);
  EXPECT_EQ(t.TiltPosition(-2.0, res), 1000);
}

// Position replies of the emulator, paired as the driver pairs them (PP answer, then TP answer).
// Replies later than max_latency_s after their query are ones the driver has timed out on, so a
// pair with such a reply is not a sample.
std::vector<std::pair<std::int64_t, std::int64_t>> TruthPairs(const std::vector<TruthLine>& truth, double before,
                                                              double max_latency_s = 1e18) {
  std::vector<std::pair<std::int64_t, std::int64_t>> out;
  bool have_pan = false;
  std::int64_t pan = 0;
  // In-order matching: the n-th reply answers the n-th command.
  std::vector<std::string> commands;
  std::vector<double> asked_at;
  std::vector<TruthLine> replies;
  for (const auto& l : truth) {
    if (l.event == "received") {
      commands.push_back(l.data);
      asked_at.push_back(l.mono_s);
    }
    if (l.event == "sent" || l.event == "dropped" || l.event == "garbage" || l.event == "lost") replies.push_back(l);
  }
  for (std::size_t i = 0; i < replies.size() && i < commands.size(); ++i) {
    if (replies[i].mono_s >= before) break;
    const PtuReply r = ParsePtuReply(replies[i].data);
    const bool good = replies[i].event == "sent" && r.kind == PtuReplyKind::kOk && r.value &&
                      replies[i].mono_s - asked_at[i] <= max_latency_s;
    if (commands[i] == "PP") {
      have_pan = good;
      pan = good ? static_cast<std::int64_t>(*r.value) : 0;
    } else if (commands[i] == "TP") {
      if (have_pan && good) out.push_back({pan, static_cast<std::int64_t>(*r.value)});
      have_pan = false;
    } else {
      have_pan = false;
    }
  }
  return out;
}

TEST(PtuDriver, PollsBothAxesAndReadsTheResolution) {
  const rk::test::TempDir dir_tmp("capture_ptu");
  const std::string dir = dir_tmp.path();
  PtuEmulatorOptions e;
  e.common.link = dir + "/ptu";
  e.common.truth_path = dir + "/truth.csv";
  e.pan_res_arcsec = 46.2857;  // a PTU-D46 figure: the driver must read it, not assume 10.8
  e.tilt_res_arcsec = 11.5714;
  Running<PtuEmulator> emu(e);
  PtuOptions o;
  o.serial = Serial(emu.port());
  o.rate_hz = 50;
  o.map.pan_zero_deg = 355.0;
  std::vector<TurretSample> samples;
  std::atomic<std::size_t> count{0};
  PtuDriver d(o, DeviceReporter{}, [&](const TurretSample& s) {
    samples.push_back(s);
    ++count;
  });
  std::string why;
  ASSERT_TRUE(d.Connect(&why)) << why;
  EXPECT_DOUBLE_EQ(d.stats().pan_res_arcsec, 46.2857);
  EXPECT_DOUBLE_EQ(d.stats().tilt_res_arcsec, 11.5714);
  // Runs until 24 samples (0.48 s at 50 Hz) or a generous limit: on a loaded machine the poller may get
  // the CPU late, which is no fault of the driver; polling faster than the rate would be.
  std::atomic<bool> stop{false};
  const auto start = std::chrono::steady_clock::now();
  std::thread t([&] { d.Run(stop); });
  while (count < 24 && std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  stop = true;
  t.join();
  const double ran_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  emu.Stop();
  EXPECT_GE(samples.size(), 24u);
  EXPECT_LE(static_cast<double>(samples.size()), 50.0 * ran_s + 2.0);  // never faster than --rate
  const auto pairs = TruthPairs(ReadTruth(e.common.truth_path), 1e18);
  ASSERT_EQ(pairs.size(), samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    EXPECT_EQ(samples[i].pan_pos, pairs[i].first) << i;
    EXPECT_EQ(samples[i].tilt_pos, pairs[i].second) << i;
    EXPECT_GE(samples[i].pair_dt_s, 0.0);
  }
  // The emulator's pan sine is centred on 0 with 30 deg amplitude: azimuths straddle 355 ± small.
  const double az = o.map.AzimuthDeg(samples.back().pan_pos, samples.back().pan_res_arcsec);
  EXPECT_NEAR(geo::WrapDeg180(az - 355.0), static_cast<double>(samples.back().pan_pos) * 46.2857 / 3600.0, 1e-9);
  fs::remove_all(dir);
}

TEST(PtuDriver, FaultsNeverMispairReplies) {
  const rk::test::TempDir dir_tmp("capture_ptu2");
  const std::string dir = dir_tmp.path();
  PtuEmulatorOptions e;
  e.common.link = dir + "/ptu";
  e.common.truth_path = dir + "/truth.csv";
  std::string why;
  // Late replies (0.25 s, longer than the 0.1 s timeout) are the dangerous fault: without the
  // resynchronisation they would be taken for answers to later queries.
  for (const char* f :
       {"error:0.2:0.15", "silence:0.5:0.25", "slow:1.1:0.25:0.25", "garbage:1.6:0.1", "disconnect:1.9:0.2"}) {
    Fault fault;
    ASSERT_TRUE(ParseFault(f, &fault, &why));
    e.common.faults.push_back(fault);
  }
  Running<PtuEmulator> emu(e);
  PtuOptions o;
  o.serial = Serial(emu.port());
  o.rate_hz = 50;
  o.timeout_s = 0.1;
  o.reconnect_s = 0.1;
  Recorded rec;
  std::vector<TurretSample> samples;
  PtuDriver d(o, rec.Reporter(), [&](const TurretSample& s) { samples.push_back(s); });
  ASSERT_TRUE(d.Connect(&why)) << why;
  std::atomic<bool> stop{false};
  std::thread t([&] { d.Run(stop); });
  std::this_thread::sleep_for(std::chrono::milliseconds(2600));
  stop = true;
  t.join();
  emu.Stop();
  const PtuStats st = d.stats();
  EXPECT_GE(st.error_replies, 1);
  EXPECT_GE(st.timeouts, 1);  // silence and slow (one gap if the machine is too slow to close the first in between)
  EXPECT_EQ(st.disconnects, 1);
  EXPECT_EQ(st.reconnects, 1);  // and the resolution read again from the re-created unit
  EXPECT_GE(rec.gaps_begun, 3);
  // The late replies of the slow fault were seen and thrown away, not used.
  bool discarded = false;
  for (const auto& e : rec.events) discarded = discarded || e.find("late line(s) discarded") != std::string::npos;
  EXPECT_TRUE(discarded);
  EXPECT_EQ(rec.gaps_begun, rec.gaps_ended);
  // Every sample is a (PP answer, TP answer) pair the unit really gave, in time, for those two queries
  // (a TP answer the slow fault delays past the timeout ends that poll without a sample).
  const auto pairs = TruthPairs(ReadTruth(e.common.truth_path), 1e18, o.timeout_s);
  ASSERT_EQ(pairs.size(), samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    EXPECT_EQ(samples[i].pan_pos, pairs[i].first) << i;
    EXPECT_EQ(samples[i].tilt_pos, pairs[i].second) << i;
  }
  EXPECT_GE(samples.size(), 40u);  // 2.6 s at 50 Hz minus ~1.3 s of faults and resynchronisation
  EXPECT_GT(samples.back().stamp.mono_ns, samples.front().stamp.mono_ns + 2 * kNsPerS);  // polls after the reconnect
  fs::remove_all(dir);
}

TEST(PtuDriver, PointsTheTurretAtStart) {
  const rk::test::TempDir dir_tmp("capture_ptu3");
  const std::string dir = dir_tmp.path();
  PtuEmulatorOptions e;
  e.common.link = dir + "/ptu";
  e.slew_deg_s = 1000;  // arrives within one poll
  Running<PtuEmulator> emu(e);
  PtuOptions o;
  o.serial = Serial(emu.port());
  o.map.pan_zero_deg = 300.0;
  o.point_az_deg = 10.0;  // 70 deg of pan from 300, through north
  o.point_el_deg = 12.0;
  std::vector<TurretSample> samples;
  PtuDriver d(o, DeviceReporter{}, [&](const TurretSample& s) { samples.push_back(s); });
  std::string why;
  ASSERT_TRUE(d.Connect(&why)) << why;
  std::atomic<bool> stop{false};
  std::thread t([&] { d.Run(stop); });
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  stop = true;
  t.join();
  ASSERT_FALSE(samples.empty());
  const TurretSample& s = samples.back();
  // Within half a position (0.0015 deg): the quantisation of the commanded angle.
  EXPECT_NEAR(o.map.AzimuthDeg(s.pan_pos, s.pan_res_arcsec), 10.0, 0.0015 + 1e-9);
  EXPECT_NEAR(o.map.ElevationDeg(s.tilt_pos, s.tilt_res_arcsec), 12.0, 0.0015 + 1e-9);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rk::capture

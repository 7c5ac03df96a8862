// Serial drivers against the pty emulators, in process. Truth: the emulator's log of every reply it
// sent (host_mono_s on the same CLOCK_MONOTONIC the drivers stamp with). Every measurement the
// device sent must come out of the driver as a sample, in order, with the same value, stamped at
// arrival; faults must become gaps and counters, never wrong data.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "capture/dimetix.h"
#include "capture/emulator_dimetix.h"
#include "capture/emulator_ptu.h"
#include "capture/ptu.h"
#include "geo/angles.h"
#include "test_temp_dir.h"

namespace rk::capture {
namespace {
namespace fs = std::filesystem;

// A reply is stamped after the driver's read returns; the emulator logs just before writing. On a
// loaded 2-core machine a thread can wait tens of ms for the CPU; 100 ms bounds that with margin
// and is still far below the 200 ms between two 5 Hz range samples.
constexpr double kArrivalTolS = 0.1;

struct TruthLine {
  double mono_s = 0;
  std::string event, data;
};

std::vector<TruthLine> ReadTruth(const std::string& path) {
  std::vector<TruthLine> out;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto a = line.find(','), b = line.find(',', a + 1);
    out.push_back({std::stod(line.substr(0, a)), line.substr(a + 1, b - a - 1), line.substr(b + 1)});
  }
  return out;
}

// Runs an emulator on its own thread for the lifetime of the object.
template <class Emu>
class Running {
 public:
  template <class Opt>
  explicit Running(const Opt& o) : emu_(o) {
    std::string why;
    ok_ = emu_.Start(&why);
    EXPECT_TRUE(ok_) << why;
    if (ok_) thread_ = std::thread([this] { emu_.Run(stop_, 0.0); });
  }
  ~Running() { Stop(); }
  void Stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  std::string port() const { return emu_.port(); }
  EmulatorStats stats() const { return emu_.stats(); }

 private:
  Emu emu_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  bool ok_ = false;
};

struct Recorded {
  std::mutex mutex;
  std::vector<std::string> events;
  int gaps_begun = 0, gaps_ended = 0;
  DeviceReporter Reporter() {
    DeviceReporter r;
    r.event = [this](EventLevel, const std::string& m) {
      std::lock_guard<std::mutex> lock(mutex);
      events.push_back(m);
    };
    r.gap_begin = [this](const Stamp&, const std::string&) {
      std::lock_guard<std::mutex> lock(mutex);
      ++gaps_begun;
    };
    r.gap_end = [this](const Stamp&) {
      std::lock_guard<std::mutex> lock(mutex);
      ++gaps_ended;
    };
    return r;
  }
};

SerialOptions Serial(const std::string& port) {
  SerialOptions s;
  s.port = port;
  s.baud = 115200;
  return s;
}

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
  const std::string dir = TempDir("dls");
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
  const std::string dir = TempDir("dls1");
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
  const std::string dir = TempDir("dls2");
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
  const std::string dir = TempDir("ptu");
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
  const std::string dir = TempDir("ptu2");
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
  const std::string dir = TempDir("ptu3");
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

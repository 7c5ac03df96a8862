// Protocol parsing, angle mapping and small helpers of rk-capture, against hand-made replies of the
// Dimetix DLS and FLIR PTU manuals' forms.
#include <gtest/gtest.h>

#include <cmath>

#include "capture/clock.h"
#include "capture/dimetix.h"
#include "capture/emulator.h"
#include "capture/ptu.h"
#include "capture/segment_writer.h"
#include "capture/serial_port.h"

namespace rk::capture {
namespace {

// Angles from counts: a product of a count (exact integer) and a resolution; 1e-9 deg is far below
// the 0.003 deg step and only covers floating-point rounding.
constexpr double kAngleTolDeg = 1e-9;

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

TEST(Serial, OptionsAreChecked) {
  SerialOptions o;
  o.port = "/dev/ttyUSB0";
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  EXPECT_EQ(o.BitsPerChar(), 10);
  o.parity = "even";
  EXPECT_EQ(o.BitsPerChar(), 11);
  o.baud = 12345;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_NE(why.find("baud"), std::string::npos);
  o.baud = 9600;
  o.parity = "mark";
  EXPECT_FALSE(o.Check(&why));
  o.parity = "odd";
  o.data_bits = 9;
  EXPECT_FALSE(o.Check(&why));
  o.data_bits = 7;
  o.stop_bits = 3;
  EXPECT_FALSE(o.Check(&why));
}

TEST(Serial, LineSplitterHandlesCrLfAndOverlongRuns) {
  LineSplitter s(16);
  std::vector<std::string> lines;
  const std::string in = "g0g+1\r\ng0g+2\rg0g+3\n\n";
  s.Feed(in.data(), 4, &lines);  // split across feeds
  s.Feed(in.data() + 4, in.size() - 4, &lines);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "g0g+1");
  EXPECT_EQ(lines[2], "g0g+3");
  lines.clear();
  const std::string junk(40, 'x');
  s.Feed(junk.data(), junk.size(), &lines);
  s.Feed("\r\nok\r\n", 6, &lines);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "ok");
  EXPECT_EQ(s.overlong(), 1u);
  EXPECT_EQ(EscapeForLog(std::string("a\x01\xff", 3)), "a\\x01\\xff");
}

TEST(Emulator, FaultSpecs) {
  Fault f;
  std::string why;
  ASSERT_TRUE(ParseFault("error:1.5:2", &f, &why)) << why;
  EXPECT_EQ(f.kind, FaultKind::kError);
  EXPECT_EQ(f.code, 255);
  EXPECT_TRUE(f.ActiveAt(1.5));
  EXPECT_TRUE(f.ActiveAt(3.4));
  EXPECT_FALSE(f.ActiveAt(3.5));
  ASSERT_TRUE(ParseFault("error:0:1:256", &f, &why));
  EXPECT_EQ(f.code, 256);
  ASSERT_TRUE(ParseFault("slow:2:1:0.8", &f, &why));
  EXPECT_DOUBLE_EQ(f.delay_s, 0.8);
  ASSERT_TRUE(ParseFault("disconnect:3:0.5", &f, &why));
  EXPECT_EQ(f.kind, FaultKind::kDisconnect);
  for (const char* bad : {"error", "error:1", "boom:1:2", "error:x:2", "error:1:0", "silence:1:2:3", "error:1:2:abc",
                          "slow:1:2:-1", "error:-1:2"}) {
    EXPECT_FALSE(ParseFault(bad, &f, &why)) << bad;
  }
}

TEST(Video, Y4mHeaderRoundTrip) {
  FrameFormat f{2448, 2048, 8, 20.0};
  EXPECT_EQ(Y4mHeader(f), "YUV4MPEG2 W2448 H2048 F20:1 Ip A1:1 Cmono\n");
  f.fps = 29.97;
  f.bit_depth = 16;
  EXPECT_EQ(Y4mHeader(f), "YUV4MPEG2 W2448 H2048 F2997:100 Ip A1:1 Cmono16\n");
  FrameFormat g;
  const std::string h = Y4mHeader(f);
  ASSERT_TRUE(ParseY4mHeader(h.substr(0, h.size() - 1), &g));
  EXPECT_EQ(g.width, 2448);
  EXPECT_EQ(g.height, 2048);
  EXPECT_EQ(g.bit_depth, 16);
  EXPECT_NEAR(g.fps, 29.97, 1e-12);
  EXPECT_FALSE(ParseY4mHeader("YUV4MPEG2 W10 H10 F20:1 C420jpeg", &g));  // colour: not ours
  EXPECT_FALSE(ParseY4mHeader("PNG", &g));
}

TEST(Clock, EpochIsTheWholeSecondBeforeTheStart) {
  const Stamp now = Now();
  const TrialEpoch e = TrialEpoch::FromStamp(now);
  EXPECT_EQ(e.real_ns % kNsPerS, 0);
  EXPECT_LE(e.real_ns, now.real_ns);
  EXPECT_GT(e.real_ns, now.real_ns - kNsPerS);
  // The start is at t_s = (its fraction of a second) on both clocks.
  EXPECT_NEAR(e.TrialSeconds(now.mono_ns), static_cast<double>(now.real_ns - e.real_ns) * 1e-9, 1e-9);
  EXPECT_EQ(FormatUtc(0), "1970-01-01T00:00:00Z");
  EXPECT_EQ(FormatUtc(1795364623123456789LL, 3), "2026-11-22T16:23:43.123Z");
  // Monotonic and real-time readings of one stamp refer to one instant: consecutive stamps agree
  // on the elapsed time to well under a millisecond (no NTP step expected during a test).
  const Stamp a = Now(), b = Now();
  EXPECT_NEAR(static_cast<double>((b.mono_ns - a.mono_ns) - (b.real_ns - a.real_ns)), 0.0, 1e6);
}

}  // namespace
}  // namespace rk::capture

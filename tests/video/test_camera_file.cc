// Camera files read directly (video/camera_file.h, packed_pixels.h, recording_times.h): synthetic CINE and
// MRAW files with known samples and stamps (camera_files.h writes them from the format descriptions), every
// packing and orientation, the faults a broken file can have; and the two real files of
// ../shared/data/real (skipped when absent): chart1.cine against ffmpeg's decode, ball_12bit.mraw against an
// unpacking written here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>

#include "camera_files.h"
#include "io/error.h"
#include "rk_test/temp_dir.h"
#include "video/camera_file.h"
#include "video/frame_source.h"
#include "video/packed_pixels.h"
#include "video/recording_times.h"

namespace rk::video {
namespace {
namespace fs = std::filesystem;
using testing::CineSpec;
using testing::Samples;

// Tolerance of a time that went through a 32-bit binary fraction of a second (2^-32 s, and the two flag bits).
constexpr double kStampTolS = 2e-9;

void WriteBytes(const fs::path& p, const std::vector<std::uint8_t>& b) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}
void WriteText(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

std::vector<Samples> RandomFrames(int n, int w, int h, int bits, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Samples> out(static_cast<std::size_t>(n), Samples(static_cast<std::size_t>(w * h)));
  for (Samples& f : out) {
    for (auto& v : f) v = static_cast<std::uint16_t>(rng() & ((1u << bits) - 1u));
  }
  return out;
}

// The expected 16-bit sample of a `bits`-bit value: bit replication (as ffmpeg widens).
std::uint16_t Widened(std::uint32_t v, int bits) {
  if (bits == 16) return static_cast<std::uint16_t>(v);
  std::uint32_t out = 0;
  for (int filled = 0; filled < 16; filled += bits) out |= (v << (16 - bits)) >> filled;
  return static_cast<std::uint16_t>(out);
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(PackedPixels, EveryPackingRoundTripsThroughAnIndependentBitWriter) {
  struct Case { Packing packing; int bits; };
  for (const Case c : {Case{Packing::kP10BE, 10}, Case{Packing::kP12BE, 12}, Case{Packing::kU16LE, 12}, Case{Packing::kU16LE, 16}}) {
    const Samples v = RandomFrames(1, 64, 3, c.bits, 7 + static_cast<unsigned>(c.bits))[0];
    CineSpec s;
    s.width = 64;
    s.height = 3;
    s.bit_count = 16;
    s.compression = c.packing == Packing::kP10BE ? 256 : c.packing == Packing::kP12BE ? 1024 : 0;
    s.top_down_height = true;
    const std::vector<std::uint8_t> packed = testing::PackFrame(s, v);
    ASSERT_EQ(packed.size(), PackedBytes(c.packing, v.size()));
    std::vector<std::uint16_t> out(v.size());
    EXPECT_EQ(Unpack16(c.packing, c.bits, packed.data(), v.size(), out.data()), 0u);
    for (std::size_t i = 0; i < v.size(); ++i) ASSERT_EQ(out[i], Widened(v[i], c.bits)) << InfoOf(c.packing).name << " at " << i;
  }
  // Every length: the vector kernel's groups of 8 and the loop for the last ones.
  for (const Case c : {Case{Packing::kP10BE, 10}, Case{Packing::kP12BE, 12}}) {
    for (std::uint64_t n = 4; n <= 68; n += 4) {
      CineSpec s;
      s.width = static_cast<int>(n);
      s.height = 1;
      s.compression = c.packing == Packing::kP10BE ? 256 : 1024;
      const Samples v = RandomFrames(1, s.width, 1, c.bits, static_cast<unsigned>(n))[0];
      const std::vector<std::uint8_t> packed = testing::PackFrame(s, v);
      std::vector<std::uint16_t> out(n);
      Unpack16(c.packing, c.bits, packed.data(), n, out.data());
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(out[i], Widened(v[i], c.bits)) << c.bits << "-bit, " << n << " pixels, at " << i;
      // In place, the packed bytes at the end of the output buffer (as CameraFileReader reads a frame).
      std::vector<std::uint16_t> in_place(n);
      auto* bytes = reinterpret_cast<std::uint8_t*>(in_place.data());
      std::memcpy(bytes + 2 * n - packed.size(), packed.data(), packed.size());
      Unpack16(c.packing, c.bits, bytes + 2 * n - packed.size(), n, in_place.data());
      EXPECT_EQ(in_place, out) << c.bits << "-bit in place, " << n << " pixels";
    }
  }
  // A 12-bit sample above 4095 in a 16-bit container is clamped and counted.
  const std::uint16_t over[2] = {5000, 4095};
  std::uint16_t out[2];
  EXPECT_EQ(Unpack16(Packing::kU16LE, 12, reinterpret_cast<const std::uint8_t*>(over), 2, out), 1u);
  EXPECT_EQ(out[0], 65535);
  EXPECT_EQ(out[1], 65535);
}

struct CineCase {
  const char* name;
  int bit_count;
  std::uint32_t compression;
  bool top_down_height;
};

TEST(CineFile, EveryDepthPackingAndOrientationDecodesToTheWrittenSamples) {
  const rk::test::TempDir tmp("cine_depths");
  for (const CineCase c : {CineCase{"8-bit", 8, 0, false}, CineCase{"16-bit bottom-up", 16, 0, false},
                           CineCase{"16-bit top-down", 16, 0, true}, CineCase{"10-bit packed", 16, 256, false},
                           CineCase{"12-bit packed", 16, 1024, false}}) {
    CineSpec s;
    s.width = 24;
    s.height = 5;
    s.bit_count = c.bit_count;
    s.compression = c.compression;
    s.top_down_height = c.top_down_height;
    s.real_bpp = c.bit_count == 8 ? 8 : 12;
    const int bits = c.compression == 256 ? 10 : c.compression == 1024 ? 12 : c.bit_count == 8 ? 8 : 12;
    const std::vector<Samples> frames = RandomFrames(3, s.width, s.height, bits, 11);
    const fs::path p = tmp / (std::string("f") + std::to_string(c.compression) + "_" + std::to_string(c.bit_count) +
                              (c.top_down_height ? "td" : "") + ".cine");
    WriteBytes(p, testing::MakeCine(s, frames));
    FrameSource src({p.string()});
    cv::Mat m;
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(src.Read(&m)) << c.name;
      ASSERT_EQ(m.cols, s.width);
      ASSERT_EQ(m.rows, s.height);
      for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
          const std::uint16_t v = frames[static_cast<std::size_t>(k)][static_cast<std::size_t>(y * s.width + x)];
          const int got = bits == 8 ? m.at<std::uint8_t>(y, x) : m.at<std::uint16_t>(y, x);
          ASSERT_EQ(got, bits == 8 ? v : Widened(v, bits)) << c.name << " frame " << k << " (" << x << "," << y << ")";
        }
      }
    }
    EXPECT_FALSE(src.Read(&m));
  }
}

TEST(CineFile, BayerMosaicBecomesGreyByOpenCvsDemosaicing) {
  const rk::test::TempDir tmp("cine_bayer");
  CineSpec s;
  s.width = 16;
  s.height = 8;
  s.compression = 256;
  s.file_compression = 2;
  s.cfa = 3;  // GBRG
  const std::vector<Samples> frames = RandomFrames(1, s.width, s.height, 10, 3);
  WriteBytes(tmp / "b.cine", testing::MakeCine(s, frames));
  CameraFileReader r((tmp / "b.cine"));
  EXPECT_EQ(r.file().cfa, "GBRG");
  cv::Mat mosaic, grey, expected;
  r.ReadMosaic(0, &mosaic);
  r.Read(0, &grey);
  cv::cvtColor(mosaic, expected, cv::COLOR_BayerGR2GRAY);
  EXPECT_EQ(cv::norm(grey, expected, cv::NORM_INF), 0.0);
  // An unknown colour filter is refused with the byte offset of the setup's CFA field.
  s.cfa = 1;
  WriteBytes(tmp / "vri.cine", testing::MakeCine(s, frames));
  EXPECT_NE(ErrorOf([&] { CameraFileReader((tmp / "vri.cine")); }).find("byte 892"), std::string::npos);
}

TEST(CineFile, TimeBlockStampsCarryTheIrigFlagExposureAndTriggerDisagreement) {
  CineSpec s;
  const double t0 = 1700000000.0;
  for (int i = 0; i < 4; ++i) {
    const double frac = 0.25 + i * 0.001;  // 1 ms apart
    std::uint32_t fractions = static_cast<std::uint32_t>(std::llround(frac * 4294967296.0)) & ~3u;
    if (i == 2) fractions |= 1u;  // not IRIG-synchronised
    if (i == 3) fractions |= 2u;  // event input
    s.stamps.push_back((static_cast<std::uint64_t>(t0) << 32) | fractions);
    s.exposures.push_back(static_cast<std::uint32_t>(std::llround(250e-6 * 4294967296.0)));
  }
  s.first_image_no = -2;
  s.trigger_seconds = static_cast<std::uint32_t>(t0) + 86400;  // a day off: said
  const std::vector<Samples> frames = RandomFrames(4, s.width, s.height, 12, 5);
  const std::vector<std::uint8_t> bytes = testing::MakeCine(s, frames);
  const CameraFile cf = ParseCine(ByteView(bytes.data(), bytes.size(), "t.cine"));
  ASSERT_EQ(cf.times.frames.size(), 4u);
  EXPECT_TRUE(cf.times.absolute);
  for (int i = 0; i < 4; ++i) {
    const FrameStamp& f = cf.times.frames[static_cast<std::size_t>(i)];
    EXPECT_NEAR(f.t_s + (cf.times.origin_s - t0), 0.25 + i * 0.001, kStampTolS);  // origin_s - t0: exact
    EXPECT_NEAR(f.exposure_s, 250e-6, kStampTolS);
    EXPECT_EQ(f.source, i == 2 ? TimeSource::kCamera : TimeSource::kIrig);
    EXPECT_EQ(f.event, i == 3);
  }
  ASSERT_EQ(cf.times.warnings.size(), 1u);
  EXPECT_EQ(cf.times.warnings[0].code, "times_disagree");
  EXPECT_NE(cf.times.warnings[0].message.find("differ by 86399.748"), std::string::npos) << cf.times.warnings[0].message;
}

TEST(CineFile, WithoutATimeBlockTheTriggerTimePlusImageNumberIsNominal) {
  CineSpec s;
  s.rate_hz = 500;
  s.first_image_no = -10;
  s.trigger_seconds = 1700000000;
  const std::vector<std::uint8_t> bytes = testing::MakeCine(s, RandomFrames(3, s.width, s.height, 12, 6));
  const CameraFile cf = ParseCine(ByteView(bytes.data(), bytes.size(), "n.cine"));
  EXPECT_TRUE(cf.times.absolute);
  for (int i = 0; i < 3; ++i) {
    const FrameStamp& f = cf.times.frames[static_cast<std::size_t>(i)];
    EXPECT_EQ(f.source, TimeSource::kNominal);
    EXPECT_NEAR(f.t_s + (cf.times.origin_s - 1700000000.0), (-10 + i) / 500.0, 1e-9);
    EXPECT_NEAR(f.exposure_s, 500e-6, 1e-12);  // the setup's ShutterNs
  }
}

// Each fault of a CINE file: exit 3 naming the file and the byte offset where it was found.
TEST(CineFile, BrokenFilesNameTheByteOffset) {
  CineSpec s;
  const std::vector<std::uint8_t> good = testing::MakeCine(s, RandomFrames(2, s.width, s.height, 12, 8));
  const auto parse = [](std::vector<std::uint8_t> b) { ParseCine(ByteView(b.data(), b.size(), "x.cine")); };
  struct Fault { const char* what; std::size_t at; std::uint64_t value; int n; const char* expect; };
  for (const Fault f : {Fault{"magic", 0, 0x4242, 2, "x.cine: byte 0: not a Phantom CINE"},
                        Fault{"bit depth", 58, 12, 2, "x.cine: byte 58: unknown bit depth or packing"},
                        Fault{"packing", 60, 512, 4, "x.cine: byte 60: unknown bit depth or packing"},
                        Fault{"offsets past the end", 32, 0x7FFFFFF0, 4, "runs past the end of the file"},
                        Fault{"setup marker", 84 + 140, 0, 2, "x.cine: byte 224: no \"ST\" marker"},
                        Fault{"JPEG", 4, 1, 2, "JPEG-compressed"}}) {
    std::vector<std::uint8_t> b = good;
    testing::PutLe(&b, f.at, f.value, f.n);
    EXPECT_NE(ErrorOf([&] { parse(b); }).find(f.expect), std::string::npos) << f.what;
  }
  // Truncated: the last image cut short.
  std::vector<std::uint8_t> cut(good.begin(), good.end() - 10);
  const std::string e = ErrorOf([&] { parse(cut); });
  EXPECT_NE(e.find("image 1"), std::string::npos) << e;
  EXPECT_NE(e.find("runs past the end"), std::string::npos) << e;
}

TEST(MrawFile, CihxAndCihGiveTheFramesAtEveryDepth) {
  const rk::test::TempDir tmp("mraw_depths");
  for (int bits : {8, 12, 16}) {
    const int w = 10, h = 4, n = 3;
    const std::vector<Samples> frames = RandomFrames(n, w, h, bits == 16 ? 12 : bits, 20 + static_cast<unsigned>(bits));
    const std::string stem = "m" + std::to_string(bits);
    WriteBytes(tmp / (stem + ".mraw"), testing::MakeMraw(bits, frames));
    WriteText(tmp / (stem + ".cihx"), testing::MakeCihx(w, h, bits, n, 100, 2, 5000, 100000));
    for (const std::string& open : {stem + ".mraw", stem + ".cihx"}) {
      FrameSource src({(tmp / open)});
      cv::Mat m;
      for (int k = 0; k < n; ++k) {
        ASSERT_TRUE(src.Read(&m));
        for (int i = 0; i < w * h; ++i) {
          const std::uint16_t v = frames[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)];
          const int got = bits == 8 ? m.at<std::uint8_t>(i / w, i % w) : m.at<std::uint16_t>(i / w, i % w);
          ASSERT_EQ(got, bits == 8 ? v : Widened(v, 12)) << bits << "-bit frame " << k << " pixel " << i;
        }
      }
      EXPECT_FALSE(src.Read(&m));
    }
    // Times: frame numbers 100, 102, 104 at 5000 fps; exposure 100 µs.
    CameraFileReader r((tmp / (stem + ".mraw")));
    ASSERT_EQ(r.frames(), n);
    for (int k = 0; k < n; ++k) {
      EXPECT_NEAR(r.file().times.frames[static_cast<std::size_t>(k)].camera_ts_s, (100 + 2 * k) / 5000.0, 1e-12);
      EXPECT_NEAR(r.file().times.frames[static_cast<std::size_t>(k)].exposure_s, 100e-6, 1e-12);
    }
    EXPECT_DOUBLE_EQ(r.file().times.nominal_rate_hz, 2500.0);
  }
  // The .cih text form.
  const std::vector<Samples> frames = RandomFrames(2, 6, 2, 12, 30);
  WriteBytes(tmp / "c.mraw", testing::MakeMraw(12, frames));
  WriteText(tmp / "c.cih", testing::MakeCih(6, 2, 12, 2, 0, 60000, "1/800000"));
  CameraFileReader r((tmp / "c.mraw"));
  EXPECT_EQ(r.file().header, (tmp / "c.cih"));
  EXPECT_NEAR(r.file().times.frames[1].camera_ts_s, 1 / 60000.0, 1e-12);
  EXPECT_NEAR(r.file().times.frames[1].exposure_s, 1.25e-6, 1e-15);
}

// A CIHX that says the camera ran on IRIG: its per-frame stamps are not read, and the user is told (not UTC).
TEST(MrawFile, AnIrigRecordingIsSaidToBeTimedNominally) {
  const rk::test::TempDir tmp("mraw_irig");
  WriteBytes(tmp / "i.mraw", testing::MakeMraw(12, RandomFrames(2, 10, 4, 12, 41)));
  std::string x = testing::MakeCihx(10, 4, 12, 2, 0, 1, 1000, 1000);
  x.replace(x.find("</cih>"), 6, "<deviceInfo>\n<irig>1</irig>\n</deviceInfo>\n</cih>");
  WriteText(tmp / "i.cihx", x);
  const RecordingFrameTimes t = ReadFrameTimes({(tmp / "i.mraw")}, {});
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_EQ(t.warnings[0].code, "irig_not_read");
  EXPECT_NE(t.warnings[0].message.find("i.cihx:"), std::string::npos) << t.warnings[0].message;
  EXPECT_NE(t.warnings[0].message.find("not UTC"), std::string::npos) << t.warnings[0].message;
  EXPECT_FALSE(t.absolute);
  bool in_summary = false;
  for (const auto& w : FrameTimesSummary(t).warnings) in_summary |= w.code == "irig_not_read";
  EXPECT_TRUE(in_summary);
  // irig 0 (the real sample's value): nothing said.
  x.replace(x.find("<irig>1"), 7, "<irig>0");
  WriteText(tmp / "i.cihx", x);
  EXPECT_TRUE(ReadFrameTimes({(tmp / "i.mraw")}, {}).warnings.empty());
}

TEST(MrawFile, HeaderFaultsNameTheLine) {
  const rk::test::TempDir tmp("mraw_faults");
  const std::vector<Samples> frames = RandomFrames(3, 10, 4, 12, 40);
  WriteBytes(tmp / "a.mraw", testing::MakeMraw(12, frames));
  // A frame count the .mraw does not hold: the XML line of totalFrame (17: no newline in the preamble).
  WriteText(tmp / "a.cihx", testing::MakeCihx(10, 4, 12, 4, 0, 1, 1000, 1000));
  std::string e = ErrorOf([&] { CameraFileReader((tmp / "a.mraw")); });
  EXPECT_NE(e.find("a.cihx:17: 4 frames"), std::string::npos) << e;
  // An unknown bit depth.
  WriteText(tmp / "a.cihx", testing::MakeCihx(10, 4, 10, 3, 0, 1, 1000, 1000));
  e = ErrorOf([&] { CameraFileReader((tmp / "a.mraw")); });
  EXPECT_NE(e.find("unknown bit depth 10"), std::string::npos) << e;
  // Broken XML: tinyxml2's line.
  std::string x = testing::MakeCihx(10, 4, 12, 3, 0, 1, 1000, 1000);
  x.replace(x.find("</width>"), 8, "</wid>");
  WriteText(tmp / "a.cihx", x);
  e = ErrorOf([&] { CameraFileReader((tmp / "a.mraw")); });
  EXPECT_NE(e.find("not well-formed XML"), std::string::npos) << e;
  EXPECT_NE(e.find("a.cihx:"), std::string::npos) << e;
  // A colour recording is refused, not misread.
  WriteText(tmp / "a.cihx", testing::MakeCihx(10, 4, 12, 3, 0, 1, 1000, 1000, "Color"));
  e = ErrorOf([&] { CameraFileReader((tmp / "a.mraw")); });
  EXPECT_NE(e.find("colour type 'Color'"), std::string::npos) << e;
  // No header beside the .mraw: an I/O error.
  fs::remove(tmp / "a.cihx");
  try {
    CameraFileReader((tmp / "a.mraw"));
    ADD_FAILURE() << "no error";
  } catch (const Error& err) {
    EXPECT_EQ(err.code(), ExitCode::kIo) << err.what();
  }
}

TEST(RecordingTimes, EpochGapsAndBackwardsStampsAreSaidNeverRenumbered) {
  const rk::test::TempDir tmp("rec_times");
  CineSpec s;
  const std::uint32_t t0 = 1700000000;
  // 1 kHz: frames at 0, 1, 2, 5 (a gap of 3 intervals), 4 (backwards), 5 ms.
  for (int ms : {0, 1, 2, 5, 4, 5}) {
    s.stamps.push_back((static_cast<std::uint64_t>(t0) << 32) |
                       (static_cast<std::uint32_t>(std::llround(ms * 1e-3 * 4294967296.0)) & ~3u));
  }
  WriteBytes(tmp / "g.cine", testing::MakeCine(s, RandomFrames(6, s.width, s.height, 12, 9)));
  FrameTimesOptions o;
  o.epoch_unix_s = t0 - 10.0;
  const RecordingFrameTimes r = ReadFrameTimes({(tmp / "g.cine")}, o);
  ASSERT_EQ(r.frames.size(), 6u);
  EXPECT_TRUE(r.relative_to_epoch);
  EXPECT_NEAR(r.frames[3].t_s, 10.005, kStampTolS);
  EXPECT_EQ(r.frames[4].frame, 4);
  EXPECT_EQ(r.gaps, 1);
  EXPECT_EQ(r.backwards, 1);
  ASSERT_EQ(r.problems.size(), 2u);
  EXPECT_NE(r.problems[0].find("frame 3: gap of 0.003"), std::string::npos) << r.problems[0];
  EXPECT_NE(r.problems[1].find("frame 4: time goes back by 0.001"), std::string::npos) << r.problems[1];
  // Without an epoch: from the first frame, and said.
  const RecordingFrameTimes rel = ReadFrameTimes({(tmp / "g.cine")}, {});
  EXPECT_FALSE(rel.relative_to_epoch);
  EXPECT_NEAR(rel.frames[5].t_s, 0.005, kStampTolS);
  ASSERT_FALSE(rel.warnings.empty());
  EXPECT_NE(rel.warnings.back().message.find("no --epoch-utc"), std::string::npos);
  // An image sequence has no times of its own: --fps, else a usage error.
  EXPECT_THROW(ReadFrameTimes({(tmp / "seq_%03d.png")}, {}), Error);
}

// The real files of ../shared/data/real (RK_REAL_DATA overrides the folder): skipped, not passed, when absent.
fs::path RealData() {
  const char* env = std::getenv("RK_REAL_DATA");
  return env && *env ? fs::path(env) : fs::path(RK_REAL_DATA_DIR);
}

TEST(RealFiles, Chart1CineEqualsFfmpegsDecodePixelForPixel) {
  const fs::path cine = RealData() / "chart1.cine";
  if (!fs::exists(cine)) GTEST_SKIP() << cine << " is absent";
  CameraFileReader r(cine.string());
  EXPECT_EQ(r.frames(), 1);
  EXPECT_EQ(r.file().width, 2048);
  EXPECT_EQ(r.file().height, 1080);
  EXPECT_EQ(r.file().cfa, "GBRG");
  EXPECT_EQ(r.file().packing, Packing::kP10BE);
  cv::Mat mosaic;
  r.ReadMosaic(0, &mosaic);
  // ffmpeg's cine demuxer + rawvideo decoder, as bayer_gbrg16le.
  const rk::test::TempDir tmp("chart1");
  const fs::path raw = tmp / "chart1.raw";
  const std::string cmd = "ffmpeg -v error -nostdin -y -i " + ShellQuote(cine.string()) +
                          " -f rawvideo -pix_fmt bayer_gbrg16le " + ShellQuote(raw.string());
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  ASSERT_EQ(fs::file_size(raw), 2048u * 1080u * 2u);
  cv::Mat ff(1080, 2048, CV_16UC1);
  std::ifstream(raw, std::ios::binary).read(reinterpret_cast<char*>(ff.data), 2048 * 1080 * 2);
  EXPECT_EQ(cv::countNonZero(mosaic != ff), 0) << "pixels that differ from ffmpeg's decode";
  // Its times: a time block (not IRIG-synchronised) dated 2000-07-13, a trigger time of 2014-07-14: said.
  const RecordingTimes& t = r.file().times;
  EXPECT_EQ(t.frames[0].source, TimeSource::kCamera);
  EXPECT_NEAR(t.origin_s + t.frames[0].t_s, 963484684.0, 1.0);
  EXPECT_NEAR(t.frames[0].exposure_s, 0.02, 1e-5);  // the exposure block: 85907195 / 2^32 s (ShutterNs says 20000078 ns)
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_EQ(t.warnings[0].code, "times_disagree");
  EXPECT_NE(t.warnings[0].message.find("2014-07-14"), std::string::npos) << t.warnings[0].message;
}

// An unpacking of Photron's 12-bit packing written independently of packed_pixels.cc: bit by bit.
std::vector<std::uint16_t> Unpack12BitByBit(const std::vector<std::uint8_t>& b, std::size_t pixels) {
  std::vector<std::uint16_t> out(pixels, 0);
  for (std::size_t i = 0; i < pixels; ++i) {
    for (int k = 0; k < 12; ++k) {
      const std::size_t bit = i * 12 + static_cast<std::size_t>(k);
      const int v = (b[bit / 8] >> (7 - bit % 8)) & 1;
      out[i] = static_cast<std::uint16_t>((out[i] << 1) | v);
    }
  }
  return out;
}

TEST(RealFiles, Ball12BitMrawEqualsAnIndependentUnpackingAndFallsDown) {
  const fs::path mraw = RealData() / "ball_12bit.mraw";
  if (!fs::exists(mraw)) GTEST_SKIP() << mraw << " is absent";
  CameraFileReader r(mraw.string());
  ASSERT_EQ(r.frames(), 15);
  EXPECT_EQ(r.file().width, 384);
  EXPECT_EQ(r.file().height, 384);
  std::ifstream in(mraw, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t frame_bytes = 384 * 384 * 3 / 2;
  std::vector<double> dark_row;  // the ball: the row of the darkest pixels' centroid, per frame
  for (int k = 0; k < 15; ++k) {
    const std::vector<std::uint8_t> one(bytes.begin() + static_cast<std::ptrdiff_t>(k * frame_bytes),
                                        bytes.begin() + static_cast<std::ptrdiff_t>((k + 1) * frame_bytes));
    const std::vector<std::uint16_t> ref = Unpack12BitByBit(one, 384 * 384);
    cv::Mat m;
    r.Read(k, &m);
    double sy = 0, n = 0;
    for (int i = 0; i < 384 * 384; ++i) {
      ASSERT_EQ(m.at<std::uint16_t>(i / 384, i % 384), Widened(ref[static_cast<std::size_t>(i)], 12)) << "frame " << k;
      if (ref[static_cast<std::size_t>(i)] < 1500 && i / 384 < 300) {  // the dark ball, above the textured edge
        sy += i / 384;
        n += 1;
      }
    }
    ASSERT_GT(n, 50) << "no dark ball in frame " << k;
    dark_row.push_back(sy / n);
  }
  // Physics: it falls (image y grows) over the 15 frames.
  EXPECT_GT(dark_row.back(), dark_row.front());
  // Times: 30 000 fps from frame 52, shutter 20 µs; no stamps (nominal).
  const RecordingTimes& t = r.file().times;
  EXPECT_NEAR(t.frames[0].camera_ts_s, 52 / 30000.0, 1e-12);
  EXPECT_NEAR(t.frames[14].t_s - t.frames[0].t_s, 14 / 30000.0, 1e-12);
  EXPECT_NEAR(t.frames[0].exposure_s, 20e-6, 1e-12);
  EXPECT_EQ(t.frames[0].source, TimeSource::kNominal);
}

}  // namespace
}  // namespace rk::video

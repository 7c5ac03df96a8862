// The ASTERIX decoder, the capture reader and the feed into plots, against records and captures written by the
// test's own encoder (asterix_encoder.h) with known values: every item rangekit decodes, every item it must skip
// by its length, malformed records with their offsets, redundant feeds, midnight, CAT001's truncated time, IP
// fragments, pcapng; and the elevation from a height against the forward geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "asterix/block.h"
#include "asterix/capture.h"
#include "asterix/feed.h"
#include "asterix_encoder.h"
#include "formats/radar_plots.h"
#include "geo/wgs84.h"
#include "io/error.h"
#include "rk_test/temp_dir.h"

namespace rk::asterix {
namespace {

using test::Be;
using test::Block;
using test::Bytes;
using test::Cat;
using test::Cat048;
using test::Cat048Record;
using test::Record;

constexpr double kTodTol = 1e-9;        // times of day are exact multiples of 1/128 s
constexpr double kRangeTol = 1e-9;      // m: ρ × 1852/256 computed in double
constexpr double kAzTol = 1e-12;        // deg
constexpr double kHeightTol = 1e-3;     // m: ElevationToHeight's target is 0.1 mm

struct Collect : BlockVisitor {
  std::vector<RecordLayout> records;
  std::vector<std::size_t> offsets;
  std::vector<std::pair<std::size_t, std::string>> bad;
  void OnRecord(const RecordLayout& r, std::size_t offset) override {
    records.push_back(r);
    offsets.push_back(offset);
  }
  void OnBad(std::size_t offset, std::uint8_t, const char* reason) override { bad.push_back({offset, reason}); }
};

TEST(AsterixRecord, Cat048ItemsDecodedAndOthersSkippedByTheirLength) {
  Cat048 a;
  a.tod_s = 86399.9921875;  // last 1/128 s of the day
  a.rho = 65535;            // 256 NM − 1/256
  a.theta = 65535;          // just below 360°
  a.fl_quarters = -4;       // FL −1: two's complement
  a.height_25ft = -3;       // −75 ft
  a.mode3a = 07700;
  a.address = 0xABCDEF;
  a.track = 4095;
  Cat048 b;
  b.rho = 256;  // 1 NM
  b.theta = 16384;  // 90°
  b.extras = false;
  const Bytes data = Block(48, {Cat048Record(a), Cat048Record(b)});
  Collect c;
  EXPECT_EQ(WalkBlocks(data.data(), data.size(), &c), 1u);
  ASSERT_TRUE(c.bad.empty()) << c.bad[0].second;
  ASSERT_EQ(c.records.size(), 2u);
  const TargetReport t = DecodeTargetReport(c.records[0]);
  EXPECT_EQ(t.sac, 25);
  EXPECT_EQ(t.sic, 10);
  EXPECT_NEAR(t.time_of_day_s, 86399.9921875, kTodTol);
  EXPECT_NEAR(t.rho_m, 65535.0 / 256 * 1852, kRangeTol);
  EXPECT_NEAR(t.theta_deg, 65535.0 * 360 / 65536, kAzTol);
  EXPECT_DOUBLE_EQ(t.flight_level, -1.0);
  EXPECT_NEAR(t.height_m, -75 * 0.3048, 1e-12);
  EXPECT_EQ(t.mode3a, 07700);
  EXPECT_STREQ(Mode3aText(t.mode3a).data(), "7700");
  EXPECT_EQ(t.address, 0xABCDEF);
  EXPECT_EQ(t.track_number, 4095);
  EXPECT_EQ(t.detection_type, 5);
  const TargetReport u = DecodeTargetReport(c.records[1]);
  EXPECT_NEAR(u.rho_m, 1852.0, kRangeTol);
  EXPECT_NEAR(u.theta_deg, 90.0, kAzTol);
  EXPECT_TRUE(std::isnan(u.flight_level));
  EXPECT_EQ(u.mode3a, -1);
  EXPECT_EQ(c.offsets[1], 3 + Cat048Record(a).size());
}

TEST(AsterixRecord, NotValidatedOrGarbledCodesAreNotValues) {
  Cat048 a;
  a.fl_quarters = 1400;
  a.fl_invalid = true;
  a.mode3a = 0x8000 | 01234;  // V set
  const Bytes data = Block(48, {Cat048Record(a)});
  Collect c;
  WalkBlocks(data.data(), data.size(), &c);
  ASSERT_EQ(c.records.size(), 1u);
  const TargetReport t = DecodeTargetReport(c.records[0]);
  EXPECT_TRUE(std::isnan(t.flight_level));
  EXPECT_TRUE(t.flight_level_invalid);
  EXPECT_EQ(t.mode3a, -1);
  EXPECT_TRUE(t.mode3a_invalid);
}

TEST(AsterixRecord, Cat001PlotAndTrackLayoutsFollowTyp) {
  // Plot: 010, 020 (TYP 0), 040 at FRN 3 (ρ in 1/128 NM), 141 at FRN 7.
  const Bytes plot = Record({{1, {25, 3}}, {2, {0x20}}, {3, Cat({Be(128, 2), Be(32768, 2)})}, {7, Be(512 * 128 - 1, 2)}});
  // Track: 020 TYP 1, 161 at FRN 3, 040 at FRN 4, 200 at FRN 6 (skipped), 141 at FRN 9, 210 (FX chain) at 14.
  const Bytes track = Record({{1, {25, 3}},
                              {2, {0x80}},
                              {3, Be(777, 2)},
                              {4, Cat({Be(30000, 2), Be(100, 2)})},
                              {6, Be(0x01020304, 4)},
                              {9, Be(640, 2)},
                              {14, {0x01, 0x02}}});
  // Random field sequencing (plot FRN 21): I001/131 (FRN 10) and I001/150 (FRN 15) given inside it.
  const Bytes rfs = Record({{1, {25, 3}}, {2, {0x20}}, {3, Cat({Be(1, 2), Be(2, 2)})}, {21, {2, 10, 0x7F, 15, 0x00}}});
  // A track record without FRN 3 (no I001/161): still the track layout, its ρ at FRN 4.
  const Bytes track_no_161 = Record({{1, {25, 3}}, {2, {0x80}}, {4, Cat({Be(256, 2), Be(0, 2)})}});
  const Bytes data = Block(1, {plot, track, rfs, track_no_161});
  Collect c;
  WalkBlocks(data.data(), data.size(), &c);
  ASSERT_TRUE(c.bad.empty()) << c.bad[0].second;
  ASSERT_EQ(c.records.size(), 4u);
  const TargetReport p = DecodeTargetReport(c.records[0]);
  EXPECT_FALSE(p.track_record);
  EXPECT_NEAR(p.rho_m, 1852.0, kRangeTol);
  EXPECT_NEAR(p.theta_deg, 180.0, kAzTol);
  EXPECT_NEAR(p.truncated_time_of_day_s, 512 - 1.0 / 128, kTodTol);
  const TargetReport t = DecodeTargetReport(c.records[1]);
  EXPECT_TRUE(t.track_record);
  EXPECT_EQ(t.track_number, 777);
  EXPECT_NEAR(t.rho_m, 30000 / 128.0 * 1852, kRangeTol);  // 234 NM: a track's ρ read with the track layout
  EXPECT_NEAR(t.truncated_time_of_day_s, 5.0, kTodTol);
  EXPECT_NEAR(DecodeTargetReport(c.records[2]).rho_m, 1852.0 / 128, kRangeTol);
  EXPECT_TRUE(DecodeTargetReport(c.records[3]).track_record);
  EXPECT_NEAR(DecodeTargetReport(c.records[3]).rho_m, 2 * 1852.0, kRangeTol);
}

TEST(AsterixRecord, Cat034ServiceMessages) {
  const Bytes north = Record({{1, {25, 12}}, {2, {1}}, {3, Be(100 * 128, 3)}, {5, Be(4 * 128 + 64, 2)},
                              {6, {0b1001'1100, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE}},  // 050: COM, PSR, SSR, MDS (2)
                              {7, {0b1001'1100, 1, 2, 3, 4}},                   // 060: COM, PSR, SSR, MDS
                              {8, {2, 0, 1, 0, 2}}});                           // 070: REP 2 × 2
  const Bytes sector = Record({{1, {25, 12}}, {2, {2}}, {3, Be(101 * 128, 3)}, {4, {64}}});
  const Bytes data = Block(34, {north, sector});
  Collect c;
  WalkBlocks(data.data(), data.size(), &c);
  ASSERT_TRUE(c.bad.empty()) << c.bad[0].second;
  ASSERT_EQ(c.records.size(), 2u);
  const ServiceMessage n = DecodeServiceMessage(c.records[0]);
  EXPECT_EQ(n.message_type, 1);
  EXPECT_NEAR(n.time_of_day_s, 100.0, kTodTol);
  EXPECT_NEAR(n.rotation_period_s, 4.5, kTodTol);
  const ServiceMessage s = DecodeServiceMessage(c.records[1]);
  EXPECT_EQ(s.message_type, 2);
  EXPECT_NEAR(s.sector_deg, 90.0, kAzTol);
}

struct Malformed {
  const char* name;
  Bytes data;
  std::size_t good_records;  // decoded before the problem
  std::size_t offset;        // of the problem
  const char* reason_part;
};

TEST(AsterixRecord, MalformedInputNamesItsOffset) {
  const Bytes good = Cat048Record(Cat048{});
  const std::size_t g = good.size();
  const std::vector<Malformed> cases = {
      {"block length past the datagram", Cat({{48, 0, 200}, good}), 0, 0, "runs past the end of the datagram"},
      {"block length below its header", {48, 0, 2, 0}, 0, 0, "below 3"},
      {"unknown category, then a good block", Cat({Block(62, {good}), Block(48, {good})}), 1, 0, "unknown category"},
      {"FSPEC past the block", Block(48, {good, {0xFF, 0xFF}}), 1, 3 + g + 2, "FSPEC runs past"},
      {"FSPEC longer than the UAP", Block(48, {{0x01, 0x01, 0x01, 0x01, 0x01}}), 0, 3 + 3, "longer than the category's UAP"},
      {"item past the block", Block(48, {Record({{1, {1, 2}}, {4, {0, 0}}})}), 0, 3 + 1 + 2, "runs past the end"},
      {"spare FRN of CAT001", Block(1, {Record({{1, {1, 2}}, {2, {0}}, {16, {}}})}), 0, 3 + 2, "does not use"},
      {"explicit item of length 0", Block(48, {Record({{1, {1, 2}}, {27, {0}}})}), 0, 3 + 4 + 2, "length 0"},
      {"compound with an undefined subfield", Block(34, {Record({{1, {1, 2}}, {6, {0b0100'0000}}})}), 0, 3 + 1 + 2,
       "does not define"},
      {"empty FSPEC inside data", Block(48, {good, {0x00, 0x05}}), 1, 3 + g, "empty FSPEC"},
  };
  for (const Malformed& m : cases) {
    Collect c;
    WalkBlocks(m.data.data(), m.data.size(), &c);
    EXPECT_EQ(c.records.size(), m.good_records) << m.name;
    ASSERT_EQ(c.bad.size(), 1u) << m.name;
    EXPECT_EQ(c.bad[0].first, m.offset) << m.name << ": " << c.bad[0].second;
    EXPECT_NE(c.bad[0].second.find(m.reason_part), std::string::npos) << m.name << ": " << c.bad[0].second;
  }
  // Zero padding after the last record is not a problem.
  const Bytes padded = Block(48, {good, Bytes(5, 0)});
  Collect c;
  WalkBlocks(padded.data(), padded.size(), &c);
  EXPECT_EQ(c.records.size(), 1u);
  EXPECT_TRUE(c.bad.empty());
}

// 2016-05-05T00:00:00Z.
constexpr double kDay0 = 1462406400.0;

test::Packet Datagram(double t, Bytes payload, std::uint32_t src = 0x0A000001, std::uint32_t dst = 0xE8010101) {
  test::Packet p;
  p.t_unix_s = t;
  p.payload = std::move(payload);
  p.src = src;
  p.dst = dst;
  return p;
}

FeedResult Import(const std::string& path, double epoch, std::vector<formats::RadarSite> radars = {},
                  bool bad_error = false) {
  FeedOptions o;
  o.epoch_unix_s = epoch;
  o.radars = std::move(radars);
  o.bad_records_error = bad_error;
  return ImportFeed({path}, o);
}

TEST(AsterixFeed, RedundantFeedMidnightFragmentsAndOrder) {
  rk::test::TempDir dir;
  std::vector<test::Packet> packets;
  // Radar 25-10, a record stamped 23:59:59.5 captured just after midnight: it belongs to the day before.
  Cat048 late;
  late.tod_s = 86399.5;
  late.rho = 1000;
  late.theta = 65000;
  Cat048 early;  // 00:00:00.25 of the next day, captured at 00:00:00.4
  early.tod_s = 0.25;
  early.rho = 2000;
  early.theta = 10;
  const Bytes b1 = Block(48, {Cat048Record(early), Cat048Record(late)});  // arrival order ≠ time order
  packets.push_back(Datagram(kDay0 + 86400 + 0.4, b1, 0x0A000001, 0xE8010101));
  packets.push_back(Datagram(kDay0 + 86400 + 0.4001, b1, 0x0A000002, 0xE8020101));  // the redundant copy
  // A long datagram in three IP fragments (arriving last first) on a VLAN.
  std::vector<Bytes> many;
  for (int k = 0; k < 60; ++k) {
    Cat048 r;
    r.tod_s = 1.0 + k / 128.0;
    r.rho = static_cast<std::uint32_t>(3000 + k);
    r.theta = static_cast<std::uint32_t>(k * 1000);
    many.push_back(Cat048Record(r));
  }
  test::Packet frag = Datagram(kDay0 + 86400 + 2.0, Block(48, many));
  frag.fragments = 3;
  frag.vlan = true;
  frag.ip_id = 77;
  packets.push_back(frag);
  test::Packet tcp = Datagram(kDay0 + 86400 + 2.1, Bytes(20, 1));
  tcp.tcp = true;
  packets.push_back(tcp);
  const std::string pcap = dir.path() + "/feed.pcap";
  test::WritePcap(pcap, packets);
  const FeedResult r = Import(pcap, kDay0 + 86400);
  ASSERT_EQ(r.rows.size(), 62u);
  EXPECT_NEAR(r.rows[0].t_s, -0.5, kTodTol);  // the day before the capture's
  EXPECT_NEAR(r.rows[0].az_deg, 65000 * 360.0 / 65536, kAzTol);
  EXPECT_NEAR(r.rows[1].t_s, 0.25, kTodTol);
  EXPECT_NEAR(r.rows[2].t_s, 1.0, kTodTol);
  EXPECT_NEAR(r.rows[61].range_m, (3000 + 59) / 256.0 * 1852, kRangeTol);
  for (std::size_t i = 1; i < r.rows.size(); ++i) EXPECT_LE(r.rows[i - 1].t_s, r.rows[i].t_s);
  ASSERT_EQ(r.radar_names.size(), 1u);
  EXPECT_EQ(r.radar_names[0], "25-10");
  const io::Json& d = r.summary.details["asterix"];
  EXPECT_EQ(d["duplicates"], 2);
  EXPECT_EQ(d["inputs"][0]["reassembled_datagrams"], 1);
  EXPECT_EQ(d["inputs"][0]["other_packets"], 1);
  EXPECT_EQ(d["rows_out_of_arrival_order"], 1);
  // Duplicates counted against the source that sent the copy.
  std::size_t dup_sources = 0;
  for (const io::Json& s : d["sources"]) dup_sources += s["duplicates"].get<std::size_t>() > 0;
  EXPECT_EQ(dup_sources, 1u);
  // The same capture as pcapng gives the same plots.
  const std::string ng = dir.path() + "/feed.pcapng";
  test::WritePcapng(ng, packets);
  const FeedResult g = Import(ng, kDay0 + 86400);
  ASSERT_EQ(g.rows.size(), r.rows.size());
  for (std::size_t i = 0; i < g.rows.size(); ++i) EXPECT_EQ(g.rows[i].t_s, r.rows[i].t_s);
  EXPECT_EQ(g.summary.details["asterix"]["inputs"][0]["format"], "pcapng");
}

TEST(AsterixFeed, Cat001TruncatedTimeUnwrappedAroundTheCaptureTime) {
  rk::test::TempDir dir;
  // Captured at 10:00:00.5; the plot's time of day modulo 512 s is 36000 mod 512 − 0.25 s: 0.75 s earlier.
  const double capture = kDay0 + 36000.5;
  const double tod = 36000.0 - 0.25;
  const Bytes plot = Record({{1, {25, 3}}, {2, {0x20}}, {3, Cat({Be(128, 2), Be(0, 2)})},
                             {7, Be(static_cast<std::uint32_t>(std::fmod(tod, 512.0) * 128), 2)}});
  // Across midnight, where a day is not a whole number of 512-s periods: 23:59:55 (86395 mod 512 = 379 s)
  // captured at 00:00:01 the next day.
  const Bytes late = Record({{1, {25, 3}}, {2, {0x20}}, {3, Cat({Be(256, 2), Be(0, 2)})}, {7, Be(379 * 128, 2)}});
  const std::string pcap = dir.path() + "/cat001.pcap";
  test::WritePcap(pcap, {Datagram(capture, Block(1, {plot})), Datagram(kDay0 + 86401, Block(1, {late}))});
  const FeedResult r = Import(pcap, kDay0);
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_NEAR(r.rows[0].t_s, tod, kTodTol);
  EXPECT_NEAR(r.rows[0].range_m, 1852.0, kRangeTol);
  EXPECT_NEAR(r.rows[1].t_s, 86395.0, kTodTol);
}

TEST(AsterixFeed, RawStreamTakesItsDateFromTheEpochAndRollsOverMidnight) {
  rk::test::TempDir dir;
  std::vector<Bytes> blocks;
  for (double tod : {86398.0, 86399.5, 0.5, 2.0}) {
    Cat048 c;
    c.tod_s = tod;
    blocks.push_back(Block(48, {Cat048Record(c)}));
  }
  Bytes stream;
  for (const Bytes& b : blocks) stream.insert(stream.end(), b.begin(), b.end());
  const std::string ast = dir.path() + "/feed.ast";
  std::ofstream(ast, std::ios::binary).write(reinterpret_cast<const char*>(stream.data()), static_cast<std::streamsize>(stream.size()));
  const FeedResult r = Import(ast, kDay0 + 86000);
  ASSERT_EQ(r.rows.size(), 4u);
  EXPECT_NEAR(r.rows[0].t_s, 398.0, kTodTol);
  EXPECT_NEAR(r.rows[2].t_s, 400.5, kTodTol);
  EXPECT_NEAR(r.rows[3].t_s, 402.0, kTodTol);
}

TEST(AsterixFeed, BadRecordsSkippedAndCountedOrAnError) {
  rk::test::TempDir dir;
  const Bytes good = Block(48, {Cat048Record(Cat048{})});
  const Bytes bad = Cat({{48, 0, 90}, Bytes(10, 0xFF)});  // length past its datagram
  test::Packet cut = Datagram(kDay0 + 3601, good);
  cut.snap = 40;  // the snap length cuts the IP datagram
  const std::string pcap = dir.path() + "/bad.pcap";
  test::WritePcap(pcap, {Datagram(kDay0 + 3600, good), Datagram(kDay0 + 3600.5, bad), cut});
  const FeedResult r = Import(pcap, kDay0);
  EXPECT_EQ(r.rows.size(), 1u);
  EXPECT_EQ(r.summary.details["asterix"]["bad_records"], 2);
  ASSERT_GE(r.summary.warnings.size(), 2u);
  // The bad block: the second packet's payload, after 24 + 16 + frame (14 + 20 + 8 + payload) + 16 + 42 octets.
  const std::size_t first_frame = 14 + 20 + 8 + good.size();
  const std::string where = pcap + ": byte " + std::to_string(24 + 16 + first_frame + 16 + 42) + ": ";
  EXPECT_EQ(r.summary.warnings[0].message.rfind(where, 0), 0u) << r.summary.warnings[0].message;
  EXPECT_NE(r.summary.warnings[1].message.find("snap length"), std::string::npos) << r.summary.warnings[1].message;
  try {
    Import(pcap, kDay0, {}, true);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(where, 0), 0u) << e.what();
  }
}

TEST(AsterixFeed, ElevationFromHeightOrModeCWithTheRadarsPosition) {
  rk::test::TempDir dir;
  Cat048 h;  // a 3-D radar's height, 100 NM out
  h.rho = 100 * 256;
  h.theta = 8192;
  h.height_25ft = 400;  // 10 000 ft
  h.fl_quarters = 4 * 300;
  Cat048 m;  // Mode C only: FL 300
  m.rho = 150 * 256;
  m.theta = 30000;
  m.fl_quarters = 4 * 300;
  Cat048 two_d;  // neither
  two_d.rho = 20 * 256;
  const std::string pcap = dir.path() + "/el.pcap";
  test::WritePcap(pcap, {Datagram(kDay0 + 3600, Block(48, {Cat048Record(h), Cat048Record(m), Cat048Record(two_d)}))});
  formats::RadarSite site{"north", 25, 10, geo::Geodetic{45.0, 16.0, 120.0}};
  const FeedResult r = Import(pcap, kDay0, {site});
  ASSERT_EQ(r.rows.size(), 3u);
  EXPECT_EQ(r.radar_names[0], "north");
  const geo::LocalEnu enu(*site.position);
  const auto height_at = [&](const formats::AsterixPlotRow& row) {
    const double el = row.el_deg * M_PI / 180, az = row.az_deg * M_PI / 180;
    return enu.ToGeodetic(row.range_m * Eigen::Vector3d(std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el))).h_m;
  };
  EXPECT_EQ(r.rows[0].el_source, formats::ElevationSource::k3d);
  EXPECT_NEAR(height_at(r.rows[0]), 10000 * 0.3048, kHeightTol);
  EXPECT_EQ(r.rows[1].el_source, formats::ElevationSource::kModeC);
  EXPECT_NEAR(height_at(r.rows[1]), 30000 * 0.3048, kHeightTol);
  EXPECT_EQ(r.rows[2].el_source, formats::ElevationSource::kNone);
  EXPECT_TRUE(std::isnan(r.rows[2].el_deg));
}

TEST(ElevationToHeight, MatchesTheForwardGeometryAndDiffersFromAFlatEarth) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> lat(-80, 80), lon(-180, 180), h0(0, 2000), range(5e3, 4.5e5), az(0, 2 * M_PI),
      height(0, 15000);
  double flat_min = 1e9, flat_max = 0;
  for (int i = 0; i < 200; ++i) {
    const geo::LocalEnu site(geo::Geodetic{lat(rng), lon(rng), h0(rng)});
    const double r = range(rng), a = az(rng), h = height(rng);
    const std::optional<double> el = geo::ElevationToHeight(site, r, a, h);
    if (!el) {  // only when the height is out of reach at that range
      EXPECT_GT(std::abs(h - site.origin().h_m), 0.9 * r);
      continue;
    }
    const Eigen::Vector3d p = r * Eigen::Vector3d(std::cos(*el) * std::sin(a), std::cos(*el) * std::cos(a), std::sin(*el));
    EXPECT_NEAR(site.ToGeodetic(p).h_m, h, kHeightTol);
    if (r > 1e5 && r < 4e5 && h < 13000) {  // a flat earth's elevation asin((h − h0)/r) at radar ranges
      const double flat = std::asin((h - site.origin().h_m) / r);
      flat_min = std::min(flat_min, std::abs(flat - *el) * 180 / M_PI);
      flat_max = std::max(flat_max, std::abs(flat - *el) * 180 / M_PI);
    }
  }
  // The earth's curvature alone lowers a target by r²/2R: a flat earth's elevation is off by ≈ r/2R, 0.45° at
  // 100 km — the reason for the ellipsoid.
  EXPECT_GT(flat_min, 0.4);
  EXPECT_LT(flat_max, 2.0);
  EXPECT_FALSE(geo::ElevationToHeight(geo::LocalEnu(geo::Geodetic{0, 0, 0}), 1000.0, 0.0, 5000.0));
  EXPECT_FALSE(geo::ElevationToHeight(geo::LocalEnu(geo::Geodetic{0, 0, 0}), 0.0, 0.0, 0.0));
}

TEST(RadarsFile, ErrorsNameLineAndColumn) {
  const std::string text = "{\"radars\": [\n  {\"name\": \"r1\", \"sac\": 25, \"sic\": 10},\n  {\"name\": \"r2\", \"sac\": 25, \"sic\": 300}\n]}";
  try {
    formats::ParseRadars(text, "radars.json");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("radars.json:3:", 0), 0u) << e.what();
  }
  const auto ok = formats::ParseRadars(
      "{\"radars\": [{\"name\": \"r1\", \"sac\": 25, \"sic\": 10, \"lat_deg\": 45, \"lon_deg\": 16, \"h_m\": 100}]}", "r.json");
  ASSERT_EQ(ok.size(), 1u);
  ASSERT_TRUE(ok[0].position);
  EXPECT_EQ(ok[0].position->lat_deg, 45.0);
}

}  // namespace
}  // namespace rk::asterix

// The beacon track, range log and turret log readers (formats/beacon_track.h, range_log.h, turret_log.h):
// track statuses, range log statuses and values, turret log elevation range.
#include <gtest/gtest.h>

#include <string>

#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "formats/beacon_track.h"
#include "formats/range_log.h"
#include "formats/turret_log.h"

namespace rk::formats {
namespace {

TEST(LocateInputs, TrackWithoutStatusColumn) {
  const auto t =
      io::CsvTable::Parse("# truth\nframe,t_s,x_px,y_px,visible\n0,0.0,10,20,1\n1,0.05,,,0\n", "b.csv");
  const Track track = ReadTrack(t);
  ASSERT_EQ(track.rows.size(), 2u);
  EXPECT_EQ(track.rows[0].status, RowStatus::kOk);
  EXPECT_TRUE(track.rows[0].px.has_value());
  EXPECT_EQ(track.rows[1].status, RowStatus::kLost);
  EXPECT_FALSE(track.rows[1].px.has_value());
}

TEST(LocateInputs, TrackStatuses) {
  const auto t = io::CsvTable::Parse(
      "frame,t_s,x_px,y_px,status\n0,0,1,2,ok\n1,0.1,1,2,reacquired\n2,0.2,1,2,lost\n3,0.3,,,ok\n", "tr.csv");
  const Track track = ReadTrack(t);
  EXPECT_EQ(track.rows[1].status, RowStatus::kReacquired);
  EXPECT_EQ(track.rows[2].status, RowStatus::kLost);
  EXPECT_FALSE(track.rows[2].px.has_value());
  EXPECT_EQ(track.rows[3].status, RowStatus::kLost);
  const auto bad = io::CsvTable::Parse("t_s,x_px,y_px,status\n0,1,2,found\n", "tr.csv");
  try {
    ReadTrack(bad);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("tr.csv:2:"), std::string::npos) << e.what();
  }
  const auto back = io::CsvTable::Parse("t_s,x_px,y_px\n0.2,1,2\n0.1,1,2\n", "tr.csv");
  EXPECT_THROW(ReadTrack(back), Error);
}

TEST(LocateInputs, RangeLogStatusAndValues) {
  const auto t = io::CsvTable::Parse("t_s,range_m,status\n0,10,0\n0.2,,3\n0.4,10.2,5\n0.6,10.3,\n", "r.csv");
  const RangeLog log = ReadRangeLog(t);
  EXPECT_EQ(log.device_errors, 2u);
  EXPECT_TRUE(log.range_m[0].has_value());
  EXPECT_FALSE(log.range_m[1].has_value());
  EXPECT_FALSE(log.range_m[2].has_value());
  EXPECT_TRUE(log.range_m[3].has_value());
  const auto neg = io::CsvTable::Parse("t_s,range_m\n0,-1\n", "r.csv");
  EXPECT_THROW(ReadRangeLog(neg), Error);
  const auto text = io::CsvTable::Parse("t_s,range_m\n0,abc\n", "r.csv");
  EXPECT_THROW(ReadRangeLog(text), Error);
}

TEST(LocateInputs, TurretLogElevationRange) {
  const auto t = io::CsvTable::Parse("t_s,az_deg,el_deg\n0,10,95\n", "tu.csv");
  EXPECT_THROW(ReadTurretLog(t), Error);
  const auto ok = io::CsvTable::Parse("t_s,az_deg,el_deg\n0,370,45\n", "tu.csv");
  EXPECT_NEAR(ReadTurretLog(ok).az_rad[0], geo::DegToRad(370.0), 1e-15);
}

}  // namespace
}  // namespace rk::formats

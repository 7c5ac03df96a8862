// The trajectory of SPEC.md §7 (formats/trajectory.h): what rk-intersect writes reads back, and the reader's
// checks name file:line:col; the located target's positions (LocatedRead::kPositions) for rk-export.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "formats/located.h"
#include "formats/trajectory.h"
#include "io/csv.h"
#include "io/error.h"

namespace rk::formats {
namespace {

using ::testing::HasSubstr;

const char* const kHeader = "t_s,e_m,n_m,u_m,lat_deg,lon_deg,h_m,sigma_e_m,sigma_n_m,sigma_u_m,n_stations,status\n";

std::string TrajectoryError(const std::string& text) {
  try {
    ReadTrajectory(io::CsvTable::Parse(text, "traj.csv"));
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    return e.what();
  }
  return "";
}

TEST(Trajectory, ReadsPositionsSigmaAndStatus) {
  const TrajectoryFile f = ReadTrajectory(io::CsvTable::Parse(
      std::string(kHeader) + "0.0,1,2,3,47.1,8.2,500.5,0.1,0.2,0.3,3,ok\n0.1,,,,,,,,,,1,lost\n", "traj.csv"));
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_FALSE(f.has_id);
  ASSERT_TRUE(f.rows[0].geodetic.has_value());
  EXPECT_DOUBLE_EQ(f.rows[0].geodetic->lat_deg, 47.1);
  EXPECT_DOUBLE_EQ(f.rows[0].geodetic->lon_deg, 8.2);
  EXPECT_DOUBLE_EQ(f.rows[0].geodetic->h_m, 500.5);
  ASSERT_TRUE(f.rows[0].sigma_enu_m.has_value());
  EXPECT_DOUBLE_EQ((*f.rows[0].sigma_enu_m)(2), 0.3);
  EXPECT_EQ(f.rows[0].n_stations, 3);
  EXPECT_EQ(f.rows[1].status, RowStatus::kLost);
  EXPECT_FALSE(f.rows[1].geodetic.has_value());
  EXPECT_EQ(f.rows[1].line, 3u);
}

TEST(Trajectory, ColumnNamesAreTheWritersFirst) {
  // rk-intersect writes t_s[,id] then TrajectoryColumns(): the SPEC columns of §2.1 in their order.
  std::string header = "t_s";
  for (const std::string& c : TrajectoryColumns()) header += "," + c;
  EXPECT_EQ(header + "\n",
            std::string("t_s,e_m,n_m,u_m,lat_deg,lon_deg,h_m,sigma_e_m,sigma_n_m,sigma_u_m,n_stations,status,"
                        "rms_residual_arcsec\n"));
}

TEST(Trajectory, ErrorsNameTheCell) {
  EXPECT_THAT(TrajectoryError("t_s,lat_deg,lon_deg,h_m,status\n0,1,2,3,ok\n"), HasSubstr("traj.csv:1:1: missing column 'e_m'"));
  // An ok row must have its position (column 5 = lat_deg at character 9).
  EXPECT_THAT(TrajectoryError(std::string(kHeader) + "0.0,1,2,3,,8.2,500,0.1,0.2,0.3,3,ok\n"),
              HasSubstr("traj.csv:2:11: column 'lat_deg': empty, but the row's status 'ok' has a position"));
  EXPECT_THAT(TrajectoryError(std::string(kHeader) + "0.0,1,2,3,95,8.2,500,0.1,0.2,0.3,3,ok\n"),
              HasSubstr("traj.csv:2:11: column 'lat_deg': latitude must be in [-90, 90]"));
  EXPECT_THAT(TrajectoryError(std::string(kHeader) + "0.0,1,2,3,45,8.2,500,0.1,0.2,0.3,3,fine\n"),
              HasSubstr("traj.csv:2:"));
  EXPECT_THAT(TrajectoryError(std::string(kHeader) + "0.0,1,2,3,45,8.2,500,0.1,0.2,0.3,3,fine\n"),
              HasSubstr("unknown status"));
  EXPECT_THAT(TrajectoryError(std::string(kHeader) + "0.0,1,2,3,45,8.2,500,-0.1,0.2,0.3,3,ok\n"),
              HasSubstr("must not be negative"));
  EXPECT_THAT(TrajectoryError(std::string(kHeader) + "0.0,1,2,3,45,8,500,,,,3,ok\n0.0,1,2,3,45,8,500,,,,3,ok\n"),
              HasSubstr("traj.csv:3:1: column 't_s': time does not increase (line 2 has the same)"));
}

TEST(Trajectory, IdsShareTimesButEachIncreases) {
  const std::string h = "t_s,id,e_m,n_m,u_m,lat_deg,lon_deg,h_m,sigma_e_m,sigma_n_m,sigma_u_m,n_stations,status\n";
  const TrajectoryFile f = ReadTrajectory(io::CsvTable::Parse(
      h + "0.0,a,1,2,3,45,8,500,,,,2,ok\n0.0,b,1,2,3,45,8,500,,,,2,ok\n0.1,a,1,2,3,45,8,500,,,,2,ok\n", "t.csv"));
  EXPECT_TRUE(f.has_id);
  EXPECT_EQ(f.rows[1].id, "b");
  EXPECT_THAT(TrajectoryError(h + "0.0,a,1,2,3,45,8,500,,,,2,ok\n0.0,a,1,2,3,45,8,500,,,,2,ok\n"),
              HasSubstr("time of 'a' does not increase"));
}

TEST(LocatedPositions, ReadsWgs84AndRefusesAFileWithout) {
  const std::string text =
      "t_s,az_deg,el_deg,range_m,e_m,n_m,u_m,status,sigma_az_deg,sigma_el_deg,sigma_range_m,sigma_e_m,sigma_n_m,"
      "sigma_u_m,lat_deg,lon_deg,h_m\n"
      "0.0,10,5,1000,173.6,984.8,87.2,ok,0.001,0.001,1,0.5,0.6,0.7,47.01,8.002,487.2\n"
      "0.1,10,5,,,,,ok,0.001,0.001,,,,,,,\n";
  const LocatedFile f = ReadLocated(io::CsvTable::Parse(text, "loc.csv"), LocatedRead::kPositions);
  ASSERT_EQ(f.rows.size(), 2u);
  ASSERT_TRUE(f.rows[0].geodetic.has_value());
  EXPECT_DOUBLE_EQ(f.rows[0].geodetic->lon_deg, 8.002);
  ASSERT_TRUE(f.rows[0].sigma_enu_m.has_value());
  EXPECT_DOUBLE_EQ((*f.rows[0].sigma_enu_m)(1), 0.6);
  EXPECT_FALSE(f.rows[1].geodetic.has_value());  // no range: no position
  // Lines of sight only (rk-intersect's read) ignores the positions.
  EXPECT_FALSE(ReadLocated(io::CsvTable::Parse(text, "loc.csv")).rows[0].geodetic.has_value());
  try {
    ReadLocated(io::CsvTable::Parse("t_s,az_deg,el_deg,status\n0,1,2,ok\n", "noloc.csv"), LocatedRead::kPositions);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_THAT(e.what(), HasSubstr("noloc.csv:1:1: no WGS-84 columns lat_deg, lon_deg, h_m"));
  }
}

}  // namespace
}  // namespace rk::formats

// The one reader of each shared format: image points (the three consumers' former rules in one), the
// located target (writer and reader agree), stations.json (writer and reader agree).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "formats/image_points.h"
#include "formats/located.h"
#include "formats/stations.h"
#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"

namespace rk::formats {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::string& text) {
  try {
    ReadImagePoints(io::CsvTable::Parse(text, "p.csv"));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ImagePoints, GroupsRowsIntoFramesWithStatusAndSigma) {
  const ImagePoints f = ReadImagePoints(io::CsvTable::Parse(
      "frame,t_s,id,x_px,y_px,status,sigma_px,sigma_x_px,sigma_y_px\n"
      "0,0.0,nose,1,2,ok,0.3,,\n"
      "0,0.0,tail1,3,4,predicted,,0.1,0.2\n"
      "1,0.1,nose,,,lost,,,\n"
      "1,0.1,tail1,5,6,reacquired,,,\n",
      "p.csv"));
  ASSERT_EQ(f.frames.size(), 2u);
  EXPECT_TRUE(f.has_frame);
  EXPECT_EQ(f.rows, 4u);
  const ImagePoint& nose = f.frames[0].points[0];
  EXPECT_TRUE(nose.measured());
  EXPECT_EQ(*nose.sigma_px, Eigen::Vector2d(0.3, 0.3));
  const ImagePoint& tail = f.frames[0].points[1];
  EXPECT_FALSE(tail.measured());  // a predicted position is not a measurement
  EXPECT_EQ(tail.status, RowStatus::kPredicted);
  EXPECT_EQ(*tail.sigma_px, Eigen::Vector2d(0.1, 0.2));
  EXPECT_FALSE(f.frames[1].points[0].px.has_value());
  EXPECT_TRUE(f.frames[1].points[1].measured());
  EXPECT_EQ(f.frames[1].line, 4u);
}

TEST(ImagePoints, WithoutFrameColumnEqualTimesMakeAFrame) {
  const ImagePoints f =
      ReadImagePoints(io::CsvTable::Parse("t_s,id,x_px,y_px\n0.0,a,1,2\n0.0,b,3,4\n0.1,a,1,2\n", "p.csv"));
  ASSERT_EQ(f.frames.size(), 2u);
  EXPECT_EQ(f.frames[0].points.size(), 2u);
  EXPECT_FALSE(f.frames[0].frame.has_value());
}

// Every check names file:line:col and says what is wrong, for all three consumers alike.
TEST(ImagePoints, ErrorsNameTheCell) {
  const std::string h = "frame,t_s,id,x_px,y_px,status,sigma_px\n";
  EXPECT_THAT(ErrorOf(h + "0,0,a,1,2,ok,\n0,0,a,1,2,ok,\n"), HasSubstr("p.csv:3:"));
  EXPECT_THAT(ErrorOf(h + "0,0,a,1,2,ok,\n0,0,a,1,2,ok,\n"), HasSubstr("given twice in one frame (also line 2)"));
  EXPECT_THAT(ErrorOf(h + "0,0,a,1,2,ok,\n1,0.1,a,1,2,ok,\n0,0.2,b,1,2,ok,\n"), HasSubstr("appears again (first at line 2)"));
  EXPECT_THAT(ErrorOf(h + "0,0,a,1,2,ok,\n0,0.1,b,1,2,ok,\n"), HasSubstr("p.csv:3:3: column 't_s': t_s 0.1 differs from 0 on line 2"));
  EXPECT_THAT(ErrorOf(h + "0,0,a,1,2,found,\n"), HasSubstr("unknown status 'found'"));
  EXPECT_THAT(ErrorOf(h + "0,0,a,1,2,ok,0\n"), HasSubstr("sigma_px must be > 0"));
  EXPECT_THAT(ErrorOf(h + "0,0,,1,2,ok,\n"), HasSubstr("empty point id"));
  EXPECT_THAT(ErrorOf(h + "-1,0,a,1,2,ok,\n"), HasSubstr("frame must be >= 0"));
  EXPECT_THAT(ErrorOf(h + "0,1,a,1,2,ok,\n1,0,a,1,2,ok,\n"), HasSubstr("p.csv:3:"));  // time backwards
  EXPECT_EQ(ErrorOf(h + "0,0,a,1,2,ok,\n1,0.1,a,1,2,ok,\n"), "");
}

TEST(ImagePoints, WriterHeaderIsReadBack) {
  io::CsvWriter w(ImagePointsColumns({"ncc"}));
  w.Add(std::int64_t{0}).Add(0.0, 3).Add("nose").Add(1.5, 3).Add(2.5, 3).Add("ok").Add(0.9, 2).EndRow();
  const ImagePoints f = ReadImagePoints(io::CsvTable::Parse(w.str(), "w.csv"));
  ASSERT_EQ(f.frames.size(), 1u);
  EXPECT_EQ(*f.frames[0].points[0].px, Eigen::Vector2d(1.5, 2.5));
}

// What rk-locate and rk-sim multistation write, rk-intersect reads back: angles across 0/360, σ, correlation,
// empty values on a lost row.
TEST(Located, WriterAndReaderAgree) {
  LocatedLayout layout;
  layout.frame = layout.locate_extras = layout.sigma_enu = layout.corr = layout.geodetic = true;
  LocatedWriter w(layout);
  LocatedRecord a;
  a.frame = 0;
  a.t_s = 1.25;
  a.az_rad = geo::DegToRad(359.999999);
  a.el_rad = geo::DegToRad(-0.5);
  a.range_m = 1234.5;
  a.enu_m = Eigen::Vector3d(1, 2, 3);
  a.range_status = "ok";
  a.sigma_az_rad = geo::DegToRad(0.001);
  a.sigma_el_rad = geo::DegToRad(0.002);
  a.sigma_range_m = 0.5;
  a.sigma_enu_m = Eigen::Vector3d(0.1, 0.2, 0.3);
  a.corr_az_el = -0.25;
  a.geodetic = geo::Geodetic{52.5, 13.25, 40.0};
  w.Add(a);
  LocatedRecord lost;
  lost.frame = 1;
  lost.t_s = 1.3;
  lost.status = RowStatus::kLost;
  w.Add(lost);
  const std::string text = w.csv().str();
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "frame,t_s,az_deg,el_deg,range_m,e_m,n_m,u_m,status,range_status,boresight_az_deg,boresight_el_deg,"
            "sigma_az_deg,sigma_el_deg,sigma_range_m,sigma_e_m,sigma_n_m,sigma_u_m,corr_az_el,lat_deg,lon_deg,h_m");
  const LocatedFile f = ReadLocated(io::CsvTable::Parse(text, "l.csv"));
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_TRUE(f.has_range);
  EXPECT_TRUE(f.has_sigma);
  const LocatedRecord& r = f.rows[0];
  EXPECT_TRUE(r.measured());
  EXPECT_NEAR(geo::RadToDeg(*r.az_rad), 359.999999, 1e-9);
  EXPECT_NEAR(geo::RadToDeg(*r.sigma_el_rad), 0.002, 1e-12);
  EXPECT_EQ(*r.corr_az_el, -0.25);
  EXPECT_EQ(*r.sigma_range_m, 0.5);
  EXPECT_FALSE(f.rows[1].measured());
  EXPECT_FALSE(f.rows[1].az_rad.has_value());
  EXPECT_EQ(f.rows[1].status, RowStatus::kLost);
}

TEST(Located, ReaderRefusesBadValuesAtTheirCell) {
  auto error = [](const std::string& text) -> std::string {
    try {
      ReadLocated(io::CsvTable::Parse(text, "l.csv"));
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  const std::string h = "t_s,az_deg,el_deg,sigma_az_deg,sigma_el_deg,corr_az_el,status\n";
  EXPECT_THAT(error(h + "0,1,2,0,0.1,,ok\n"), HasSubstr("l.csv:2:7: column 'sigma_az_deg': sigma_az_deg must be > 0"));
  EXPECT_THAT(error(h + "0,1,2,0.1,0.1,-1.5,ok\n"), HasSubstr("corr_az_el must be in [-1, 1]"));
  EXPECT_THAT(error(h + "0,1,2,0.1,0.1,,good\n"), HasSubstr("unknown status"));
  EXPECT_THAT(error(h + "0,1,2,0.1,0.1,,ok\n0,1,2,0.1,0.1,,ok\n"), HasSubstr("l.csv:3:"));
}

TEST(Stations, WriterAndReaderAgree) {
  StationsFile f;
  f.origin = {51.0, -1.5, 100.0};
  f.origin_given = true;
  f.stations.push_back({"east", {51.001, -1.49, 101.5}, "east/located.csv"});
  f.stations.push_back({"west", {51.002, -1.51, 99.0}, "/abs/west.csv"});
  const StationsFile g = ParseStations(StationsJson(f).dump(2), "/trial/stations.json");
  ASSERT_EQ(g.stations.size(), 2u);
  EXPECT_TRUE(g.origin_given);
  EXPECT_EQ(g.origin.lon_deg, -1.5);
  EXPECT_EQ(g.stations[0].name, "east");
  EXPECT_EQ(g.stations[0].position.h_m, 101.5);
  EXPECT_EQ(g.stations[0].located, "/trial/east/located.csv");  // relative to the file's folder
  EXPECT_EQ(g.stations[1].located, "/abs/west.csv");
  EXPECT_EQ(g.stations[1].line, 15u);  // the second station's object, as io::JsonPositions finds it
}

}  // namespace
}  // namespace rk::formats

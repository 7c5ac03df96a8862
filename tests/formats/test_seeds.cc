// The seeds file of rk-extract points (formats/seeds.h): rows, re-seeds, optional columns, and every refusal
// at its file:line:col.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "formats/seeds.h"
#include "io/csv.h"
#include "io/error.h"

namespace rk::formats {
namespace seeds_test {

using ::testing::HasSubstr;

std::string SeedsError(const std::string& text) {
  try {
    ReadSeeds(io::CsvTable::Parse(text, "seeds.csv"));
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    return e.what();
  }
  return "";
}

TEST(Seeds, ReadsRowsReseedsAndOptionalColumns) {
  const Seeds s = ReadSeeds(io::CsvTable::Parse(
      "id,frame,x_px,y_px,method,size_px,search_px\n"
      "q1,0,10.5,20.25,quadrant,30,\n"
      "c1,0,40,50,circle,,6\n"
      "q1,120,11,21,quadrant,,\n",
      "seeds.csv"));
  ASSERT_EQ(s.rows.size(), 3u);
  EXPECT_EQ(s.ids, (std::vector<std::string>{"q1", "c1"}));
  EXPECT_EQ(s.rows[0].method, PointMethod::kQuadrant);
  EXPECT_DOUBLE_EQ(*s.rows[0].size_px, 30.0);
  EXPECT_FALSE(s.rows[0].search_px);
  EXPECT_EQ(s.rows[1].method, PointMethod::kCircle);
  EXPECT_DOUBLE_EQ(*s.rows[1].search_px, 6.0);
  EXPECT_EQ(s.rows[2].frame, 120);
  EXPECT_EQ(s.rows[2].line, 4u);
  for (const char* m : {"correlation", "centroid-dark", "centroid-bright", "quadrant", "circle"}) {
    EXPECT_STREQ(PointMethodName(*ParsePointMethod(m)), m);
  }
  // Without the optional columns.
  EXPECT_EQ(ReadSeeds(io::CsvTable::Parse("id,frame,x_px,y_px,method\na,3,1,2,centroid-dark\n", "s")).rows[0].frame, 3);
}

TEST(Seeds, RefusesEachBadRowAtItsLineAndColumn) {
  EXPECT_THAT(SeedsError("id,frame,x_px,y_px,method\nq1,0,1,2,blob\n"),
              HasSubstr("seeds.csv:2:10: column 'method': unknown method 'blob' (one of correlation, centroid-dark, centroid-bright, "
                        "quadrant or circle)"));
  EXPECT_THAT(SeedsError("id,frame,x_px,y_px,method\nq1,0,1,2,quadrant\nq1,0,3,4,quadrant\n"),
              HasSubstr("seeds.csv:3:1: column 'id': point 'q1' is seeded twice at frame 0 (first on line 2)"));
  EXPECT_THAT(SeedsError("id,frame,x_px,y_px,method\nq1,0,1,2,quadrant\nq1,5,3,4,circle\n"),
              HasSubstr("seeds.csv:3:10: column 'method': point 'q1' was seeded with method quadrant on line 2"));
  EXPECT_THAT(SeedsError("id,frame,x_px,y_px,method\n,0,1,2,quadrant\n"), HasSubstr("seeds.csv:2:1: column 'id': empty point id"));
  EXPECT_THAT(SeedsError("id,frame,x_px,y_px,method\nq,-1,1,2,quadrant\n"), HasSubstr("seeds.csv:2:3: column 'frame': frame must be >= 0"));
  EXPECT_THAT(SeedsError("id,frame,x_px,y_px,method\nq,0,x,2,quadrant\n"), HasSubstr("seeds.csv:2:5:"));
  EXPECT_THAT(SeedsError("id,frame,x_px,y_px,method,size_px\nq,0,1,2,quadrant,0\n"),
              HasSubstr("seeds.csv:2:18: column 'size_px': size_px must be > 0"));
  EXPECT_THAT(SeedsError("id,frame,x_px,method\nq,0,1,quadrant\n"), HasSubstr("y_px"));
  EXPECT_THAT(SeedsError("id,frame,x_px,y_px,method\n"), HasSubstr("no seeds"));
}

}  // namespace seeds_test
}  // namespace rk::formats

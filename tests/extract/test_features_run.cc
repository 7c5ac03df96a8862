// rk-extract features' output (extract/features_run.h): the long-format points CSV.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "extract/features_run.h"
#include "target/feature_model.h"
#include "test_default_model.h"

namespace rk::extract {
namespace {

TEST(FeaturePointsCsv, LongFormatOneRowPerFrameAndId) {
  target::FeatureModel model = DefaultModel();
  FeatureFrameResult r;
  r.frame = 7;
  r.t_s = 1.25;
  r.points.assign(model.size(), FeaturePoint{});
  r.points[1].has_xy = true;
  r.points[1].px = {100.25, 200.5};
  r.points[1].status = RowStatus::kOk;
  r.points[1].sigma_px = 0.01;
  r.points[1].ncc = 0.99;
  r.points[1].radius_px = 15.5;
  const std::string csv = FeaturePointsCsv({r}, model).str();
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "frame,t_s,id,x_px,y_px,status,sigma_px,ncc,radius_px");
  EXPECT_NE(csv.find("\n7,1.250000000,belly,,,lost,,,\n"), std::string::npos);
  EXPECT_NE(csv.find("\n7,1.250000000,canopy,100.2500,200.5000,ok,0.01000,0.9900,15.500\n"), std::string::npos);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 9);
}

}  // namespace
}  // namespace rk::extract

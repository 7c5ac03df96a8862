// The one smoothed-series writer of rk-smooth aukf, singer and resample: column order and names, angles in
// degrees wrapped as their input column is (across 0/360 and ±180), empty fields, copied columns.
#include <gtest/gtest.h>

#include <string>

#include "filter/smoothed_series.h"
#include "geo/angles.h"

namespace rk::filter {
namespace {

Series TwoColumns() {
  Series s;
  s.columns = {"az_deg", "range_m"};
  s.is_angle = {true, false};
  s.t_s = {0.0, 1.0};
  s.values = Eigen::MatrixXd(2, 2);
  s.values << geo::DegToRad(359.0), 10.0, geo::DegToRad(1.0), 11.0;
  return s;
}

TEST(SmoothedSeriesWriter, ColumnsUnitsAndEmptyFields) {
  const Series s = TwoColumns();
  SmoothedColumns c;
  c.derivatives = true;
  c.sigma_orders = 3;
  SmoothedSeriesWriter w(s, c, 3);
  w.Set(0, geo::DegToRad(360.5), geo::DegToRad(2.0), geo::DegToRad(-1.0));  // wraps to 0.5 (azimuth: [0, 360))
  w.SetSigma(0, 0, geo::DegToRad(0.25));
  w.Set(1, 12.0);                                                            // no rate, accel, σ: empty
  w.Write(0.5, "smoothed", "ok");
  w.Write(1.0, "estimate", "lost");                                          // nothing set: every value empty
  EXPECT_EQ(w.csv().str(),
            "t_s,kind,az_deg,range_m,status,az_rate_deg_s,az_accel_deg_s2,range_rate_m_s,range_accel_m_s2,"
            "az_sigma_deg,az_rate_sigma_deg_s,az_accel_sigma_deg_s2,range_sigma_m,range_rate_sigma_m_s,"
            "range_accel_sigma_m_s2\n"
            "0.500,smoothed,0.500,12.000,ok,2.000,-1.000,,,0.250,,,,,\n"
            "1.000,estimate,,,lost,,,,,,,,,,\n");
}

TEST(SmoothedSeriesWriter, CopiedColumnsAndReason) {
  Series s = TwoColumns();
  s.columns = {"el_deg", "range_m"};  // an elevation whose input stays within ±180°: (−180, 180]
  s.values << 0.1, 10.0, 0.2, 11.0;
  SmoothedColumns c;
  c.copied = {"frame"};
  c.reason = true;
  SmoothedSeriesWriter w(s, c, 2);
  const std::vector<std::string_view> cells = {"7"};
  w.Set(0, geo::DegToRad(-190.0));
  w.Write(2.0, "estimate", "invalid", "outside", &cells);
  EXPECT_EQ(w.csv().str(), "t_s,frame,kind,el_deg,range_m,status,reason\n2.00,7,estimate,170.00,,invalid,outside\n");
}

}  // namespace
}  // namespace rk::filter

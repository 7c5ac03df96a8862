// Reading plots + nav (input.h): step pairing by time, nav interpolation (wrap-safe), and every
// kind of bad input named by file, line and column (SPEC.md §4, exit 3).
#include <gtest/gtest.h>

#include <string>

#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "registration/input.h"

namespace rk::registration {
namespace {

constexpr double kInterpTol = 1e-9;  // linear interpolation of exactly linear nav
double DegToRadForTest(double d) { return geo::DegToRad(d); }

const char* kNav =
    "t_s,radar,lat_deg,lon_deg,h_m,yaw_deg,pitch_deg,roll_deg\n"
    "0,b,25.1,110.1,20000,350,1,2\n"
    "0,a,25.0,110.0,40000,10,3,4\n"
    "# comment\n"
    "10,a,25.2,110.2,40100,20,5,6\n"
    "10,b,25.3,110.3,20100,10,3,4\n";

RegistrationInput Read(const std::string& plots, const std::string& nav = kNav, InputOptions opt = {}) {
  return ReadRegistrationInput(io::CsvTable::Parse(plots, "plots.csv"), io::CsvTable::Parse(nav, "nav.csv"), opt);
}

// Expects a DataError (exit 3) whose message starts with `where` and contains `what`.
void ExpectDataError(const std::string& plots, const std::string& nav, const std::string& where,
                     const std::string& what, InputOptions opt = {}) {
  try {
    Read(plots, nav, opt);
    FAIL() << "no error; expected " << where;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(where, 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

TEST(RegistrationInput, PairsScansByTimeAndInterpolatesNav) {
  const RegistrationInput in = Read(
      "t_s,radar,range_m,az_deg,el_deg,track_id\n"
      "5.0,a,1000,10,1,1\n"
      "5.0,a,2000,20,2,\n"
      "5.2,b,3000,30,3,1\n"   // radar b 0.2 s later: same step
      "10.0,a,4000,40,4,2\n");
  EXPECT_EQ(in.radars[0], "a");  // sorted names
  EXPECT_EQ(in.radars[1], "b");
  ASSERT_EQ(in.steps.size(), 2u);
  EXPECT_EQ(in.steps[0].plots[0].size(), 2u);
  EXPECT_EQ(in.steps[0].plots[1].size(), 1u);
  EXPECT_DOUBLE_EQ(in.steps[0].t_s, 5.2);
  EXPECT_DOUBLE_EQ(in.steps[0].t_first_s, 5.0);
  EXPECT_FALSE(in.steps[1].HasBothRadars());
  EXPECT_EQ(in.summary.steps_one_radar, 1u);
  EXPECT_EQ(in.summary.clutter_plots, 1u);
  EXPECT_NEAR(in.summary.max_pair_offset_s, 0.2, 1e-12);
  ASSERT_TRUE(in.has_track_id);
  EXPECT_EQ(in.track_ids.size(), 2u);
  EXPECT_EQ(in.steps[0].plots[0][1].track, -1);
  EXPECT_EQ(in.steps[0].plots[0][0].track, in.steps[0].plots[1][0].track);
  EXPECT_EQ(in.steps[0].plots[0][0].line, 2u);
  // Nav of a at 5 s: halfway.
  const PlatformPose& pa = in.steps[0].plots[0][0].pose;
  EXPECT_NEAR(geo::RadToDeg(pa.lat_rad), 25.1, kInterpTol);
  EXPECT_NEAR(pa.h_m, 40050, 1e-6);
  EXPECT_NEAR(geo::RadToDeg(pa.yaw_rad), 15, kInterpTol);
  // Nav of b at 5.2 s: yaw 350 → 10 goes through north (20° in 10 s), not backwards through 180.
  const PlatformPose& pb = in.steps[0].plots[1][0].pose;
  EXPECT_NEAR(geo::WrapDeg360(geo::RadToDeg(pb.yaw_rad)), 0.4, kInterpTol);
  EXPECT_NEAR(geo::RadToDeg(in.steps[0].plots[1][0].meas.az_rad), 30, 1e-12);
}

// A nav writer keeping pitch within ±90° switches to (ϑ + 180°, 180° − ϕ, α + 180°) when the pitch
// passes 90°: the reader converts back to the continuous triple (the bias is additive there).
TEST(RegistrationInput, UnfoldsPitchFoldedIntoPlusMinus90) {
  const std::string nav =
      "t_s,radar,lat_deg,lon_deg,h_m,yaw_deg,pitch_deg,roll_deg\n"
      "0,a,25,110,1000,10,85,5\n"
      "0,b,25,110,1000,0,0,0\n"
      "10,a,25,110,1000,190.2,85,185.2\n"  // continuous: 10.2, 95, 5.2
      "10,b,25,110,1000,0,0,0\n";
  const RegistrationInput in = Read("t_s,radar,range_m,az_deg,el_deg\n5,a,1,0,0\n5,b,1,0,0\n", nav);
  const PlatformPose& p = in.steps[0].plots[0][0].pose;
  EXPECT_NEAR(geo::RadToDeg(p.pitch_rad), 90.0, kInterpTol);
  EXPECT_NEAR(geo::RadToDeg(p.yaw_rad), 10.1, kInterpTol);
  EXPECT_NEAR(geo::RadToDeg(p.roll_rad), 5.1, kInterpTol);
  EXPECT_EQ(in.summary.nav_unfolded_rows[0], 1u);
  EXPECT_EQ(in.summary.nav_unfolded_rows[1], 0u);
  // The two triples are one rotation.
  const double y = DegToRadForTest(190.2), pi = DegToRadForTest(85), r = DegToRadForTest(185.2);
  EXPECT_LT((RotationEnuFromPlatform(y, pi, r) -
             RotationEnuFromPlatform(DegToRadForTest(10.2), DegToRadForTest(95), DegToRadForTest(5.2)))
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
}

TEST(RegistrationInput, ZeroToleranceSeparatesRadarsWithDifferentTimes) {
  InputOptions opt;
  opt.pair_tol_s = 0.0;
  const RegistrationInput in = Read("t_s,radar,range_m,az_deg,el_deg\n5,a,1,0,0\n5.2,b,1,0,0\n", kNav, opt);
  EXPECT_EQ(in.steps.size(), 2u);
  EXPECT_FALSE(in.has_track_id);
}

TEST(RegistrationInput, PlotOutsideNav) {
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,0,0\n10.5,b,1000,0,0\n", kNav, "plots.csv:3:1:",
                  "no nav of radar 'b' at t_s = 10.5");
}

TEST(RegistrationInput, UnknownRadar) {
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,0,0\n5,c,1000,0,0\n", kNav, "plots.csv:3:",
                  "unknown radar 'c'");
}

TEST(RegistrationInput, OneRadarMissing) {
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,0,0\n6,a,1000,0,0\n", kNav, "plots.csv:",
                  "no plots of radar 'b'");
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,0,0\n",
                  "t_s,radar,lat_deg,lon_deg,h_m,yaw_deg,pitch_deg,roll_deg\n0,a,0,0,0,0,0,0\n9,a,0,0,0,0,0,0\n",
                  "nav.csv:", "one radar only");
}

TEST(RegistrationInput, ThirdRadarInNav) {
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,0,0\n",
                  std::string(kNav) + "11,c,0,0,0,0,0,0\n", "nav.csv:7:", "a third radar 'c'");
}

TEST(RegistrationInput, NaNAndEmptyValues) {
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,nan,0\n5,b,1,0,0\n", kNav, "plots.csv:2:10:",
                  "not a finite number");
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,,1\n", kNav, "plots.csv:2:", "empty value");
  // An empty el_deg is a 2-D plot (test_two_d.cc); text there is still an error at its cell.
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,1,abc\n", kNav, "plots.csv:2:12:", "not a number");
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,1,2\n",
                  "t_s,radar,lat_deg,lon_deg,h_m,yaw_deg,pitch_deg,roll_deg\n0,a,0,0,0,NaN,0,0\n", "nav.csv:2:",
                  "not a finite number");
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,-1,1,2\n", kNav, "plots.csv:2:", "range must be > 0");
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,10,1,91\n", kNav, "plots.csv:2:", "elevation outside");
}

// SPEC.md §2.1: an empty el_deg is a 2-D radar's plot; rk-import asterix's extra columns are ignored. A radar is
// 2-D when all its plots lack el_deg; a radar with some is not (its other plots carry the el bias).
TEST(RegistrationInput, EmptyElevationIsATwoDPlotAndAsterixColumnsAreIgnored) {
  const RegistrationInput in = Read(
      "t_s,radar,range_m,az_deg,el_deg,sac,sic,flight_level,height_m,mode3a,address,el_source\n"
      "5,a,1000,10,,25,10,350,,1234,3C6586,\n"
      "5,b,2000,20,,25,11,,,,,\n"
      "6,a,1000,11,2,25,10,350,10668,1234,3C6586,mode_c\n"
      "6,b,2000,21,,25,11,,,,,\n");
  EXPECT_FALSE(in.two_d[0]);  // mixed: one plot with el_deg
  EXPECT_TRUE(in.two_d[1]);
  EXPECT_EQ(in.summary.plots_without_el[0], 1u);
  EXPECT_EQ(in.summary.plots_without_el[1], 2u);
  ASSERT_EQ(in.steps.size(), 2u);
  EXPECT_FALSE(in.steps[0].plots[0][0].meas.has_el);
  EXPECT_TRUE(in.steps[1].plots[0][0].meas.has_el);
  EXPECT_NEAR(in.steps[1].plots[0][0].meas.el_rad, DegToRadForTest(2), kInterpTol);
  EXPECT_FALSE(in.steps[1].plots[1][0].meas.has_el);
  EXPECT_EQ(in.summary.ToJson(in.radars)["plots_without_el"]["b"], 2);
  // Without 2-D plots the report's input block has no plots_without_el (a 3-D trial's report is unchanged).
  const RegistrationInput in3 = Read("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,10,1\n5,b,2000,20,2\n");
  EXPECT_FALSE(in3.two_d[0] || in3.two_d[1]);
  EXPECT_FALSE(in3.summary.ToJson(in3.radars).contains("plots_without_el"));
}

TEST(RegistrationInput, TimesOutOfOrder) {
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,0,0\n4,b,1000,0,0\n", kNav, "plots.csv:3:1:",
                  "goes backwards");
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,0,0\n",
                  "t_s,radar,lat_deg,lon_deg,h_m,yaw_deg,pitch_deg,roll_deg\n0,a,0,0,0,0,0,0\n0,a,0,0,0,0,0,0\n",
                  "nav.csv:3:1:", "repeats the time");
}

TEST(RegistrationInput, TrackIdRequired) {
  InputOptions opt;
  opt.require_track_id = true;
  ExpectDataError("t_s,radar,range_m,az_deg,el_deg\n5,a,1000,0,0\n5,b,1000,0,0\n", kNav, "plots.csv:1:",
                  "missing column 'track_id'", opt);
}

TEST(RegistrationInput, MissingColumn) {
  ExpectDataError("t_s,radar,range_m,az_deg\n5,a,1000,0\n", kNav, "plots.csv:1:", "missing column 'el_deg'");
}

}  // namespace
}  // namespace rk::registration

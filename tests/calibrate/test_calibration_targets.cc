// The calibration targets' forward model (target/calibration_targets.h): landmarks through GeographicLib,
// stars through ERFA. (Here rather than in tests/target so the pointing tests and these build as one.)
#include <gtest/gtest.h>

#include <cstdio>

#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "target/calibration_targets.h"

namespace rk::target {
namespace {

// eraAtoc13 inverts eraAtco13 to < 1 mas above 15° elevation; lower, its inverse refraction is approximate
// (53 mas at 5°). The simulator only uses the inverse to place stars, the forward model decides the truth.
constexpr double kRoundTripMas = 1.0, kRoundTripLowMas = 100.0;
constexpr double kCurvatureTolM = 1e-3;     // 1 km north on the ellipsoid drops by ≈ 0.078 m

TEST(CalibrationTargets, StarObservedPlaceInvertsCatalogue) {
  const Geodetic station{32.5, -106.6, 1300.0};
  const UtcJd utc = ParseUtc("2026-03-20T03:00:00Z", "test");
  const Atmosphere atm;
  for (double el_deg : {5.0, 30.0, 75.0}) {
    for (double az_deg : {10.0, 200.0}) {
      const ObservedPlace want{geo::DegToRad(az_deg), geo::DegToRad(el_deg)};
      const Star star = StarFromObservedPlace("s", want, station, utc, 0.0, atm);
      const ObservedPlace got = StarObservedPlace(star, station, utc, 0.0, atm);
      const double mas = geo::kArcsecPerRad * 1e3;
      const double tol = el_deg < 15.0 ? kRoundTripLowMas : kRoundTripMas;
      EXPECT_LT(std::abs(geo::WrapPi(got.az_rad - want.az_rad)) * std::cos(want.el_rad) * mas, tol);
      EXPECT_LT(std::abs(got.el_rad - want.el_rad) * mas, tol);
    }
  }
}

TEST(CalibrationTargets, RefractionRaisesALowStar) {
  const Geodetic station{32.5, -106.6, 1300.0};
  const UtcJd utc = ParseUtc("2026-03-20T03:00:00.5Z", "test");
  Atmosphere atm;
  const Star star = StarFromObservedPlace("s", {1.0, geo::DegToRad(10.0)}, station, utc, 0.0, atm);
  atm.pressure_hpa = 0.0;  // no air
  const ObservedPlace vacuum = StarObservedPlace(star, station, utc, 0.0, atm);
  // Refraction at 10° elevation, 1013 hPa, 10 °C: ≈ 5.4′ (Bennett) in visible light, ≈ 1.5 % less at 0.85 µm.
  EXPECT_NEAR(geo::RadToDeg(geo::DegToRad(10.0) - vacuum.el_rad) * 60.0, 5.3, 0.3);
}

TEST(CalibrationTargets, StarsMoveWithTheSky) {
  const Geodetic station{32.5, -106.6, 1300.0};
  const UtcJd utc = ParseUtc("2026-03-20T03:00:00Z", "test");
  const Star star = StarFromObservedPlace("s", {geo::DegToRad(90.0), geo::DegToRad(30.0)}, station, utc, 0.0, {});
  const ObservedPlace later = StarObservedPlace(star, station, utc.Plus(60.0), 0.0, {});
  // A star in the east rises: 15″/s × cos(latitude) × ... ≈ 0.1–0.25°/min.
  EXPECT_GT(geo::RadToDeg(later.el_rad) - 30.0, 0.05);
}

TEST(CalibrationTargets, LandmarkOneKilometreNorthDropsWithTheEarth) {
  const Geodetic station{45.0, 7.0, 200.0};
  const io::CsvTable t = io::CsvTable::Parse("id,e_m,n_m,u_m\nA,0,1000,5\n", "lm.csv");
  const std::vector<Landmark> enu = ReadLandmarks(t, station);
  ASSERT_EQ(enu.size(), 1u);
  EXPECT_NEAR(enu[0].p_enu.y(), 1000.0, 1e-9);
  // The same point given by latitude and longitude at the station's height: the earth curves away below it.
  const Geodetic g = geo::LocalEnu(station).ToGeodetic(Eigen::Vector3d(0, 1000, 0));
  char row[128];
  std::snprintf(row, sizeof row, "id,lat_deg,lon_deg,h_m\nA,%.12f,%.12f,200\n", g.lat_deg, g.lon_deg);
  const std::vector<Landmark> wgs = ReadLandmarks(io::CsvTable::Parse(row, "lm.csv"), station);
  ASSERT_EQ(wgs.size(), 1u);
  const Eigen::Vector3d back = wgs[0].p_enu;
  EXPECT_NEAR(back.y(), 1000.0, 1e-3);
  EXPECT_NEAR(back.z(), -1000.0 * 1000.0 / (2 * 6.3781e6), kCurvatureTolM * 20);
}

TEST(CalibrationTargets, BadFilesNameTheCell) {
  const Geodetic station{17.2, 11.5, 0.0};
  try {
    ReadStars(io::CsvTable::Parse("id,ra_deg,dec_deg\nA,10,95\n", "stars.csv"));
    FAIL();
  } catch (const rk::Error& e) {
    EXPECT_NE(std::string(e.what()).find("stars.csv:2:6"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadLandmarks(io::CsvTable::Parse("id,x\nA,1\n", "l.csv"), station), rk::Error);
  EXPECT_THROW(ReadLandmarks(io::CsvTable::Parse("id,e_m,n_m,u_m\nA,1,2,3\nA,4,5,6\n", "l.csv"), station), rk::Error);
  EXPECT_THROW(ParseUtc("2026-13-01T00:00:00Z", "--epoch-utc"), rk::Error);
  EXPECT_THROW(ReadLandmarks(io::CsvTable::Parse("id,lat_deg,lon_deg,h_m\nA,91,0,0\n", "l.csv"), station), rk::Error);
}

}  // namespace
}  // namespace rk::target

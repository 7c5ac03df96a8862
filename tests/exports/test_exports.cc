// rk-export's writers (lib/exports): which rows are placed and how runs split, the sample marks, and the KML and
// CZML documents: coordinates equal the file's WGS-84 columns to 1e-7 degrees (issue 34), times from the epoch,
// the CZML packet structure of its specification. The KML schema validation is the CLI test's (xmllint).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "exports/czml.h"
#include "exports/geo_track.h"
#include "exports/kml.h"
#include "formats/located.h"
#include "formats/trajectory.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/utc_time.h"
#include "rk_test/temp_dir.h"

namespace rk::exports {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// The target: coordinates equal the trajectory's WGS-84 columns to 1e-7°.
constexpr double kDegTolerance = 1e-7;
// Heights are written to the micrometre.
constexpr double kHeightTolerance = 1e-6;

const char* const kHeader = "t_s,e_m,n_m,u_m,lat_deg,lon_deg,h_m,sigma_e_m,sigma_n_m,sigma_u_m,n_stations,status\n";

// Rows at 10 Hz: ok ×3, lost, ok ×2 (one predicted), invalid, ok; longitudes across a few 1e-9°.
std::string SampleTrajectory() {
  return std::string(kHeader) +
         "0.0,1,2,3,47.123456789,8.987654321,500.123,0.1,0.2,0.3,3,ok\n"
         "0.1,1,2,3,47.123456799,8.987654331,501.456,0.1,0.2,0.3,3,ok\n"
         "0.2,1,2,3,47.123456809,8.987654341,502.789,0.1,0.2,0.3,2,reacquired\n"
         "0.3,,,,,,,,,,1,lost\n"
         "0.4,1,2,3,47.123456829,8.987654361,504.000,0.1,0.2,0.3,3,ok\n"
         "0.5,1,2,3,47.123456839,-179.999999999,505.000,0.1,0.2,0.3,3,predicted\n"
         "0.6,,,,,,,,,,3,invalid\n"
         "0.7,1,2,3,-47.5,190.25,506.000,0.1,0.2,0.3,3,ok\n";
}

GeoTrack Track(const std::string& text) {
  return FromTrajectory(formats::ReadTrajectory(io::CsvTable::Parse(text, "traj.csv")));
}

TEST(GeoTrack, PlacesRowsWithValuesAndSplitsRunsAtTheOthers) {
  const GeoTrack t = Track(SampleTrajectory());
  ASSERT_EQ(t.paths.size(), 1u);
  const GeoPath& p = t.paths[0];
  EXPECT_EQ(t.rows, 8u);
  EXPECT_EQ(t.placed, 6u);
  EXPECT_EQ(p.samples.size(), 6u);
  ASSERT_EQ(p.runs.size(), 3u);
  EXPECT_EQ(p.runs[0], (std::pair<std::size_t, std::size_t>{0, 3}));
  EXPECT_EQ(p.runs[1], (std::pair<std::size_t, std::size_t>{3, 5}));
  EXPECT_EQ(p.runs[2], (std::pair<std::size_t, std::size_t>{5, 6}));
  EXPECT_EQ(p.samples[2].status, RowStatus::kReacquired);
  EXPECT_EQ(p.samples[4].status, RowStatus::kPredicted);
  EXPECT_NEAR(p.samples[5].wgs84.lon_deg, -169.75, 1e-12);  // 190.25 brought to [-180, 180)
  EXPECT_EQ(t.rows_by_status[static_cast<std::size_t>(RowStatus::kLost)], 1u);
  const io::RunSummary s = t.Summary();
  ASSERT_EQ(s.headline.size(), 1u);
  EXPECT_NEAR(s.headline[0].value, 6.0 / 8.0, 1e-12);
}

TEST(GeoTrack, IdsAreSeparatePaths) {
  const std::string h = "t_s,id,e_m,n_m,u_m,lat_deg,lon_deg,h_m,sigma_e_m,sigma_n_m,sigma_u_m,n_stations,status\n";
  const GeoTrack t = Track(h + "0.0,nose,1,2,3,45,8,500,,,,2,ok\n0.0,tail,1,2,3,46,9,600,,,,2,ok\n"
                               "0.1,nose,,,,,,,,,,1,lost\n0.1,tail,1,2,3,46.1,9.1,601,,,,2,ok\n"
                               "0.2,nose,1,2,3,45.2,8.2,502,,,,2,ok\n");
  ASSERT_EQ(t.paths.size(), 2u);
  EXPECT_EQ(t.paths[0].id, "nose");
  EXPECT_EQ(t.paths[0].runs.size(), 2u);  // the lost row splits nose, not tail
  EXPECT_EQ(t.paths[1].id, "tail");
  EXPECT_EQ(t.paths[1].runs.size(), 1u);
}

TEST(GeoTrack, NothingPlacedIsAProcessingFailure) {
  test::TempDir dir("exports");
  test::WriteFile(dir / "lost.csv", std::string(kHeader) + "0.0,,,,,,,,,,1,lost\n0.1,,,,,,,,,,0,invalid\n");
  try {
    ReadGeoTrack(dir / "lost.csv", InputKind::kTrajectory, io::BadRows::kError);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kProcessing);
    EXPECT_THAT(e.what(), HasSubstr("lost.csv: no row has a position to export (2 rows, 1 lost, 1 invalid)"));
  }
}

TEST(GeoTrack, LocatedTargetWithoutRangeRowsIsPlacedWhereItHasPositions) {
  const std::string text =
      "t_s,az_deg,el_deg,range_m,e_m,n_m,u_m,status,sigma_az_deg,sigma_el_deg,sigma_range_m,sigma_e_m,sigma_n_m,"
      "sigma_u_m,lat_deg,lon_deg,h_m\n"
      "0.0,10,5,1000,173.6,984.8,87.2,ok,0.001,0.001,1,0.5,0.6,0.7,47.01,8.002,487.2\n"
      "0.1,10,5,,,,,ok,0.001,0.001,,,,,,,\n"
      "0.2,10,5,1000,173.6,984.8,87.2,ok,0.001,0.001,1,0.5,0.6,0.7,47.02,8.003,488.2\n";
  const GeoTrack t = FromLocated(formats::ReadLocated(io::CsvTable::Parse(text, "loc.csv"), formats::LocatedRead::kPositions));
  EXPECT_EQ(t.kind, InputKind::kLocated);
  EXPECT_EQ(t.placed, 2u);
  EXPECT_EQ(t.paths[0].runs.size(), 2u);  // the row without a range has no position: the line does not bridge it
}

TEST(SampleMarks, FirstAndLastOfEachRunAndEveryIntervalBetween) {
  const GeoTrack t = Track(SampleTrajectory());
  EXPECT_EQ(SampleMarks(t.paths[0], 0.0), (std::vector<std::size_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(SampleMarks(t.paths[0], 10.0), (std::vector<std::size_t>{0, 2, 3, 4, 5}));
  EXPECT_EQ(SampleMarks(t.paths[0], 0.15), (std::vector<std::size_t>{0, 2, 3, 4, 5}));
}

TEST(UtcText, FormatsAndRoundsTheWayAnIntervalNeeds) {
  io::UtcTime t;
  std::string why;
  ASSERT_TRUE(io::ParseUtcIso("2026-11-21T08:00:00Z", &t, &why));
  const double e = io::UnixSeconds(t);
  EXPECT_EQ(io::FormatUtcIso(e + 1.25, 3), "2026-11-21T08:00:01.250Z");
  EXPECT_EQ(io::FormatUtcIso(e + 86399.25, 6), "2026-11-22T07:59:59.250000Z");
  EXPECT_EQ(io::FormatUtcIso(e + 0.0000004, 6, io::Rounding::kUp), "2026-11-21T08:00:00.000001Z");
  EXPECT_EQ(io::FormatUtcIso(e + 0.0000004, 6, io::Rounding::kDown), "2026-11-21T08:00:00.000000Z");
  EXPECT_EQ(io::FormatUtcIso(951782400.0, 0), "2000-02-29T00:00:00Z");  // a leap day
  EXPECT_EQ(io::FormatUtcIso(-1.0, 0), "1969-12-31T23:59:59Z");
}

// lon,lat,alt triples of every <coordinates> element of `kml` in order (the LineStrings' and the Points').
std::vector<std::vector<std::array<double, 3>>> KmlCoordinates(const std::string& kml) {
  std::vector<std::vector<std::array<double, 3>>> out;
  const std::regex re("<coordinates>([^<]*)</coordinates>");
  for (auto it = std::sregex_iterator(kml.begin(), kml.end(), re); it != std::sregex_iterator(); ++it) {
    std::istringstream s((*it)[1].str());
    std::vector<std::array<double, 3>> triples;
    std::string tuple;
    while (s >> tuple) {
      std::array<double, 3> v{};
      char c1 = 0, c2 = 0;
      std::istringstream ts(tuple);
      ts >> v[0] >> c1 >> v[1] >> c2 >> v[2];
      triples.push_back(v);
    }
    out.push_back(triples);
  }
  return out;
}

TEST(Kml, LinesAndSamplesCarryTheFilesCoordinates) {
  const GeoTrack t = Track(SampleTrajectory());
  ExportHeader h;
  h.name = "trial 7";
  KmlOptions o;
  o.sample_interval_s = 0.0;
  o.geoid_undulation_m = 47.5;
  KmlCounts counts;
  const std::string kml = KmlText(t, h, o, &counts);
  EXPECT_EQ(counts.lines, 2u);       // the one-sample run has no line
  EXPECT_EQ(counts.placemarks, 6u);  // every row with interval 0
  EXPECT_EQ(kml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">", 0), 0u);
  EXPECT_THAT(kml, HasSubstr("<name>trial 7</name>"));
  EXPECT_THAT(kml, Not(HasSubstr("<TimeStamp>")));  // no epoch, no time stamps
  const auto coords = KmlCoordinates(kml);
  ASSERT_EQ(coords.size(), 2u + 6u);
  // Lines: samples 0-2 and 3-4; then the points 0..5.
  const GeoPath& p = t.paths[0];
  const std::vector<std::size_t> order = {0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 5};
  std::vector<std::array<double, 3>> flat;
  for (const auto& c : coords) flat.insert(flat.end(), c.begin(), c.end());
  ASSERT_EQ(flat.size(), order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const PathSample& s = p.samples[order[k]];
    EXPECT_NEAR(flat[k][0], s.wgs84.lon_deg, kDegTolerance) << k;
    EXPECT_NEAR(flat[k][1], s.wgs84.lat_deg, kDegTolerance) << k;
    EXPECT_NEAR(flat[k][2], s.wgs84.h_m - 47.5, kHeightTolerance) << k;
  }
  EXPECT_THAT(kml, HasSubstr("<SimpleData name=\"sigma_u_m\">0.3000</SimpleData>"));
  EXPECT_THAT(kml, HasSubstr("<SimpleData name=\"status\">predicted</SimpleData>"));
  EXPECT_THAT(kml, HasSubstr("<SimpleData name=\"h_ellipsoid_m\">505.000000</SimpleData>"));
}

TEST(Kml, EpochGivesTimeStampsAndSpansAndNamesAreEscaped) {
  const GeoTrack t = Track(SampleTrajectory());
  ExportHeader h;
  h.name = "a<b & \"c\"";
  h.epoch_text = "2026-11-21T08:00:00Z";
  h.epoch_unix_s = *io::ParseEpochOption(h.epoch_text);
  const std::string kml = KmlText(t, h, KmlOptions());
  EXPECT_THAT(kml, HasSubstr("<name>a&lt;b &amp; \"c\"</name>"));
  EXPECT_THAT(kml, HasSubstr("<TimeStamp><when>2026-11-21T08:00:00.500000Z</when></TimeStamp>"));
  EXPECT_THAT(kml, HasSubstr("<TimeSpan>"));
  EXPECT_THAT(kml, HasSubstr("<begin>2026-11-21T08:00:00.000000Z</begin>"));
  EXPECT_THAT(kml, HasSubstr("<end>2026-11-21T08:00:00.200000Z</end>"));
}

TEST(Czml, PacketsFollowTheSpecificationAndCarryTheFilesCoordinates) {
  const GeoTrack t = Track(SampleTrajectory());
  ExportHeader h;
  h.name = "trial 7";
  h.epoch_text = "2026-11-21T08:00:00Z";
  h.epoch_unix_s = *io::ParseEpochOption(h.epoch_text);
  const nlohmann::json doc = nlohmann::json::parse(CzmlText(t, h, CzmlOptions()));
  ASSERT_TRUE(doc.is_array());
  ASSERT_EQ(doc.size(), 2u);
  EXPECT_EQ(doc[0]["id"], "document");
  EXPECT_EQ(doc[0]["version"], "1.0");
  EXPECT_EQ(doc[0]["clock"]["interval"], "2026-11-21T08:00:00.000000Z/2026-11-21T08:00:00.700000Z");
  const nlohmann::json& p = doc[1];
  EXPECT_EQ(p["id"], "trajectory");
  EXPECT_EQ(p["availability"].size(), 3u);  // one interval per run
  EXPECT_EQ(p["position"]["epoch"], "2026-11-21T08:00:00.000000Z");
  const nlohmann::json& deg = p["position"]["cartographicDegrees"];
  const GeoPath& path = t.paths[0];
  ASSERT_EQ(deg.size(), 4 * path.samples.size());
  for (std::size_t k = 0; k < path.samples.size(); ++k) {
    EXPECT_NEAR(deg[4 * k].get<double>(), path.samples[k].t_s, 1e-9);
    EXPECT_NEAR(deg[4 * k + 1].get<double>(), path.samples[k].wgs84.lon_deg, kDegTolerance);
    EXPECT_NEAR(deg[4 * k + 2].get<double>(), path.samples[k].wgs84.lat_deg, kDegTolerance);
    EXPECT_NEAR(deg[4 * k + 3].get<double>(), path.samples[k].wgs84.h_m, kHeightTolerance);  // ellipsoidal, as is
  }
  EXPECT_EQ(p["properties"]["sigma_e_m"]["number"].size(), 2 * path.samples.size());
  EXPECT_EQ(p["properties"]["status"][0]["string"], "ok");
}

TEST(Czml, WithoutAnEpochTheStandInIsSaid) {
  const std::string czml = CzmlText(Track(SampleTrajectory()), ExportHeader(), CzmlOptions());
  const nlohmann::json doc = nlohmann::json::parse(czml);
  EXPECT_EQ(doc[1]["position"]["epoch"], "2000-01-01T00:00:00.000000Z");
  EXPECT_THAT(doc[0]["description"].get<std::string>(), HasSubstr("No epoch was given"));
}

}  // namespace
}  // namespace rk::exports

// Station clock offsets estimated with the trajectory (intersect/time_offsets.h) on rk-sim multistation trials
// with known offsets: recovered within their σ, honest σ where the geometry is poor (and the warning), none where
// it is not; awkward cases: offsets of tens of ms, different frame rates, a station that sees the target only part
// of the time, another time reference, point ids; the analytic Jacobians against numerical ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "formats/located.h"
#include "formats/stations.h"
#include "intersect/intersect.h"
#include "intersect/station_frames.h"
#include "intersect/time_offsets.h"
#include "io/csv.h"
#include "sim/multistation_scenario.h"

namespace rk::intersect {
namespace {

constexpr double kSigmas = 3.0;              // |error| ≤ 3σ (a fixed seed: a 0.3 % event per offset)
constexpr double kTurnSigmaMaxS = 5e-5;      // a climbing turn seen from 3–13 km at 2″, 20 Hz: σ ≈ 0.015 ms
constexpr double kDegenerateRatioMin = 3.0;  // the degenerate geometry's σ over the turn's

struct Trial {
  formats::StationsFile stations;
  std::vector<formats::LocatedFile> files;
  std::vector<double> truth;
};

sim::MultistationOptions Base() {
  sim::MultistationOptions o;
  o.baseline_km = 10.0;
  o.sigma_angle_arcsec = 2.0;
  o.duration_s = 30.0;
  o.seed = 11;
  o.path = sim::MultistationPath::kTurn;
  o.time_offsets = "s2:0.0043,s3:-0.0117";
  return o;
}

Trial Make(const sim::MultistationOptions& o) {
  const sim::MultistationScenario sim(o);
  Trial t;
  t.stations = formats::ParseStations(sim.StationsJson().dump(), "stations.json");
  for (std::size_t s = 0; s < sim.stations().size(); ++s) {
    t.files.push_back(formats::ReadLocated(io::CsvTable::Parse(sim.LocatedCsv(s).str(), sim.stations()[s].name)));
    t.truth.push_back(sim.stations()[s].time_offset_s);
  }
  return t;
}

TimeOffsetFit Estimate(const Trial& t, TimeOffsetOptions o = {}) {
  std::vector<StationTrack> tracks;
  OffsetTarget target;
  for (std::size_t s = 0; s < t.files.size(); ++s) {
    tracks.emplace_back(t.files[s], IntersectOptions{}.Defaults(), t.stations.stations[s].time_offset_s);
  }
  for (std::size_t s = 0; s < tracks.size(); ++s) {
    target.station.push_back(static_cast<int>(s));
    target.track.push_back(&tracks[s]);
  }
  return EstimateTimeOffsets(t.stations, {target}, o);
}

// Each offset against the reference's clock: truth[s] − truth[ref] + the reference's given offset.
void ExpectWithinSigma(const Trial& t, const TimeOffsetFit& f) {
  const std::size_t ref = f.reference;
  for (std::size_t s = 0; s < t.truth.size(); ++s) {
    if (s == ref) {
      EXPECT_EQ(f.sigma_s[s], 0.0);
      continue;
    }
    const double want = t.truth[s] - t.truth[ref] + t.stations.stations[ref].time_offset_s;
    EXPECT_LT(std::abs(f.offset_s[s] - want), kSigmas * f.sigma_s[s])
        << f.names[s] << ": " << f.offset_s[s] << " vs " << want << " ± " << f.sigma_s[s];
  }
}

TEST(TimeOffsets, AClimbingTurnGivesTheOffsetsToHundredthsOfAMillisecond) {
  const Trial t = Make(Base());
  const TimeOffsetFit f = Estimate(t);
  ExpectWithinSigma(t, f);
  EXPECT_LT(f.sigma_s[1], kTurnSigmaMaxS);
  EXPECT_LT(f.sigma_s[2], kTurnSigmaMaxS);
  EXPECT_TRUE(f.warnings.empty());
  EXPECT_GT(f.rms_arcsec_as_given, 5.0 * f.rms_arcsec_estimated);
}

TEST(TimeOffsets, JacobiansMatchNumericalOnes) {
  // A row of a station 9 km away (with a range, and without), the target moving 250 m/s inside its knot span,
  // at several positions in the span, across north (azimuth 0/360).
  constexpr double kMismatchMax = 1e-6;  // of the row's largest entry (central differences: ~1e-9 here)
  const geo::Geodetic origin{47.0, 8.0, 400.0};
  const StationFrame frame = MakeStationFrame(origin, {47.0, 8.01, 450.0});
  for (const double east : {-800.0, 750.0, 2000.0}) {
    Eigen::Vector3d c[4];
    for (int m = 0; m < 4; ++m) c[m] = Eigen::Vector3d(east + 60.0 * m, 9000.0 + 10.0 * m * m, 3000.0 + 5.0 * m);
    for (const bool range : {false, true}) {
      for (const double u : {0.1, 0.5, 0.93}) {
        LineObservation o;
        o.az_rad = 6.2;
        o.el_rad = 0.3;
        o.sigma_az_rad = o.sigma_el_rad = 1e-5;
        o.corr_az_el = 0.3;
        o.has_range = range;
        o.range_m = 9500.0;
        o.sigma_range_m = 1.0;
        const double mismatch = internal::RowJacobianMismatch(frame, o, 10.0 + u * 0.25, c, 0.0123, 10.0, 0.25);
        EXPECT_LT(mismatch, kMismatchMax) << "east " << east << " range " << range << " u " << u;
      }
    }
  }
}

TEST(TimeOffsets, StationsOnALineWithAPassAlongItGiveALargeHonestSigmaAndAWarning) {
  sim::MultistationOptions o = Base();
  const TimeOffsetFit turn = Estimate(Make(o));
  o.path = sim::MultistationPath::kCrossing;
  o.layout = sim::MultistationLayout::kLine;
  const Trial t = Make(o);
  const TimeOffsetFit f = Estimate(t);
  ExpectWithinSigma(t, f);
  EXPECT_GT(f.sigma_s[1], kDegenerateRatioMin * turn.sigma_s[1]);
  ASSERT_FALSE(f.warnings.empty());
  EXPECT_NE(f.warnings[0].find("poorly determined"), std::string::npos) << f.warnings[0];
}

TEST(TimeOffsets, AStraightPassSeenFromATriangleIsNotDegenerate) {
  sim::MultistationOptions o = Base();
  o.path = sim::MultistationPath::kCrossing;
  const Trial t = Make(o);
  const TimeOffsetFit f = Estimate(t);
  ExpectWithinSigma(t, f);
  EXPECT_TRUE(f.warnings.empty()) << f.warnings.front();
}

TEST(TimeOffsets, TensOfMillisecondsPartialViewAndAnotherReference) {
  // Offsets of several frame intervals, stations at 20/25/16 Hz, s3 sees the target only in the middle third,
  // s2 is the time reference with a given offset of its own.
  sim::MultistationOptions o = Base();
  o.time_offsets = "s2:0.037,s3:-0.052";
  Trial t = Make(o);
  auto& rows = t.files[2].rows;
  rows.erase(std::remove_if(rows.begin(), rows.end(), [](const formats::LocatedRecord& r) { return r.t_s < 10.0 || r.t_s > 20.0; }),
             rows.end());
  t.stations.stations[1].time_reference = true;
  t.stations.stations[1].time_offset_s = 0.037;
  const TimeOffsetFit f = Estimate(t);
  EXPECT_EQ(f.reference, 1u);
  EXPECT_EQ(f.offset_s[1], 0.037);
  ExpectWithinSigma(t, f);
  EXPECT_LT(f.rows[2], f.rows[0]);
}

TEST(TimeOffsets, PointIdsShareTheOffsets) {
  // Two point ids on the stations' clocks, one located file per station with an id column: the second id is the
  // same path seen with other noise (another seed). Both paths are fitted, the offsets shared: within their σ,
  // which is about 1/√2 of one id's.
  sim::MultistationOptions o = Base();
  const Trial t = Make(o);
  o.seed = 12;
  const Trial u = Make(o);
  std::vector<formats::LocatedFile> files;
  for (std::size_t s = 0; s < t.files.size(); ++s) {
    formats::LocatedFile g = t.files[s];
    g.has_id = true;
    g.rows.clear();
    for (std::size_t k = 0; k < t.files[s].rows.size() && k < u.files[s].rows.size(); ++k) {
      formats::LocatedRecord a = t.files[s].rows[k], b = u.files[s].rows[k];
      a.id = "nose";
      b.id = "tail";
      g.rows.push_back(a);
      g.rows.push_back(b);
    }
    files.push_back(g);
  }
  const TimeOffsetFit both = EstimateTimeOffsetsById(t.stations, files, IntersectOptions{}, {});
  const TimeOffsetFit one = Estimate(t);
  ExpectWithinSigma(t, both);
  EXPECT_NEAR(both.sigma_s[1] / one.sigma_s[1], 1.0 / std::sqrt(2.0), 0.15);
}

TEST(StationTrack, AClockSigmaGrowsTheAnglesSigmaByTheirRate) {
  const Trial t = Make(Base());
  StationTrack a(t.files[0], IntersectOptions{}.Defaults()), b(t.files[0], IntersectOptions{}.Defaults());
  constexpr double kClockSigmaS = 0.002;
  b.SetTimeSigma(kClockSigmaS);
  LineObservation oa, ob, o1, o2;
  const double tm = 0.5 * (t.files[0].rows[100].t_s + t.files[0].rows[101].t_s);
  ASSERT_TRUE(a.At(tm, &oa));
  ASSERT_TRUE(b.At(tm, &ob));
  ASSERT_TRUE(a.At(t.files[0].rows[100].t_s, &o1));
  ASSERT_TRUE(a.At(t.files[0].rows[101].t_s, &o2));
  const double dt = t.files[0].rows[101].t_s - t.files[0].rows[100].t_s;
  const double rate_el = (o2.el_rad - o1.el_rad) / dt;
  EXPECT_NEAR(ob.sigma_el_rad, std::hypot(oa.sigma_el_rad, rate_el * kClockSigmaS), 1e-12);
  EXPECT_GT(std::abs(ob.corr_az_el), std::abs(oa.corr_az_el));
  EXPECT_EQ(ob.el_rad, oa.el_rad);
}

}  // namespace
}  // namespace rk::intersect

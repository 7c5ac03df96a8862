// The seeded points tracker (extract/points_tracker.h) on a rendered sequence with truth: a quadrant marker on
// a dark body, hidden by a cloud while its motion reverses, with an identical marker (a look-alike, on the
// sky) shown at the point's straight-line prediction while it is hidden.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <random>
#include <vector>

#include "extract/points_tracker.h"
#include "io/csv.h"
#include "sim/points_scene.h"
#include "sim/render.h"

namespace rk::extract {
namespace points_tracker_test {  // named: tests/extract is one unity build

constexpr int kW = 160, kH = 120;
constexpr double kFps = 100.0;
constexpr int kFrames = 90;
constexpr int kHideFrom = 40, kHideTo = 55;  // frames [kHideFrom, kHideTo] hidden
constexpr double kSpeed = 30.0;               // px/s, reversed at the middle of the hidden span

double TruthX(int k) {
  const double t = k / kFps, tr = 0.5 * (kHideFrom + kHideTo) / kFps;
  return t < tr ? 50.0 + kSpeed * t : 50.0 + kSpeed * tr - kSpeed * (t - tr);
}
constexpr double kTruthY = 60.3;

// Saddle marker of side 20 px at (cx, cy): ±50 DN about level 100, PSF 0.9 px.
double Marker(double x, double y, double cx, double cy) {
  const double u = x - cx, v = y - cy;
  if (std::abs(u) > 10 || std::abs(v) > 10) return -1;
  return 100.0 + 50.0 * std::erf(u / (std::sqrt(2.0) * 0.9)) * std::erf(v / (std::sqrt(2.0) * 0.9));
}

// The scene with the marker at (cx, cy) (hidden: the look-alike at (lx, ly) instead); noise seeded by `seed`.
cv::Mat Render(double cx, double cy, bool hidden, double lx, double ly, std::uint64_t seed) {
  cv::Mat s(kH, kW, CV_32FC1);
  constexpr int kSub = 4;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      double acc = 0;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i) {
          const double px = x - 0.5 + (i + 0.5) / kSub, py = y - 0.5 + (j + 0.5) / kSub;
          double v = 170.0 - 0.2 * py;  // sky
          if (!hidden) {
            // The dark body (a 50×36 plate with a stripe) carrying the marker.
            if (std::abs(px - cx - 6) < 25 && std::abs(py - cy) < 18) v = (py - cy) > 12 ? 20.0 : 45.0;
            const double m = Marker(px, py, cx, cy);
            if (m >= 0) v = m;
          } else {
            const double m = Marker(px, py, lx, ly);
            if (m >= 0) v = m;
          }
          acc += v;
        }
      s.at<float>(y, x) = static_cast<float>(acc / (kSub * kSub));
    }
  sim::SensorOptions o{5.0, 2.0, 40.0, 8};
  std::mt19937_64 rng(seed);
  return sim::Digitise(s, o, rng);
}

cv::Mat Frame(int k) {
  // The look-alike where a straight-line prediction would put the hidden point.
  return Render(TruthX(k), kTruthY, k >= kHideFrom && k <= kHideTo, 50.0 + kSpeed * k / kFps, kTruthY,
                500 + static_cast<std::uint64_t>(k));
}

formats::Seeds OneSeed(const char* method, double x, double y) {
  return formats::ReadSeeds(io::CsvTable::Parse(std::string("id,frame,x_px,y_px,method,size_px\nq1,0,") +
                                                    std::to_string(x) + "," + std::to_string(y) + "," + method + ",20\n",
                                                "seeds.csv"));
}

// Figures of issue 31: re-acquired within 2 frames of the return, whatever the motion did while hidden;
// no row on the look-alike; moving RMS ≤ 0.03 px for a quadrant.
constexpr int kReacquireFrames = 2;
constexpr double kQuadrantMovingRms = 0.03;
constexpr double kOkErrorMax = 0.1;

TEST(PointsTracker, HiddenReversalLookalikeAndReacquisition) {
  PointsTracker tracker(OneSeed("quadrant", TruthX(0) + 0.8, kTruthY - 0.6), PointsTrackOptions{});
  int first_back = -1, invalid_rows = 0, predicted_rows = 0;
  double se = 0;
  int n = 0;
  for (int k = 0; k < kFrames; ++k) {
    const PointsFrameResult r = tracker.Process(Frame(k), k, k / kFps);
    ASSERT_EQ(r.points.size(), 1u);
    const PointRow& p = r.points[0];
    const bool measured = p.status == RowStatus::kOk || p.status == RowStatus::kReacquired;
    const bool hidden = k >= kHideFrom && k <= kHideTo;
    if (hidden) {
      EXPECT_FALSE(measured) << "frame " << k << " measured while hidden (the look-alike?) at " << p.px.x();
      invalid_rows += p.status == RowStatus::kInvalid;
      predicted_rows += p.status == RowStatus::kPredicted;
      continue;
    }
    if (k > kHideTo && first_back < 0 && measured) first_back = k;
    if (!measured) {
      EXPECT_TRUE(k > kHideTo && k <= kHideTo + kReacquireFrames) << "frame " << k << " not measured";
      continue;
    }
    const double ex = p.px.x() - TruthX(k), ey = p.px.y() - kTruthY;
    EXPECT_LT(std::hypot(ex, ey), kOkErrorMax) << "frame " << k;
    se += 0.5 * (ex * ex + ey * ey);
    ++n;
  }
  EXPECT_GE(first_back, kHideTo + 1);
  EXPECT_LE(first_back, kHideTo + kReacquireFrames);
  EXPECT_GT(predicted_rows, 0);
  const PointSummary& s = tracker.summary()[0];
  EXPECT_GT(s.lookalikes_refused + s.ambiguous, 0) << "the look-alike was never looked at";
  const double rms = std::sqrt(se / n);
  std::printf("quadrant moving: rms %.4f px over %d rows; back at frame %d; %d predicted, %d invalid while hidden\n",
              rms, n, first_back, predicted_rows, invalid_rows);
  EXPECT_LT(rms, kQuadrantMovingRms);
}

TEST(PointsTracker, ReseedRowRestartsThePoint) {
  // A second seeds row at frame 60 (after the point came back) puts the point where the user says.
  const formats::Seeds seeds = formats::ReadSeeds(io::CsvTable::Parse(
      "id,frame,x_px,y_px,method,size_px\nq1,0," + std::to_string(TruthX(0)) + "," + std::to_string(kTruthY) +
          ",quadrant,20\nq1,60," + std::to_string(TruthX(60) + 0.5) + "," + std::to_string(kTruthY) + ",quadrant,20\n",
      "seeds.csv"));
  PointsTracker tracker(seeds, PointsTrackOptions{});
  for (int k = 0; k <= 61; ++k) {
    const PointsFrameResult r = tracker.Process(Frame(k), k, k / kFps);
    if (k == 60 || k == 61) {
      EXPECT_EQ(r.points[0].status, RowStatus::kOk) << k;
      EXPECT_NEAR(r.points[0].px.x(), TruthX(k), kOkErrorMax) << k;
    }
  }
  EXPECT_EQ(tracker.summary()[0].seeds, 2);
}

// Frame stamps as real recordings have them: jitter of ±30 % of the interval, skipped frames (a gap of two and
// of three intervals) and a duplicated stamp (the same time twice). The motion is fast (150 px/s, 1.5 px a nominal
// frame), so that a tracker that took the frame index for time would miss: every row must be measured, within
// the error bound, and the filter must not be restarted by the irregular steps.
TEST(PointsTracker, JitteringSkippedAndDuplicatedStampsAreFollowed) {
  constexpr double kFastSpeed = 150.0;  // px/s: the marker stays in the 160 px frame over the 50 frames
  std::vector<double> stamps;
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  double t = 0.0;
  for (int k = 0; k < 50; ++k) {
    stamps.push_back(t);
    double step = (1.0 + jitter(rng)) / kFps;
    if (k == 15) step = 2.0 / kFps;   // one frame skipped
    if (k == 28) step = 3.0 / kFps;   // two skipped
    if (k == 38) step = 0.0;          // a duplicated stamp
    t += step;
  }
  const auto x_at = [&](double ts) { return 40.0 + kFastSpeed * ts; };
  PointsTracker tracker(OneSeed("quadrant", x_at(0) + 0.5, kTruthY - 0.4), PointsTrackOptions{});
  double worst = 0;
  for (int k = 0; k < static_cast<int>(stamps.size()); ++k) {
    const double ts = stamps[static_cast<std::size_t>(k)];
    const cv::Mat f = Render(x_at(ts), kTruthY, false, 0, 0, 900 + static_cast<std::uint64_t>(k));
    const PointRow p = tracker.Process(f, k, ts).points[0];
    ASSERT_TRUE(p.status == RowStatus::kOk) << "frame " << k << " at t " << ts << ": status " << static_cast<int>(p.status);
    worst = std::max(worst, std::hypot(p.px.x() - x_at(ts), p.px.y() - kTruthY));
  }
  EXPECT_LT(worst, kOkErrorMax);
  EXPECT_EQ(tracker.summary()[0].restarts, 0);
}

// rk-sim points' moving scene (translating, rotating, growing): a cloud crosses c1 and then t1. When each comes
// out, the cloud still covers part of its surroundings, which therefore do not match those stored before it
// hid; the other points (q1, q2, b1, d1, t2, tracked throughout) say where the target carried it and how it
// turned and grew, and the point is re-acquired there (issue 31: within 2 frames of its return). Seeded at
// frame 50 from the truth so that the run is short.
TEST(PointsTracker, AMarkerOutOfACloudIsReacquiredWhereItsGroupPutsIt) {
  constexpr int kFirst = 50;
  constexpr double kVisibleErrorMax = 0.1;  // px, a measured row while the truth says visible
  sim::PointsSceneOptions o;
  o.seed = 100;
  const sim::PointsSimulator scene(o);
  std::string csv = "id,frame,x_px,y_px,method,size_px\n";
  for (const auto& t : scene.Truth(kFirst)) {
    ASSERT_TRUE(t.visible) << t.id;
    const sim::PointsSimulator::Seed s = scene.SeedAt(t.id, kFirst);
    csv += s.id + "," + std::to_string(kFirst) + "," + std::to_string(s.x_px) + "," + std::to_string(s.y_px) + "," +
           s.method + "," + std::to_string(s.size_px) + "\n";
  }
  const formats::Seeds seeds = formats::ReadSeeds(io::CsvTable::Parse(csv, "seeds.csv"));
  PointsTracker tracker(seeds, PointsTrackOptions{});
  // Per point: frames not visible (some cloud over it), frames visible again but not measured (to be at most
  // kReacquireFrames: each point comes out of a cloud once).
  std::map<std::string, int> covered, fully_hidden, late;
  for (int k = kFirst; k < scene.frames(); ++k) {
    const PointsFrameResult r = tracker.Process(scene.Frame(k), k, scene.TimeS(k));
    const std::vector<sim::PointTruth> truth = scene.Truth(k);
    for (std::size_t i = 0; i < seeds.ids.size(); ++i) {
      const std::string& id = seeds.ids[i];
      const PointRow& p = r.points[i];
      const bool measured = p.status == RowStatus::kOk || p.status == RowStatus::kReacquired;
      for (const sim::PointTruth& t : truth) {
        if (t.id != id) continue;
        if (!t.visible) ++covered[id];
        if (t.occlusion >= 1.0) {
          ++fully_hidden[id];
          EXPECT_FALSE(measured) << id << " measured at frame " << k << " while fully hidden";
        }
        if (!t.visible) continue;
        if (!measured) {
          ++late[id];
          continue;
        }
        EXPECT_LT(std::hypot(p.px.x() - t.x_px, p.px.y() - t.y_px), kVisibleErrorMax) << id << " frame " << k;
      }
    }
  }
  for (const std::string& id : seeds.ids) {
    std::printf("%s: %d frames under a cloud (%d fully hidden), %d visible but not measured\n", id.c_str(),
                covered[id], fully_hidden[id], late[id]);
    EXPECT_LE(late[id], covered[id] > 0 ? kReacquireFrames : 0) << id;
  }
  EXPECT_GT(fully_hidden["c1"], 0) << "the scene no longer hides c1";
  EXPECT_GT(covered["t1"], 0) << "the scene no longer covers t1";
}

}  // namespace points_tracker_test
}  // namespace rk::extract

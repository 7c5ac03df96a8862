// rk-sim points (sim/points_scene.h): the truth is exact in the rendered image, the scenarios do what they
// promise (motion, hiding, reversal, look-alike), frames are deterministic, the folder is written atomically.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "io/csv.h"
#include "io/error.h"
#include "rk_test/temp_dir.h"
#include "sim/points_scene.h"

namespace rk::sim {
namespace {

constexpr double kPointsTruthTolPx = 0.002;        // the brief: the image's marker position exact to ~0.003 px
constexpr double kPointsBodyDn = 45;               // the silhouette's grey (points_render.cc)
constexpr double kPointsNoiseRelTol = 0.1;      // sample std of ~10^4 sky pixels vs the model

PointsSceneOptions PointsSmall(PointsScenario s, int frames = 60) {
  PointsSceneOptions o;
  o.scenario = s;
  o.frames = frames;
  return o;
}

const PointTruth& FindPoint(const std::vector<PointTruth>& truth, const std::string& id) {
  for (const PointTruth& t : truth) {
    if (t.id == id) return t;
  }
  throw std::runtime_error("no truth for " + id);
}

// Weighted centroid of weight(pixel value, x, y) over the pixels whose centres lie in the square of half side
// `half` around the truth, in the marker's axes rotated by theta.
cv::Point2d PointsCentroid(const cv::Mat& img, const PointTruth& t, double theta, double half,
                     const std::function<double(double, int, int)>& weight) {
  double sw = 0, sx = 0, sy = 0;
  const double c = std::cos(theta), s = std::sin(theta), reach = half * M_SQRT2 + 1;
  for (int y = static_cast<int>(t.y_px - reach); y <= static_cast<int>(t.y_px + reach); ++y) {
    for (int x = static_cast<int>(t.x_px - reach); x <= static_cast<int>(t.x_px + reach); ++x) {
      const double dx = x - t.x_px, dy = y - t.y_px;
      if (std::abs(c * dx + s * dy) > half || std::abs(-s * dx + c * dy) > half) continue;
      const double w = weight(img.at<float>(y, x), x, y);
      sw += w, sx += w * x, sy += w * y;
    }
  }
  return {sx / sw, sy / sw};
}

// The image's own centre of each symmetric marker equals the truth: quadrant (the blob and, squared, the
// checker), lamp and dark disc, in a static frame and in a moving, rotating, growing, motion-blurred one.
void ExpectSymmetricAtTruth(PointsScenario sc, int supersample) {
  PointsSceneOptions o = PointsSmall(sc);
  o.clouds = false;
  const PointsSimulator sim(o);
  const int k = 37;
  const cv::Mat img = sim.Signal(k, supersample > 0 ? supersample : o.SupersampleN());
  const std::vector<PointTruth> truth = sim.Truth(k);
  const PointsSimulator::Pose pose = sim.PoseAt(sim.TimeS(k));
  const double sigma = o.psf_sigma_px;
  const auto check = [&](const std::string& id, double half, const std::function<double(double, int, int)>& w) {
    const PointTruth& t = FindPoint(truth, id);
    const cv::Point2d c = PointsCentroid(img, t, pose.theta_rad, half, w);
    const std::string where = id + " " + PointsScenarioName(sc) + " n " + std::to_string(supersample);
    EXPECT_NEAR(c.x, t.x_px, kPointsTruthTolPx) << where;
    EXPECT_NEAR(c.y, t.y_px, kPointsTruthTolPx) << where;
  };
  const double quad_half = 8 * pose.scale + 6 * sigma;
  check("q1", quad_half, [](double v, int, int) { return v - kPointsBodyDn; });
  check("q2", quad_half, [](double v, int, int) { return (v - kPointsBodyDn) * (v - kPointsBodyDn); });
  check("b1", 6 * pose.scale + 5 * sigma, [](double v, int, int) { return v - kPointsBodyDn; });
  // d1 is on the sky: its weight is the sky (column 0 of its row: no target there) minus the pixel.
  check("d1", 6 * pose.scale + 6 * sigma, [&img](double v, int, int y) { return img.at<float>(y, 0) - v; });
}

TEST(PointsScene, TruthIsTheImagesCentreOfSymmetry) {
  ExpectSymmetricAtTruth(PointsScenario::kStatic, 0);
  ExpectSymmetricAtTruth(PointsScenario::kMoving, 0);
}

// c1's rim is centred on the truth: intensity above the body under a smooth ring window 2 sigma outside the
// radius, where the highlight inside the disc has faded (the window is centred on the truth: an off-centre
// rim would pull it). Without motion blur: a growing disc smeared by motion has its leading rim from the
// latest, largest disc (docs/rk-sim.md "Truth").
TEST(PointsScene, CircleRimIsCentredOnTheTruth) {
  for (PointsScenario sc : {PointsScenario::kStatic, PointsScenario::kMoving}) {
    PointsSceneOptions o = PointsSmall(sc);
    o.clouds = false;
    o.exposure_s = 0;
    const PointsSimulator sim(o);
    const int k = 37;
    const cv::Mat img = sim.Signal(k);
    const std::vector<PointTruth> truth = sim.Truth(k);
    const PointTruth& c1 = FindPoint(truth, "c1");
    const PointsSimulator::Pose pose = sim.PoseAt(sim.TimeS(k));
    const double sigma = o.psf_sigma_px, rim = 8 * pose.scale + 2 * sigma;
    const cv::Point2d c = PointsCentroid(img, c1, pose.theta_rad, rim + 6 * sigma, [&](double v, int x, int y) {
      const double r = std::hypot(x - c1.x_px, y - c1.y_px);
      return (v - kPointsBodyDn) * std::exp(-0.5 * (r - rim) * (r - rim) / (sigma * sigma));
    });
    EXPECT_NEAR(c.x, c1.x_px, kPointsTruthTolPx) << PointsScenarioName(sc);
    EXPECT_NEAR(c.y, c1.y_px, kPointsTruthTolPx) << PointsScenarioName(sc);
  }
}

// The n x n lattice that integrates each pixel is a symmetric aperture (n points instead of the box): it
// changes the pixel values slightly (~0.3 DN at a lamp's peak between n = 3 and 12), never the centres.
TEST(PointsScene, PixelLatticeDoesNotMoveTheTruth) {
  ExpectSymmetricAtTruth(PointsScenario::kMoving, 2);
  ExpectSymmetricAtTruth(PointsScenario::kMoving, 12);
}

TEST(PointsScene, FramesAreDeterministicPerFrame) {
  const PointsSimulator a(PointsSmall(PointsScenario::kMoving)), b(PointsSmall(PointsScenario::kMoving));
  EXPECT_EQ(cv::norm(a.Frame(5), b.Frame(5), cv::NORM_INF), 0.0);
  PointsSceneOptions o = PointsSmall(PointsScenario::kMoving);
  o.seed = 2;
  EXPECT_GT(cv::norm(a.Frame(5), PointsSimulator(o).Frame(5), cv::NORM_INF), 0.0);
  EXPECT_EQ(a.Frame(5).type(), CV_8UC1);
  o.bits = 16;
  const cv::Mat deep = PointsSimulator(o).Frame(5);
  EXPECT_EQ(deep.type(), CV_16UC1);
  double lo = 0, hi = 0;
  cv::minMaxLoc(deep, &lo, &hi);
  EXPECT_GT(hi, 255);
  EXPECT_LE(hi, 4095);
}

// Noise on the sky has the model's std: sqrt(mean / gain + read²).
TEST(PointsScene, NoiseHasTheModelsStd) {
  PointsSceneOptions o = PointsSmall(PointsScenario::kStatic);
  const PointsSimulator sim(o);
  const cv::Rect sky(0, 0, 100, 100);
  cv::Mat frame, signal = sim.Signal(3)(sky);
  sim.Frame(3)(sky).convertTo(frame, CV_32F);
  cv::Scalar mean, sd;
  cv::meanStdDev(frame - signal, mean, sd);
  const double level = cv::mean(signal)[0];
  const double expected = std::sqrt(level / o.gain_e_per_dn + o.read_noise_dn * o.read_noise_dn);
  EXPECT_NEAR(sd[0], expected, kPointsNoiseRelTol * expected);
}

TEST(PointsScene, StaticDoesNotMoveAndMovingRotatesAndGrows) {
  const PointsSimulator still(PointsSmall(PointsScenario::kStatic));
  EXPECT_EQ(FindPoint(still.Truth(0), "t1").x_px, FindPoint(still.Truth(59), "t1").x_px);
  const PointsSimulator moving(PointsSmall(PointsScenario::kMoving));
  const auto span = [&](int k) {
    const auto t = moving.Truth(k);
    return std::hypot(FindPoint(t, "q1").x_px - FindPoint(t, "q2").x_px, FindPoint(t, "q1").y_px - FindPoint(t, "q2").y_px);
  };
  EXPECT_NEAR(span(59) / span(0), 1.3, 1e-9);
  EXPECT_NEAR(moving.PoseAt(moving.TimeS(59)).theta_rad - moving.PoseAt(0).theta_rad, 20 * M_PI / 180, 1e-9);
  // A cloud hides c1 in the middle of the run, not at its ends.
  int hidden = 0;
  for (int k = 0; k < moving.frames(); ++k) hidden += FindPoint(moving.Truth(k), "c1").visible ? 0 : 1;
  EXPECT_GT(hidden, 5);
  EXPECT_TRUE(FindPoint(moving.Truth(0), "c1").visible);
  EXPECT_TRUE(FindPoint(moving.Truth(59), "c1").visible);
  EXPECT_FALSE(FindPoint(moving.Truth(30), "c1").visible);
}

// q2's motion reverses while the cloud hides it; the look-alike shows only then, near q2's prediction.
TEST(PointsScene, ReversalWhileHiddenAndTheLookalike) {
  const PointsSimulator sim(PointsSmall(PointsScenario::kLookalike, 200));
  int first = -1, last = -1, shown = 0;
  for (int k = 0; k < sim.frames(); ++k) {
    const auto t = sim.Truth(k);
    const PointTruth& q2 = FindPoint(t, "q2");
    if (!q2.visible) {
      if (first < 0) first = k;
      last = k;
    }
    const PointTruth& look = FindPoint(t, "lookalike");
    if (look.visible) {
      ++shown;
      EXPECT_GE(q2.occlusion, 1.0) << k;
      EXPECT_GT(std::hypot(look.x_px - q2.x_px, look.y_px - q2.y_px), 20.0) << k;
    }
  }
  ASSERT_GT(first, 0);
  ASSERT_LT(last, sim.frames() - 1);
  EXPECT_GE(shown, 5);
  const auto velocity = [&](int k) {
    const PointTruth a = FindPoint(sim.Truth(k), "q2"), b = FindPoint(sim.Truth(k + 1), "q2");
    return cv::Point2d(b.x_px - a.x_px, b.y_px - a.y_px);
  };
  EXPECT_LT(velocity(first).dot(velocity(last)), 0.0);
  for (const PointsSimulator::Seed& s : sim.Seeds()) EXPECT_NE(s.id, "lookalike");
  EXPECT_EQ(sim.Seeds().size(), 7u);
}

TEST(PointsScene, WritesTheFolder) {
  namespace fs = std::filesystem;
  const rk::test::TempDir tmp("points_trial");
  const fs::path dir = fs::path(tmp.path()) / "trial";
  PointsSceneOptions o = PointsSmall(PointsScenario::kReversal, 8);
  o.bits = 16;
  o.exposure_s = 0;  // 8 frames make the run's motion fast: the auto blur steps would take many renders
  PointsWriteOptions w;
  w.reseeds = {{"q2", 5}};
  const PointsTrialSummary sum = WritePointsTrial(o, dir, w);
  EXPECT_EQ(sum.frames, 8);
  EXPECT_EQ(sum.seeds, 8);
  for (const char* f : {"frames.csv", "seeds.csv", "truth/points.csv", "video/000007.png"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  const io::CsvTable seeds = io::CsvTable::Read((dir / "seeds.csv").string());
  EXPECT_EQ(seeds.Cell(7, seeds.RequireColumn("id")), "q2");
  EXPECT_EQ(seeds.Cell(7, seeds.RequireColumn("frame")), "5");
  const io::CsvTable truth = io::CsvTable::Read((dir / "truth/points.csv").string());
  EXPECT_EQ(truth.rows(), 8u * 7u);
  // A bad re-seed writes nothing.
  w.reseeds = {{"zz", 1}};
  EXPECT_THROW(WritePointsTrial(o, fs::path(tmp.path()) / "bad", w), rk::Error);
  EXPECT_FALSE(fs::exists(fs::path(tmp.path()) / "bad"));
}

}  // namespace
}  // namespace rk::sim

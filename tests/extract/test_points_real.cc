// rk-extract points on a real recording (../shared/data/real/ball_12bit.mraw: Photron, a dark ball with a
// bright highlight inside it, falling at 30 000 fps; read in place, skipped when the folder is absent).
// Over 0.5 ms the fall is a parabola: the circle's centre must follow one to ≤ 0.02 px RMS (issue 31), and the
// rim, not the highlight, must decide it — the blob centroid of the same dark ball (a hole where the
// highlight is) lies more than a pixel away.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <filesystem>
#include <string>
#include <vector>

#include "extract/points_run.h"
#include "io/csv.h"

namespace rk::extract {
namespace points_real_test {

constexpr double kParabolaRmsMax = 0.02;  // px, issue 31
constexpr double kHighlightPullMin = 0.5;  // px: how far the highlight moves a centroid

std::string Ball() { return std::string(RK_REAL_DATA_DIR) + "/ball_12bit.mraw"; }

std::vector<Eigen::Vector3d> Track(const char* method) {
  const formats::Seeds seeds = formats::ReadSeeds(io::CsvTable::Parse(
      std::string("id,frame,x_px,y_px,method,size_px\nball,0,175,109.5,") + method + ",127\n", "seeds.csv"));
  const formats::FrameClock clock = formats::FrameClock::FromRate(30000.0, 0.0);
  const PointsRunResult r = RunPoints({Ball()}, clock, seeds, PointsTrackOptions{});
  std::vector<Eigen::Vector3d> out;
  for (const PointsFrameResult& f : r.rows) {
    EXPECT_EQ(f.points[0].status, RowStatus::kOk) << method << " frame " << f.frame;
    out.emplace_back(f.t_s, f.points[0].px.x(), f.points[0].px.y());
  }
  return out;
}

// RMS residual of column c (1 = x, 2 = y) from a least-squares parabola in time.
double ParabolaRms(const std::vector<Eigen::Vector3d>& v, int c) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(v.size()), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double t = v[i](0) * 1e3;  // ms: a well-conditioned design
    A.row(static_cast<Eigen::Index>(i)) << 1.0, t, t * t;
    b(static_cast<Eigen::Index>(i)) = v[i](c);
  }
  const Eigen::VectorXd r = b - A * A.colPivHouseholderQr().solve(b);
  return std::sqrt(r.squaredNorm() / static_cast<double>(v.size()));
}

TEST(PointsReal, FallingBallFollowsAParabolaByItsRim) {
  if (!std::filesystem::exists(Ball())) GTEST_SKIP() << "no real data at " << RK_REAL_DATA_DIR;
  const std::vector<Eigen::Vector3d> circle = Track("circle");
  ASSERT_EQ(circle.size(), 15u);
  const double rx = ParabolaRms(circle, 1), ry = ParabolaRms(circle, 2);
  std::printf("ball: circle centre from a parabola: %.4f px (x), %.4f px (y) RMS\n", rx, ry);
  EXPECT_LT(rx, kParabolaRmsMax);
  EXPECT_LT(ry, kParabolaRmsMax);
  const std::vector<Eigen::Vector3d> blob = Track("centroid-dark");
  double pull = 0;
  for (std::size_t i = 0; i < blob.size(); ++i) pull += (blob[i] - circle[i]).tail<2>().norm() / blob.size();
  std::printf("ball: the dark blob's centroid lies %.3f px from the rim's centre\n", pull);
  EXPECT_GT(pull, kHighlightPullMin);
}

}  // namespace points_real_test
}  // namespace rk::extract

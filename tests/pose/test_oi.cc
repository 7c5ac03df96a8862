// Orthogonal iteration and its Procrustes step (pose/oi.h) against simulated truth
// (sim/attitude_problems.h).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "geo/angles.h"
#include "pose/oi.h"
#include "pose/pnp.h"
#include "pose_test_util.h"
#include "sim/attitude_problems.h"

namespace rk::pose {
namespace {

using sim::PnpGeometry;
using sim::PnpProblem;
using testing::kNoiseFreeRad;
using testing::kRoundoff;
using testing::Normalised;
using testing::Problem;
using testing::Rays;

double DirectObjectError(const std::vector<Eigen::Vector3d>& rays, const std::vector<Eigen::Vector3d>& p,
                         const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  double e = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Eigen::Matrix3d V = rays[i] * rays[i].transpose() / rays[i].squaredNorm();
    e += ((Eigen::Matrix3d::Identity() - V) * (R * p[i] + t)).squaredNorm();
  }
  return e;
}

TEST(Procrustes, RecoversRotationAndStaysProper) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0, 1);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Matrix3d R = sim::RandomRotation(5, static_cast<std::uint64_t>(k));
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i) = g(rng);
    const Eigen::Matrix3d H = A * A.transpose() + 0.1 * Eigen::Matrix3d::Identity();  // SPD
    EXPECT_LT((ProcrustesRotation(R * H) - R).norm(), kRoundoff) << k;
    // Rank 2 (planar model): the best proper rotation still exists and is found.
    Eigen::Matrix3d H2 = H;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(H);
    H2 = es.eigenvectors() * Eigen::Vector3d(0.0, es.eigenvalues()(1), es.eigenvalues()(2)).asDiagonal() *
         es.eigenvectors().transpose();
    EXPECT_LT((ProcrustesRotation(R * H2) - R).norm(), 1e-8) << k;
    // A reflection in M: the result is still a rotation (det +1).
    const Eigen::Matrix3d Rm = ProcrustesRotation(-R * H);
    EXPECT_NEAR(Rm.determinant(), 1.0, kRoundoff);
    EXPECT_LT((Rm.transpose() * Rm - Eigen::Matrix3d::Identity()).norm(), kRoundoff);
  }
}

TEST(OrthogonalIteration, ClosedFormsMatchDirectSums) {
  const PnpProblem pb = Problem(PnpGeometry::kBox, 4, 0.5, 8, 8);
  const auto rays = Rays(Normalised(pb, true));
  OrthogonalIteration oi;
  ASSERT_TRUE(oi.Set(rays, pb.p_body));
  for (int k = 0; k < 20; ++k) {
    const Eigen::Matrix3d R = sim::RandomRotation(9, static_cast<std::uint64_t>(k));
    const Eigen::Vector3d t = oi.Translation(R);
    const double e = DirectObjectError(rays, pb.p_body, R, t);
    EXPECT_NEAR(oi.ObjectError(R), e, 1e-9 * (1.0 + e)) << k;
    // t(R) is the minimiser over t: any perturbation raises the error.
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d dt = Eigen::Vector3d::Zero();
      dt(a) = 1e-3;
      EXPECT_GT(DirectObjectError(rays, pb.p_body, R, t + dt), e);
      EXPECT_GT(DirectObjectError(rays, pb.p_body, R, t - dt), e);
    }
  }
}

TEST(OrthogonalIteration, ErrorDecreasesMonotonically) {
  // Lu et al. §4: each OI step does not increase E (the global-convergence argument).
  for (std::uint64_t k = 0; k < 30; ++k) {
    const PnpProblem pb = Problem(k % 2 ? PnpGeometry::kPlanar : PnpGeometry::kBox, k, 0.8);
    const auto rays = Rays(Normalised(pb, true));
    OrthogonalIteration oi;
    ASSERT_TRUE(oi.Set(rays, pb.p_body));
    Eigen::Matrix3d R = sim::RandomRotation(21, k);  // an arbitrary start
    double e = DirectObjectError(rays, pb.p_body, R, oi.Translation(R));
    OiOptions one;
    one.max_iterations = 1;
    for (int it = 0; it < 50; ++it) {
      R = oi.Solve(R, one).R_cam_body;
      const double e_next = DirectObjectError(rays, pb.p_body, R, oi.Translation(R));
      EXPECT_LE(e_next, e * (1 + 1e-10) + 1e-15) << "problem " << k << " step " << it;
      e = e_next;
    }
  }
}

TEST(OrthogonalIteration, NoiseFreeConvergesToTruthFromNearbyStart) {
  for (PnpGeometry g : {PnpGeometry::kBox, PnpGeometry::kPlanar, PnpGeometry::kNarrow}) {
    for (std::uint64_t k = 0; k < 20; ++k) {
      const PnpProblem pb = Problem(g, k, 0.0);
      const auto rays = Rays(Normalised(pb, false));
      OrthogonalIteration oi;
      ASSERT_TRUE(oi.Set(rays, pb.p_body));
      const Eigen::Matrix3d R0 =
          Eigen::AngleAxisd(geo::DegToRad(10.0), Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix() *
          pb.R_cam_body;
      OiOptions opt;
      opt.max_iterations = 20000;
      opt.rotation_tol = 1e-13;
      const OiResult r = oi.Solve(R0, opt);
      EXPECT_EQ(r.termination, OiTermination::kConverged);
      EXPECT_LT(RotationAngle(r.R_cam_body, pb.R_cam_body), kNoiseFreeRad) << sim::PnpGeometryName(g) << k;
      EXPECT_LT((r.t_cam - pb.t_cam).norm(), kNoiseFreeRad * pb.t_cam.norm()) << sim::PnpGeometryName(g) << k;
      // The O(1) closed form of E has an absolute round-off of ~1e-15 Σ‖p'‖²; the direct sum not.
      EXPECT_LT(DirectObjectError(rays, pb.p_body, r.R_cam_body, r.t_cam), 1e-20);
      EXPECT_LT(r.object_error_m2, 1e-12);
    }
  }
}

TEST(OrthogonalIteration, RejectsDegenerateInput) {
  OrthogonalIteration oi;
  std::vector<Eigen::Vector3d> rays = {{0, 0, 1}, {0.1, 0, 1}, {0, 0.1, 1}, {0.1, 0.1, 1}};
  std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  EXPECT_FALSE(oi.Set(rays, line));  // collinear model
  std::vector<Eigen::Vector3d> same(4, Eigen::Vector3d(1, 2, 3));
  EXPECT_FALSE(oi.Set(rays, same));  // coincident model points
  std::vector<Eigen::Vector3d> ok = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  std::vector<Eigen::Vector3d> behind = rays;
  behind[2].z() = -1;
  EXPECT_FALSE(oi.Set(behind, ok));  // a ray behind the camera
  EXPECT_FALSE(oi.Set(std::span(rays).first(2), std::span(ok).first(2)));  // n < 3
  EXPECT_TRUE(oi.Set(rays, ok));
}

}  // namespace
}  // namespace rk::pose

// Image fit of the cylinder pose (attitude/cylinder_image_fit.h) on frames rendered by rk-sim theodolite's
// renderer, seed 004's optics on a 640×640 crop, target 2.5 m × 0.25 m at 1224 m (the 276-px image of the
// paper's Table 4), yaw 76.211°, pitch 31.257°.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "attitude/cylinder_image_fit.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "sim/theodolite_render.h"
#include "sim/theodolite_scene.h"
#include "target/cylinder.h"

namespace rk::attitude {
namespace {

using geo::DegToRad;
using geo::RadToDeg;

// The fit's own σ on this image is ≈ 0.057° yaw, 0.022° pitch (default sensor, 1.7 DN noise); the
// Cramér–Rao bound 0.039° / 0.015° (bench/cylinder_crlb). Tolerances: 4σ of one frame.
constexpr double kYawTolDeg = 0.25, kPitchTolDeg = 0.10;
// Noise-free 16-bit frame: the model is the renderer's, so only rounding (1/256 DN) and the rim sampling
// remain: a bias test.
constexpr double kNoiseFreeTolDeg = 0.002;

struct Scene {
  camera::CameraModel cam;
  sim::TheodoliteFrameTruth truth;
  target::CylinderShape shape;
};

Scene MakeScene(double dx_px, double dy_px) {
  Scene s;
  s.cam = sim::Seed004Camera();
  s.cam.width_px = s.cam.height_px = 640;
  s.cam.principal_point_px = {319.5, 319.5};
  s.truth.pose =
      target::PoseAt(1224.0, DegToRad(326.2), DegToRad(16.274), DegToRad(76.211), DegToRad(31.257), s.shape);
  s.truth.points = target::SilhouettePointsOf(s.truth.pose, s.shape);
  const Eigen::Vector3d mid = s.truth.pose.tail_centre_enu + 0.5 * s.shape.length_m * s.truth.pose.Axis();
  const geo::AzEl ae = geo::AzElFromEnu(mid);
  s.truth.boresight_az_rad = ae.az_rad + dx_px / s.cam.fx() / std::cos(ae.el_rad);
  s.truth.boresight_el_rad = ae.el_rad - dy_px / s.cam.fy();
  const double A = s.truth.boresight_az_rad, E = s.truth.boresight_el_rad;
  s.truth.nose_px = *s.cam.ProjectEnu(s.truth.points.nose, A, E);
  s.truth.tail1_px = *s.cam.ProjectEnu(s.truth.points.tail1, A, E);
  s.truth.tail2_px = *s.cam.ProjectEnu(s.truth.points.tail2, A, E);
  return s;
}

CylinderImageFitResult FitFrom(const Scene& s, const cv::Mat& img, double dyaw_deg, double dpitch_deg,
                               const Eigen::Vector3d& dpos_m) {
  return FitCylinderImage(img, s.cam, s.truth.boresight_az_rad, s.truth.boresight_el_rad, s.shape,
                          s.truth.pose.tail_centre_enu + dpos_m, s.truth.pose.yaw_rad + DegToRad(dyaw_deg),
                          s.truth.pose.pitch_rad + DegToRad(dpitch_deg), CylinderImageFitOptions{});
}

TEST(CylinderImageFit, NoiseFreeFrameFromAPerturbedStart) {
  const Scene s = MakeScene(3.3, -7.1);
  sim::SilhouetteRenderOptions ro;
  ro.sensor.read_noise_dn = 0.0;
  ro.sensor.gain_e_per_dn = 0.0;
  ro.sensor.bit_depth = 16;
  std::mt19937_64 rng(1);
  const cv::Mat img = sim::RenderSilhouetteFrame(s.cam, s.truth, s.shape, ro, rng);
  // A start as far off as the three-point solution's worst frames at this size (0.3°, 0.2°, 0.1 m).
  const CylinderImageFitResult g = FitFrom(s, img, 0.3, -0.2, Eigen::Vector3d(0.1, -0.05, 0.05));
  ASSERT_EQ(g.status, CylinderImageFitStatus::kConverged);
  EXPECT_LT(std::abs(RadToDeg(geo::AngleDiff(g.yaw_rad, s.truth.pose.yaw_rad))), kNoiseFreeTolDeg);
  EXPECT_LT(std::abs(RadToDeg(g.pitch_rad - s.truth.pose.pitch_rad)), kNoiseFreeTolDeg);
  EXPECT_NEAR(g.psf_sigma_px, ro.psf_sigma_px, 0.02);
  EXPECT_NEAR(g.nose_cone_length_m, s.shape.nose_length_m, 0.01);
  EXPECT_NEAR(g.contrast_dn, 256.0 * (ro.body_dn - ro.sky_dn), 256.0);
  EXPECT_LT(g.rms_dn, 0.5);  // rounding to 16 bits only (0.29 DN of the 16-bit scale)
  EXPECT_NEAR(RadToDeg(geo::DirectionFromAzEl(g.yaw_rad, g.pitch_rad).dot(g.axis_enu)), RadToDeg(1.0), 1e-9);
}

TEST(CylinderImageFit, NoisyFramesWithinFourSigmaAndHonestSigma) {
  sim::SilhouetteRenderOptions ro;  // default sensor: read 1 DN, 100 e-/DN, 8 bit
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-10, 10);
  for (int k = 0; k < 2; ++k) {
    const Scene s = MakeScene(U(rng), U(rng));
    const cv::Mat img = sim::RenderSilhouetteFrame(s.cam, s.truth, s.shape, ro, rng);
    const CylinderImageFitResult g = FitFrom(s, img, -0.2, 0.1, Eigen::Vector3d(-0.05, 0.05, 0.0));
    ASSERT_NE(g.status, CylinderImageFitStatus::kFailed);
    EXPECT_LT(std::abs(RadToDeg(geo::AngleDiff(g.yaw_rad, s.truth.pose.yaw_rad))), kYawTolDeg) << k;
    EXPECT_LT(std::abs(RadToDeg(g.pitch_rad - s.truth.pose.pitch_rad)), kPitchTolDeg) << k;
    // σ from the fit's covariance: the noise is 1.7 DN, the fit's σ ≈ 0.057° / 0.022°.
    EXPECT_NEAR(g.rms_dn, 1.7, 0.2);
    EXPECT_GT(RadToDeg(g.sigma_yaw_rad), 0.03);
    EXPECT_LT(RadToDeg(g.sigma_yaw_rad), 0.10);
    EXPECT_GT(RadToDeg(g.sigma_pitch_rad), 0.01);
    EXPECT_LT(RadToDeg(g.sigma_pitch_rad), 0.04);
  }
}

// Warm start (issue 20): a fit started from the previous frame's nuisance parameters and noise model (no
// cone-length scan, no noise-model fit) lands within the same tolerances, near the cold fit's result (within
// 0.5 σ: the weights differ a little) with the same honest σ, and costs fewer model evaluations; an unusable
// start is a cold fit.
TEST(CylinderImageFit, WarmStartFromThePreviousFrameIsAsGoodAndCheaper) {
  sim::SilhouetteRenderOptions ro;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-10, 10);
  Scene s = MakeScene(U(rng), U(rng));
  const cv::Mat first = sim::RenderSilhouetteFrame(s.cam, s.truth, s.shape, ro, rng);
  const CylinderImageFitResult g0 = FitFrom(s, first, -0.2, 0.1, Eigen::Vector3d(-0.05, 0.05, 0.0));
  ASSERT_EQ(g0.status, CylinderImageFitStatus::kConverged);
  EXPECT_GT(g0.noise_c0, 0.0);
  const CylinderImageFitStart start = g0.NextStart();
  for (int k = 0; k < 2; ++k) {
    s = MakeScene(U(rng), U(rng));
    const cv::Mat img = sim::RenderSilhouetteFrame(s.cam, s.truth, s.shape, ro, rng);
    const Eigen::Vector3d dpos(0.05, -0.05, 0.02);
    const CylinderImageFitResult cold = FitFrom(s, img, 0.2, -0.1, dpos);
    const CylinderImageFitResult warm =
        FitCylinderImage(img, s.cam, s.truth.boresight_az_rad, s.truth.boresight_el_rad, s.shape,
                         s.truth.pose.tail_centre_enu + dpos, s.truth.pose.yaw_rad + DegToRad(0.2),
                         s.truth.pose.pitch_rad + DegToRad(-0.1), CylinderImageFitOptions{}, &start);
    ASSERT_EQ(warm.status, CylinderImageFitStatus::kConverged) << k;
    EXPECT_LT(std::abs(RadToDeg(geo::AngleDiff(warm.yaw_rad, s.truth.pose.yaw_rad))), kYawTolDeg) << k;
    EXPECT_LT(std::abs(RadToDeg(warm.pitch_rad - s.truth.pose.pitch_rad)), kPitchTolDeg) << k;
    // The same minimum as the cold fit, to a small fraction of the fit's σ.
    EXPECT_LT(std::abs(RadToDeg(geo::AngleDiff(warm.yaw_rad, cold.yaw_rad))), 0.5 * RadToDeg(cold.sigma_yaw_rad)) << k;
    EXPECT_LT(std::abs(RadToDeg(warm.pitch_rad - cold.pitch_rad)), 0.5 * RadToDeg(cold.sigma_pitch_rad)) << k;
    EXPECT_NEAR(warm.sigma_yaw_rad, cold.sigma_yaw_rad, 0.1 * cold.sigma_yaw_rad) << k;
    EXPECT_NEAR(warm.sigma_pitch_rad, cold.sigma_pitch_rad, 0.1 * cold.sigma_pitch_rad) << k;
    EXPECT_LT(warm.evaluations, cold.evaluations) << k << ": warm " << warm.evaluations << ", cold " << cold.evaluations;
    CylinderImageFitStart unusable = start;
    unusable.noise_c0 = 0.0;
    const CylinderImageFitResult again =
        FitCylinderImage(img, s.cam, s.truth.boresight_az_rad, s.truth.boresight_el_rad, s.shape,
                         s.truth.pose.tail_centre_enu + dpos, s.truth.pose.yaw_rad + DegToRad(0.2),
                         s.truth.pose.pitch_rad + DegToRad(-0.1), CylinderImageFitOptions{}, &unusable);
    EXPECT_EQ(again.evaluations, cold.evaluations) << k;  // an unusable start is a cold fit
    EXPECT_EQ(again.yaw_rad, cold.yaw_rad) << k;
  }
}

TEST(CylinderImageFit, OutlineLeavingTheFrameOrWrongImageFails) {
  const Scene s = MakeScene(0, 0);
  sim::SilhouetteRenderOptions ro;
  std::mt19937_64 rng(3);
  const cv::Mat img = sim::RenderSilhouetteFrame(s.cam, s.truth, s.shape, ro, rng);
  // A start 2000 px to the side: the outline is not in the frame.
  const Eigen::Vector3d side = 1224.0 * 2000.0 / s.cam.fx() *
                               Eigen::Vector3d(1, 0, 0).cross(s.truth.pose.tail_centre_enu.normalized());
  EXPECT_EQ(FitFrom(s, img, 0, 0, side).status, CylinderImageFitStatus::kFailed);
  EXPECT_EQ(FitFrom(s, cv::Mat(), 0, 0, Eigen::Vector3d::Zero()).status, CylinderImageFitStatus::kFailed);
  cv::Mat colour(640, 640, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_EQ(FitFrom(s, colour, 0, 0, Eigen::Vector3d::Zero()).status, CylinderImageFitStatus::kFailed);
  std::string why;
  CylinderImageFitOptions bad;
  bad.initial_psf_sigma_px = 0;
  EXPECT_FALSE(bad.Check(&why));
  EXPECT_TRUE(CylinderImageFitOptions{}.Check(&why));
}

}  // namespace
}  // namespace rk::attitude

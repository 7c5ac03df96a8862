// Property tests of the one camera and turret geometry (camera/projection.h) over random cameras, pointing models,
// mounts and turret angles (azimuths across 0/360, elevations to 85°): every tool's former path to a line of
// sight now calls it, and each is checked here against camera::CameraModel::RayEnu — rk-locate's position and its
// σ model, the equivalent boresight and mount (rk-attitude, rk-pose, rk-sim), rk-analyze budget's locate model,
// rk-calibrate pointing's pixel residual — and the jet derivatives against central differences.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "analysis/budget_locate.h"
#include "calibrate/pointing_cost.h"
#include "camera/camera_model.h"
#include "camera/projection.h"
#include "camera/station_view.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "geo/pointing.h"
#include "locate/locate_sigma.h"
#include "rk_test/matchers.h"

namespace rk::camera {
namespace {

constexpr int kCases = 400;
constexpr double kAgreeRad = 1e-12;      // the former paths against RayEnu: double rounding only
constexpr double kBackToPixelPx = 1e-8;    // pixel → ray → pixel through the Newton undistortion
constexpr double kDerivativeRel = 2e-6;  // jet against central differences (truncation and rounding of the latter)

struct Case {
  CameraModel cam;
  geo::PointingTerms terms;
  double az = 0, el = 0;
  Eigen::Vector2d px;
};

// A random camera (focal 8–200 mm, pixel 2–10 µm, barrel or pincushion up to |k1| 0.3), a random pointing model
// (terms to ±0.5°; one case in four all zero: the closed-form path), a random mount (±0.3°) and a pixel anywhere
// on the sensor. Azimuths are drawn near 0/360 for one case in four.
Case RandomCase(std::mt19937_64* rng, int i) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto in = [&](double a, double b) { return a + (b - a) * u(*rng); };
  Case c;
  c.cam.width_px = 640 + static_cast<int>(in(0, 4000));
  c.cam.height_px = 480 + static_cast<int>(in(0, 3000));
  c.cam.pixel_size_mm = {in(0.002, 0.010), 0};
  c.cam.pixel_size_mm[1] = c.cam.pixel_size_mm[0] * in(0.98, 1.02);
  c.cam.focal_length_mm = in(8, 200);
  c.cam.principal_point_px = {c.cam.width_px / 2.0 + in(-30, 30), c.cam.height_px / 2.0 + in(-30, 30)};
  if (i % 5 != 0) c.cam.distortion = {in(-0.3, 0.2), in(-0.1, 0.1), in(-1e-3, 1e-3), in(-1e-3, 1e-3), in(-0.02, 0.02)};
  // Keep the strongest lenses to the focal lengths that see little of their edge (wide angle, mild distortion).
  if (c.cam.focal_length_mm < 20) c.cam.distortion[0] *= 0.2;
  const double m = geo::DegToRad(0.3);
  c.cam.mount_yaw_rad = in(-m, m);
  c.cam.mount_pitch_rad = in(-m, m);
  c.cam.mount_roll_rad = in(-m, m);
  if (i % 4 != 1) {
    const double t = geo::DegToRad(0.5);
    c.terms = {in(-t, t), in(-t, t), in(-t, t), in(-t, t)};
  }
  c.az = i % 4 == 2 ? geo::WrapTwoPi(in(-0.02, 0.02)) : in(0, 2 * geo::kPi);
  c.el = geo::DegToRad(in(-10, 85));
  c.px = {in(0, c.cam.width_px - 1), in(0, c.cam.height_px - 1)};
  return c;
}

double Angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

TEST(Projection, ClosedFormTurretRotationIsTheProductWithZeroTermsBitForBit) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> az(-7.0, 7.0), el(-1.6, 1.6);
  for (int i = 0; i < 2000; ++i) {
    const double a = az(rng), e = el(rng);
    const Eigen::Matrix3d closed = geo::RotationEnuFromTurretT<double>(a, e);
    const Eigen::Matrix3d product = geo::RotationEnuFromTurretProductT<double>(a, e, 0.0, 0.0, 0.0, 0.0);
    ASSERT_TRUE((closed.array() == product.array()).all()) << "az " << a << " el " << e << "\n"
                                                            << closed - product;
  }
}

TEST(Projection, EveryFormerPathAgreesWithTheOneLineOfSight) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < kCases; ++i) {
    const Case c = RandomCase(&rng, i);
    SCOPED_TRACE(testing::Message() << "case " << i << " az " << geo::RadToDeg(c.az) << " el "
                                    << geo::RadToDeg(c.el));
    const Eigen::Vector3d ray = c.cam.RayEnu(c.px, c.az, c.el, c.terms);
    ASSERT_NEAR(ray.norm(), 1.0, 1e-15);

    // rk-attitude, rk-pose, rk-sim: the pointing model as an equivalent boresight and mount.
    const StationView view = ApplyPointing(c.cam, {c.az, c.el}, c.terms);
    const Eigen::Vector3d via_view =
        CameraInView(c.cam, view).RayEnu(c.px, view.boresight.az_rad, view.boresight.el_rad);
    EXPECT_LT(Angle(ray, via_view), kAgreeRad);

    // rk-locate's σ model evaluated at its nominal point (the function whose jet gives the σ).
    locate::SigmaPoint p;
    p.px = c.px;
    p.az_rad = c.az;
    p.el_rad = c.el;
    p.range_m = 1000.0;
    const auto y = locate::LocatedFunction(c.cam, p, locate::SigmaNominal(c.cam, c.terms, p));
    EXPECT_THAT((geo::AzEl{y(0), y(1)}), test::AzElNear(geo::AzElFromEnu(ray), kAgreeRad));
    EXPECT_THAT(Eigen::Vector3d(y.tail<3>()), test::EnuNear(1000.0 * ray, 1000.0 * kAgreeRad));

    // rk-analyze budget's locate model.
    PointingModel pm;
    pm.terms = c.terms;
    const io::Json nominal = {{"boresight_az_deg", geo::RadToDeg(c.az)}, {"boresight_el_deg", geo::RadToDeg(c.el)},
                              {"x_px", c.px.x()}, {"y_px", c.px.y()}, {"range_m", 1000.0}};
    const auto model = analysis::MakeLocateBudgetModel(nominal, c.cam, pm, "budget");
    Eigen::VectorXd out;
    ASSERT_TRUE(model->Evaluate(model->NominalInputs(), &out));
    const Eigen::Vector3d ray_deg = c.cam.RayEnu(c.px, geo::DegToRad(geo::RadToDeg(c.az)),
                                                 geo::DegToRad(geo::RadToDeg(c.el)), c.terms);
    EXPECT_LT((out.tail<3>() - 1000.0 * ray_deg).norm(), 1000.0 * kAgreeRad);

    // rk-calibrate pointing: the residual of a target seen exactly along the ray is zero (the projection back
    // through the Newton undistortion, to a round trip's accuracy).
    calibrate::PointingObservation o;
    o.px = c.px;
    o.az_log_rad = c.az;
    o.el_log_rad = c.el;
    o.dir_enu = ray;
    const calibrate::PointingPixelCost cost(o, c.cam.ToIntrinsics(), 0.0);
    std::array<double, calibrate::kNumPointingParams> x{};
    x[calibrate::kParamAzOffset] = c.terms.az_offset_rad;
    x[calibrate::kParamTiltNorth] = c.terms.tilt_north_rad;
    x[calibrate::kParamTiltEast] = c.terms.tilt_east_rad;
    x[calibrate::kParamElAxisTilt] = c.terms.el_axis_tilt_rad;
    x[calibrate::kParamMountYaw] = c.cam.mount_yaw_rad;
    x[calibrate::kParamMountPitch] = c.cam.mount_pitch_rad;
    x[calibrate::kParamMountRoll] = c.cam.mount_roll_rad;
    const double zero2[2] = {0.0, 0.0};
    double r[2];
    ASSERT_TRUE(cost(x.data(), zero2, zero2, r));
    EXPECT_LT(std::hypot(r[0], r[1]), kBackToPixelPx);

    // And back: with the pointing terms folded into the view, ProjectEnu returns the pixel.
    const auto back = CameraInView(c.cam, view).ProjectEnu(ray, view.boresight.az_rad, view.boresight.el_rad);
    ASSERT_TRUE(back.has_value());
    EXPECT_LT((*back - c.px).norm(), kBackToPixelPx);
  }
}

// The jet derivative of the line of sight with respect to every quantity it depends on, against central
// differences of the double evaluation.
TEST(Projection, JetDerivativesMatchCentralDifferences) {
  constexpr int kN = 12;  // x, y, az, el, 4 pointing terms, 3 mount angles, focal scale
  using J = ceres::Jet<double, kN>;
  const auto sight = [](const auto* v, auto zero) {
    using T = decltype(zero);
    SightParams<T> s;
    s.az_rad = v[2], s.el_rad = v[3];
    s.az_offset_rad = v[4], s.tilt_north_rad = v[5], s.tilt_east_rad = v[6], s.el_axis_tilt_rad = v[7];
    s.mount_yaw_rad = v[8], s.mount_pitch_rad = v[9], s.mount_roll_rad = v[10];
    s.focal_scale = v[11];
    return s;
  };
  std::mt19937_64 rng(9);
  double worst = 0.0;
  for (int i = 0; i < 100; ++i) {
    const Case c = RandomCase(&rng, i);
    const Intrinsics in = c.cam.ToIntrinsics();
    const double v0[kN] = {c.px.x(), c.px.y(), c.az, c.el, c.terms.az_offset_rad, c.terms.tilt_north_rad,
                           c.terms.tilt_east_rad, c.terms.el_axis_tilt_rad, c.cam.mount_yaw_rad,
                           c.cam.mount_pitch_rad, c.cam.mount_roll_rad, 1.0};
    J vj[kN];
    for (int k = 0; k < kN; ++k) vj[k] = J(v0[k], k);
    const Eigen::Matrix<J, 3, 1> ray = RayEnuT<J>(in, vj[0], vj[1], sight(vj, J(0.0)));
    for (int k = 0; k < kN; ++k) {
      const double h = k < 2 ? 1e-3 : 1e-6;
      double vp[kN], vm[kN];
      std::copy(v0, v0 + kN, vp);
      std::copy(v0, v0 + kN, vm);
      vp[k] += h;
      vm[k] -= h;
      const Eigen::Vector3d d = (RayEnuT<double>(in, vp[0], vp[1], sight(vp, 0.0)) -
                                 RayEnuT<double>(in, vm[0], vm[1], sight(vm, 0.0))) / (2 * h);
      const Eigen::Vector3d a(ray(0).v(k), ray(1).v(k), ray(2).v(k));
      const double rel = (a - d).norm() / std::max(d.norm(), 1e-9);
      worst = std::max(worst, rel);
      EXPECT_LT(rel, kDerivativeRel) << "case " << i << " input " << k << " jet " << a.transpose() << " numeric "
                                     << d.transpose();
    }
    // The jet's value is the double evaluation (to rounding: a jet divides by multiplying with the inverse).
    const Eigen::Vector3d value = RayEnuT<double>(in, v0[0], v0[1], sight(v0, 0.0));
    EXPECT_LT((Eigen::Vector3d(ray(0).a, ray(1).a, ray(2).a) - value).norm(), kAgreeRad);
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
}

TEST(Projection, PixelToRayAndBackOverTheSensorOfRandomLenses) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 100; ++i) {
    const Case c = RandomCase(&rng, i);
    const Intrinsics in = c.cam.ToIntrinsics();
    for (double fx = 0.0; fx <= 1.0; fx += 0.25) {
      for (double fy = 0.0; fy <= 1.0; fy += 0.25) {
        const double x = fx * (c.cam.width_px - 1), y = fy * (c.cam.height_px - 1);
        const Eigen::Vector2d n = NormalisedFromPixelT<double>(in, x, y);
        const Eigen::Vector2d p = PixelFromNormalisedT<double>(in, n.x(), n.y());
        EXPECT_LT((p - Eigen::Vector2d(x, y)).norm(), kBackToPixelPx) << "case " << i << " pixel " << x << ", " << y;
      }
    }
  }
}

}  // namespace
}  // namespace rk::camera

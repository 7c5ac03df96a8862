// Marker identification against the target model (extract/features_identify.h): spurious, missing and
// shuffled detections; symmetric layouts and too few markers refused.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "extract/features_identify.h"
#include "geo/angles.h"
#include "sim/attitude_problems.h"
#include "target/feature_model.h"
#include "test_default_model.h"

namespace rk::extract {
namespace {

// Detections from a random view of the model with the attitude camera.
std::vector<Eigen::Vector2d> View(const target::FeatureModel& m, std::uint64_t k, double range_m) {
  const Eigen::Matrix3d R = sim::RandomRotation(31, k);
  const camera::CameraModel cam = sim::AttitudeCamera();
  std::vector<Eigen::Vector2d> px;
  for (const auto& p : m.p_body) px.push_back(*cam.Project(R * p + Eigen::Vector3d(0.01, -0.02, range_m)));
  return px;
}

TEST(Identify, AssignsIdsDespiteSpuriousMissingAndShuffledDetections) {
  const target::FeatureModel model = DefaultModel();
  const AffineCameraModel affine(model);
  EXPECT_FALSE(affine.planar());
  int identified_views = 0;
  for (std::uint64_t k = 0; k < 40; ++k) {
    const std::vector<Eigen::Vector2d> px = View(model, k, 20.0);
    // Views where two markers nearly overlap cannot be told apart by geometry: skip them.
    double min_sep = 1e9;
    for (std::size_t i = 0; i < px.size(); ++i) {
      for (std::size_t j = i + 1; j < px.size(); ++j) min_sep = std::min(min_sep, (px[i] - px[j]).norm());
    }
    if (min_sep < 60.0) continue;
    std::vector<Eigen::Vector2d> det;
    std::vector<int> truth_of_det;
    for (std::size_t i = 0; i < px.size(); ++i) {
      if (i == k % px.size()) continue;  // one marker hidden
      det.push_back(px[i]);
      truth_of_det.push_back(static_cast<int>(i));
    }
    det.push_back(px[0] + Eigen::Vector2d(400, 230));  // two glints
    truth_of_det.push_back(-1);
    det.push_back(px[3] + Eigen::Vector2d(-350, 180));
    truth_of_det.push_back(-1);
    std::mt19937_64 rng(k);
    std::vector<std::size_t> order(det.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<Eigen::Vector2d> shuffled;
    std::vector<int> truth_sh;
    for (std::size_t i : order) {
      shuffled.push_back(det[i]);
      truth_sh.push_back(truth_of_det[i]);
    }
    const Identification id = Identify(shuffled, model, affine, IdentifyOptions{});
    if (!id.ok) {
      // Refusing is allowed (never a wrong answer); it must say why.
      EXPECT_FALSE(id.why.empty());
      continue;
    }
    ++identified_views;
    for (std::size_t i = 0; i < model.size(); ++i) {
      const int d = id.detection_of_model[i];
      if (d >= 0) {
        EXPECT_EQ(truth_sh[static_cast<std::size_t>(d)], static_cast<int>(i)) << "view " << k;
      }
    }
    EXPECT_EQ(id.identified, 7);
  }
  EXPECT_GE(identified_views, 20);
}

TEST(Identify, RefusesASymmetricLayoutAndTooFewMarkers) {
  // A layout symmetric about the body x-z plane, seen along the body y axis: mirrored
  // assignments explain the image equally well → refused, never a guess.
  target::FeatureModel sym;
  sym.source = "sym.json";
  sym.ids = {"a", "b", "c", "d", "e", "f"};
  sym.p_body = {{0.4, 0.3, 0.0}, {0.4, -0.3, 0.0}, {-0.3, 0.2, 0.1}, {-0.3, -0.2, 0.1}, {0.0, 0.0, -0.3},
                {0.1, 0.0, 0.25}};
  const AffineCameraModel affine(sym);
  const camera::CameraModel cam = sim::AttitudeCamera();
  // Looking down the body z axis (the symmetry plane x-z contains the line of sight).
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  std::vector<Eigen::Vector2d> px;
  for (const auto& p : sym.p_body) {
    const Eigen::Vector3d q = R * Eigen::Vector3d(p.x(), p.z(), p.y());  // body y along the line of sight
    px.push_back(*cam.Project(q + Eigen::Vector3d(0, 0, 25.0)));
  }
  const Identification id = Identify(px, sym, affine, IdentifyOptions{});
  EXPECT_FALSE(id.ok);
  EXPECT_TRUE(id.ambiguous) << id.why;
  const target::FeatureModel model = DefaultModel();
  const AffineCameraModel a2(model);
  std::vector<Eigen::Vector2d> four = View(model, 1, 20.0);
  four.resize(4);
  const Identification few = Identify(four, model, a2, IdentifyOptions{});
  EXPECT_FALSE(few.ok);
  EXPECT_NE(few.why.find("needed"), std::string::npos);
}

}  // namespace
}  // namespace rk::extract

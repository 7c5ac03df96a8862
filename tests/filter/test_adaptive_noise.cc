// Innovation covariance estimation (filter/adaptive_noise.h): the window and fading estimates equal their
// direct sums.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "filter/adaptive_noise.h"
#include "filter/ukf.h"
#include "test_tolerances.h"

namespace rk::filter {
namespace {

TEST(AdaptiveNoise, WindowAndFadingMatchDirectSums) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  AdaptiveNoiseOptions wo;
  wo.window = 4;
  AdaptiveNoiseOptions fo;
  fo.memory = AdaptMemory::kFading;
  fo.fading = 0.8;
  InnovationCovariance cw, cf;
  cw.Reset(2, wo);
  cf.Reset(2, fo);
  std::vector<ukf::MeasVec> ds;
  for (int k = 0; k < 9; ++k) {
    ukf::MeasVec d(2);
    d << g(rng), g(rng);
    ds.push_back(d);
    ukf::MeasMat hph = ukf::MeasMat::Identity(2, 2) * (k + 1.0);
    cw.Add(d, hph);
    cf.Add(d, hph);
  }
  Eigen::Matrix2d Cw = Eigen::Matrix2d::Zero(), Cf = Eigen::Matrix2d::Zero();
  double wsum = 0;
  for (int k = 5; k < 9; ++k) Cw += ds[static_cast<std::size_t>(k)] * ds[static_cast<std::size_t>(k)].transpose();
  Cw /= 4;
  for (int k = 0; k < 9; ++k) {
    const double lw = std::pow(0.8, 8 - k);
    Cf += lw * ds[static_cast<std::size_t>(k)] * ds[static_cast<std::size_t>(k)].transpose();
    wsum += lw;
  }
  Cf /= wsum;
  EXPECT_LT((Eigen::Matrix2d(cw.C()) - Cw).norm(), kExactTolerance);
  EXPECT_LT((Eigen::Matrix2d(cf.C()) - Cf).norm(), kExactTolerance);
  EXPECT_NEAR(cw.HPH()(0, 0), (6 + 7 + 8 + 9) / 4.0, kExactTolerance);
  EXPECT_TRUE(cw.Ready());
  EXPECT_EQ(fo.Warmup(), 5);
}

}  // namespace
}  // namespace rk::filter

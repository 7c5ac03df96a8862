// The "locate" error-budget model (analysis/budget_locate.h): its autodiff Jacobian against central
// differences.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/budget.h"
#include "test_locate_model.h"

namespace rk::analysis {
namespace {

TEST(Budget, LocateJacobianMatchesCentralDifferences) {
  for (double az : {0.0, 123.0, 359.9}) {
    for (double el : {-5.0, 30.0, 80.0}) {
      const auto m = Locate(az, el, 2100.0, 300.0);
      Eigen::MatrixXd Jn;
      ASSERT_TRUE(NumericalJacobian(*m, m->NominalInputs(), &Jn));
      const Eigen::MatrixXd J = m->Jacobian();
      EXPECT_LT((J - Jn).cwiseAbs().maxCoeff(), kJacobianRel * Jn.cwiseAbs().maxCoeff()) << az << " " << el;
      // Azimuth error of a boresight azimuth error is exactly 1 for the image centre... roughly here.
      EXPECT_NEAR(J(0, 0), 1.0, 0.05);
    }
  }
}

}  // namespace
}  // namespace rk::analysis

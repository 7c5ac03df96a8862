// Test-support library (tests/support): temporary folders and the domain matchers' helpers.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <fstream>
#include <system_error>

#include "rk_test/matchers.h"
#include "rk_test/temp_dir.h"

namespace rk::test {

TempDir::TempDir(const std::string& tag) {
  std::string templ = (std::filesystem::temp_directory_path() / ("rk_" + tag + ".XXXXXX")).string();
  if (::mkdtemp(templ.data()) == nullptr) ADD_FAILURE() << "cannot make a temporary folder " << templ;
  path_ = templ;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void WriteFile(const std::string& path, const std::string& text) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  std::ofstream f(path, std::ios::binary);
  f << text;
  if (!f) ADD_FAILURE() << "cannot write " << path;
}

double RotationAngleRad(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  // Through the quaternion, 2·atan2(|v|, |w|): exact near zero, where acos((trace − 1)/2) bottoms out at ≈ 2e-8 rad.
  const Eigen::Quaterniond q(a.transpose() * b);
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

void PrintTo(const Pose& p, std::ostream* os) {
  const Eigen::AngleAxisd aa(p.R);
  *os << "rotation " << geo::RadToDeg(aa.angle()) << " deg about (" << aa.axis().transpose() << "), position ("
      << p.t.transpose() << ") m";
}

}  // namespace rk::test

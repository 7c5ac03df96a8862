// Budget model "locate"; see budget_locate.h.
#include "analysis/budget_locate.h"

#include "analysis/budget_autodiff.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"

namespace rk::analysis {
namespace {

class LocateModel : public BudgetModel {
 public:
  LocateModel(const camera::CameraModel& cam, double az, double el, double x, double y, double range)
      : cam_(cam) {
    inputs_ = {{"boresight_az", BudgetUnit::kAngle, az, true},
               {"boresight_el", BudgetUnit::kAngle, el, false},
               {"x", BudgetUnit::kPixel, x, false},
               {"y", BudgetUnit::kPixel, y, false},
               {"range", BudgetUnit::kLength, range, false}};
    Eigen::VectorXd y0;
    Evaluate(NominalInputs(), &y0);
    outputs_ = {{"az", BudgetUnit::kAngle, y0(0), true},
                {"el", BudgetUnit::kAngle, y0(1), false},
                {"e", BudgetUnit::kLength, y0(2), false},
                {"n", BudgetUnit::kLength, y0(3), false},
                {"u", BudgetUnit::kLength, y0(4), false}};
    groups_ = {{"boresight", {0, 1}}, {"pixels", {2, 3}}};
  }
  std::string Name() const override { return "locate"; }
  std::string Description() const override {
    return "pixel + boresight angles + range -> line-of-sight az/el and ENU position (rk-locate, SPEC.md 3)";
  }
  bool Evaluate(const Eigen::VectorXd& x, Eigen::VectorXd* y) const override {
    const Eigen::Vector3d ray = cam_.RayEnu(Eigen::Vector2d(x(2), x(3)), x(0), x(1));
    const geo::AzEl ae = geo::AzElFromEnu(ray);
    y->resize(5);
    *y << ae.az_rad, ae.el_rad, x(4) * ray;
    return true;
  }
  Eigen::MatrixXd Jacobian() const override {
    using J = ceres::Jet<double, 5>;
    const Eigen::VectorXd x0 = NominalInputs();
    J x[5];
    for (int i = 0; i < 5; ++i) x[i] = J(x0(i), i);
    const Eigen::Matrix<J, 3, 1> ray = RayEnuAutodiff<J>(cam_, Eigen::Vector2d(x0(2), x0(3)), x[2], x[3], x[0], x[1]);
    J out[5];
    AzElAutodiff<J>(ray, &out[0], &out[1]);
    for (int k = 0; k < 3; ++k) out[2 + k] = x[4] * ray(k);
    Eigen::MatrixXd D(5, 5);
    for (int k = 0; k < 5; ++k) D.row(k) = out[k].v.transpose();
    return D;
  }
  io::Json NominalJson() const override {
    const Eigen::VectorXd x0 = NominalInputs();
    return {{"boresight_az_deg", geo::RadToDeg(x0(0))}, {"boresight_el_deg", geo::RadToDeg(x0(1))},
            {"x_px", x0(2)}, {"y_px", x0(3)}, {"range_m", x0(4)}, {"camera", camera::CameraModelToJson(cam_)}};
  }

 private:
  camera::CameraModel cam_;
};

}  // namespace

std::unique_ptr<BudgetModel> MakeLocateBudgetModel(const io::Json& nominal, const camera::CameraModel& camera,
                                                   const std::string& where) {
  if (!nominal.is_object()) throw DataError(where, 0, 0, "\"nominal\" must be an object");
  const std::string w = where + ": nominal";
  const double az = io::RequireNumber(nominal, "boresight_az_deg", w);
  const double el = io::RequireNumber(nominal, "boresight_el_deg", w);
  if (el < -90.0 || el > 90.0) throw DataError(where, 0, 0, "nominal boresight_el_deg must be in [-90, 90]");
  const double x = io::RequireNumber(nominal, "x_px", w);
  const double y = io::RequireNumber(nominal, "y_px", w);
  const double r = io::RequireNumber(nominal, "range_m", w);
  if (!(r > 0.0)) throw DataError(where, 0, 0, "nominal range_m must be > 0");
  return std::make_unique<LocateModel>(camera, geo::DegToRad(az), geo::DegToRad(el), x, y, r);
}

}  // namespace rk::analysis

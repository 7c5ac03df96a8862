// Budget model "locate"; see budget_locate.h.
#include "analysis/budget_locate.h"

#include <ceres/jet.h>

#include <cstdio>

#include "camera/projection.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"

namespace rk::analysis {
namespace {

enum LocateInput {
  kAz = 0, kEl = 1, kX = 2, kY = 3, kRange = 4, kTerm0 = 5, kMount0 = 9, kLocateInputs = 12
};
constexpr const char* kTermNames[4] = {"az_offset", "tilt_north", "tilt_east", "el_axis_tilt"};
constexpr const char* kMountNames[3] = {"mount_yaw", "mount_pitch", "mount_roll"};

// The line-of-sight parameters of input vector x (any scalar).
template <typename T, typename V>
camera::SightParams<T> SightOf(const V& x) {
  camera::SightParams<T> s;
  s.az_rad = x[kAz];
  s.el_rad = x[kEl];
  s.az_offset_rad = x[kTerm0];
  s.tilt_north_rad = x[kTerm0 + 1];
  s.tilt_east_rad = x[kTerm0 + 2];
  s.el_axis_tilt_rad = x[kTerm0 + 3];
  s.mount_yaw_rad = x[kMount0];
  s.mount_pitch_rad = x[kMount0 + 1];
  s.mount_roll_rad = x[kMount0 + 2];
  return s;
}

class LocateModel : public BudgetModel {
 public:
  LocateModel(const camera::CameraModel& cam, const geo::PointingTerms& terms, double az, double el, double x,
              double y, double range)
      : cam_(cam), intrinsics_(cam.ToIntrinsics()) {
    inputs_ = {{"boresight_az", BudgetUnit::kAngle, az, true},
               {"boresight_el", BudgetUnit::kAngle, el, false},
               {"x", BudgetUnit::kPixel, x, false},
               {"y", BudgetUnit::kPixel, y, false},
               {"range", BudgetUnit::kLength, range, false},
               {kTermNames[0], BudgetUnit::kAngle, terms.az_offset_rad, false},
               {kTermNames[1], BudgetUnit::kAngle, terms.tilt_north_rad, false},
               {kTermNames[2], BudgetUnit::kAngle, terms.tilt_east_rad, false},
               {kTermNames[3], BudgetUnit::kAngle, terms.el_axis_tilt_rad, false},
               {kMountNames[0], BudgetUnit::kAngle, cam.mount_yaw_rad, false},
               {kMountNames[1], BudgetUnit::kAngle, cam.mount_pitch_rad, false},
               {kMountNames[2], BudgetUnit::kAngle, cam.mount_roll_rad, false}};
    Eigen::VectorXd y0;
    Evaluate(NominalInputs(), &y0);
    outputs_ = {{"az", BudgetUnit::kAngle, y0(0), true},
                {"el", BudgetUnit::kAngle, y0(1), false},
                {"e", BudgetUnit::kLength, y0(2), false},
                {"n", BudgetUnit::kLength, y0(3), false},
                {"u", BudgetUnit::kLength, y0(4), false}};
    groups_ = {{"boresight", {kAz, kEl}},
               {"pixels", {kX, kY}},
               {"pointing", {kTerm0, kTerm0 + 1, kTerm0 + 2, kTerm0 + 3}},
               {"mount", {kMount0, kMount0 + 1, kMount0 + 2}}};
  }
  std::string Name() const override { return "locate"; }
  std::string Description() const override {
    return "pixel + turret angles + pointing model + camera mount + range -> line-of-sight az/el and ENU position "
           "(rk-locate, SPEC.md 3 and 3.1)";
  }
  bool Evaluate(const Eigen::VectorXd& x, Eigen::VectorXd* y) const override {
    const Eigen::Vector3d ray = camera::RayEnuT<double>(intrinsics_, x(kX), x(kY), SightOf<double>(x));
    const geo::AzEl ae = geo::AzElFromEnu(ray);
    y->resize(5);
    *y << ae.az_rad, ae.el_rad, x(kRange) * ray;
    return true;
  }
  Eigen::MatrixXd Jacobian() const override {
    using J = ceres::Jet<double, kLocateInputs>;
    const Eigen::VectorXd x0 = NominalInputs();
    J x[kLocateInputs];
    for (int i = 0; i < kLocateInputs; ++i) x[i] = J(x0(i), i);
    const Eigen::Matrix<J, 3, 1> ray = camera::RayEnuT<J>(intrinsics_, x[kX], x[kY], SightOf<J>(x));
    J out[5];
    camera::AzElT<J>(ray, &out[0], &out[1]);
    for (int k = 0; k < 3; ++k) out[2 + k] = x[kRange] * ray(k);
    Eigen::MatrixXd D(5, kLocateInputs);
    for (int k = 0; k < 5; ++k) D.row(k) = out[k].v.transpose();
    return D;
  }
  io::Json NominalJson() const override {
    const Eigen::VectorXd x0 = NominalInputs();
    io::Json pointing = io::Json::object();
    for (int i = 0; i < 4; ++i) pointing[std::string(kTermNames[i]) + "_deg"] = geo::RadToDeg(x0(kTerm0 + i));
    return {{"boresight_az_deg", geo::RadToDeg(x0(kAz))},
            {"boresight_el_deg", geo::RadToDeg(x0(kEl))},
            {"x_px", x0(kX)},
            {"y_px", x0(kY)},
            {"range_m", x0(kRange)},
            {"camera", camera::CameraModelToJson(cam_)},
            {"pointing", pointing}};
  }

 private:
  camera::CameraModel cam_;
  camera::Intrinsics intrinsics_;
};

BudgetSource CalibratedSource(const std::string& name, int input, double sigma_rad, const std::string& from) {
  char given[96];
  std::snprintf(given, sizeof given, "%.6g arcsec (%s)", geo::RadToDeg(sigma_rad) * 3600.0, from.c_str());
  BudgetSource s;
  s.name = name;
  s.inputs = {input};
  s.unit = BudgetUnit::kAngle;
  s.sigma_si = sigma_rad;
  s.given = given;
  return s;
}

}  // namespace

std::unique_ptr<BudgetModel> MakeLocateBudgetModel(const io::Json& nominal, const camera::CameraModel& camera,
                                                   const camera::PointingModel& pointing, const std::string& where) {
  if (!nominal.is_object()) throw DataError(where, 0, 0, "\"nominal\" must be an object");
  const std::string w = where + ": nominal";
  const double az = io::RequireNumber(nominal, "boresight_az_deg", w);
  const double el = io::RequireNumber(nominal, "boresight_el_deg", w);
  if (el < -90.0 || el > 90.0) throw DataError(where, 0, 0, "nominal boresight_el_deg must be in [-90, 90]");
  const double x = io::RequireNumber(nominal, "x_px", w);
  const double y = io::RequireNumber(nominal, "y_px", w);
  const double r = io::RequireNumber(nominal, "range_m", w);
  if (!(r > 0.0)) throw DataError(where, 0, 0, "nominal range_m must be > 0");
  return std::make_unique<LocateModel>(camera, pointing.terms, geo::DegToRad(az), geo::DegToRad(el), x, y, r);
}

std::vector<BudgetSource> LocateCalibrationSources(const BudgetModel& model, const camera::CameraModel& camera,
                                                   const camera::PointingModel& pointing,
                                                   const std::string& pointing_file, const std::string& where) {
  const auto index = [&](const char* name) {
    for (std::size_t i = 0; i < model.inputs().size(); ++i) {
      if (model.inputs()[i].name == name) return static_cast<int>(i);
    }
    throw ProcessingError(std::string("budget model has no input ") + name);
  };
  std::vector<BudgetSource> out;
  for (int i = 0; i < 4; ++i) {
    const double s = pointing.sigma_rad[i].value_or(0.0);
    if (s > 0.0) {
      out.push_back(CalibratedSource(std::string("pointing model ") + kTermNames[i], index(kTermNames[i]), s,
                                     pointing_file + " sigma"));
    }
  }
  const camera::CalibrationSigma c = camera::CameraCalibrationSigma(camera, where);
  for (int i = 0; i < 3; ++i) {
    if (c.mount_rad[i] > 0.0) {
      out.push_back(CalibratedSource(std::string("camera ") + kMountNames[i], index(kMountNames[i]), c.mount_rad[i],
                                     "camera calibration sigma"));
    }
  }
  return out;
}

}  // namespace rk::analysis

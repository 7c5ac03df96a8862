// Jacobians (ceres::Jet) and budget models of the seed 004 cylinder attitude; see cylinder_budget.h.
// All automatic differentiation of the attitude module lives in this translation unit.
#include "attitude/cylinder_budget.h"

#include <ceres/jet.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "camera/projection.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"
#include "target/cylinder.h"

namespace rk::attitude {
namespace {

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

// F(R) of cylinder_geometry.h for jet rays and target, double ranges.
template <typename T>
Vec3<T> ResidualsT(const Vec3<T>& u1, const Vec3<T>& u2, const Vec3<T>& u3, const T& slant2, const T& diam2,
                   const Eigen::Vector3d& R) {
  const T k12 = 0.5 * (u1 - u2).squaredNorm();
  const T k13 = 0.5 * (u1 - u3).squaredNorm();
  const T k23 = 0.5 * (u2 - u3).squaredNorm();
  auto side2 = [](double a, double b, const T& k) { return T((a - b) * (a - b)) + 2.0 * a * b * k; };
  return Vec3<T>(side2(R(0), R(1), k12) - slant2, side2(R(0), R(2), k13) - slant2, side2(R(1), R(2), k23) - diam2);
}

// ∂F/∂R at R for double rays (cf. PolishRanges).
Eigen::Matrix3d ResidualJacobian(const RayAngles& a, const Eigen::Vector3d& R) {
  Eigen::Matrix3d J;
  J << 2 * (R(0) - R(1)) + 2 * R(1) * a.k12, 2 * (R(1) - R(0)) + 2 * R(0) * a.k12, 0.0,
      2 * (R(0) - R(2)) + 2 * R(2) * a.k13, 0.0, 2 * (R(2) - R(0)) + 2 * R(0) * a.k13,
      0.0, 2 * (R(1) - R(2)) + 2 * R(2) * a.k23, 2 * (R(2) - R(1)) + 2 * R(1) * a.k23;
  return J;
}

// Axis yaw/pitch from three range-direction pairs (jets).
template <typename T>
void AxisYawPitch(const Vec3<T>& p1, const Vec3<T>& p2, const Vec3<T>& p3, T* yaw, T* pitch) {
  const Vec3<T> axis = p1 - 0.5 * (p2 + p3);
  camera::AzElT<T>(axis, yaw, pitch);
}

// Line of sight through a jet pixel for jet boresight angles (the camera's mount, no pointing terms).
template <typename T>
Vec3<T> RayT(const camera::CameraModel& cam, const T& x_px, const T& y_px, const T& az_rad, const T& el_rad) {
  camera::SightParams<T> s = cam.Sight(0.0, 0.0).cast<T>();
  s.az_rad = az_rad;
  s.el_rad = el_rad;
  return camera::RayEnuT<T>(cam.ToIntrinsics(), x_px, y_px, s);
}

}  // namespace

CylinderRays RaysFromInputs(const camera::CameraModel& cam, const CylinderInputs& x) {
  CylinderRays r;
  r.nose = cam.RayEnu(Eigen::Vector2d(x(2), x(3)), x(0), x(1));
  r.tail1 = cam.RayEnu(Eigen::Vector2d(x(4), x(5)), x(0), x(1));
  r.tail2 = cam.RayEnu(Eigen::Vector2d(x(6), x(7)), x(0), x(1));
  return r;
}

bool CylinderJacobian(const camera::CameraModel& cam, const CylinderInputs& x0, const Eigen::Vector3d& R0,
                      CylinderJacobianMatrix* Jout) {
  using J = ceres::Jet<double, kCylinderInputs>;
  J x[kCylinderInputs];
  for (int i = 0; i < kCylinderInputs; ++i) x[i] = J(x0(i), i);
  const Vec3<J> u1 = RayT<J>(cam, x[2], x[3], x[0], x[1]);
  const Vec3<J> u2 = RayT<J>(cam, x[4], x[5], x[0], x[1]);
  const Vec3<J> u3 = RayT<J>(cam, x[6], x[7], x[0], x[1]);
  const J slant2 = x[8] * x[8] + 0.25 * x[9] * x[9];
  const J diam2 = x[9] * x[9];
  const Vec3<J> F = ResidualsT<J>(u1, u2, u3, slant2, diam2, R0);

  CylinderRays rays;
  rays.nose = Eigen::Vector3d(u1(0).a, u1(1).a, u1(2).a);
  rays.tail1 = Eigen::Vector3d(u2(0).a, u2(1).a, u2(2).a);
  rays.tail2 = Eigen::Vector3d(u3(0).a, u3(1).a, u3(2).a);
  const Eigen::Matrix3d JR = ResidualJacobian(AnglesOf(rays), R0);
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(JR);
  // Singular at a double root; also refuse a numerically singular matrix (relative pivot < 1e-12).
  if (!lu.isInvertible() || std::abs(lu.matrixLU()(2, 2)) < 1e-12 * std::abs(lu.matrixLU()(0, 0))) return false;
  const Eigen::Matrix3d JRinv = lu.inverse();
  Vec3<J> R;
  for (int i = 0; i < 3; ++i) {
    R(i) = J(R0(i));
    for (int j = 0; j < 3; ++j) R(i) -= JRinv(i, j) * F(j);
  }
  J yaw, pitch;
  AxisYawPitch<J>(R(0) * u1, R(1) * u2, R(2) * u3, &yaw, &pitch);
  Jout->row(0) = yaw.v.transpose();
  Jout->row(1) = pitch.v.transpose();
  for (int i = 0; i < 3; ++i) Jout->row(2 + i) = R(i).v.transpose();
  return Jout->allFinite();
}

std::optional<CylinderSolution> SolveNearest(const camera::CameraModel& cam, const CylinderInputs& x,
                                             const CylinderSolveOptions& options, const Eigen::Vector3d& ref_axis) {
  if (!(x(8) > 0.0) || !(x(9) > 0.0)) return std::nullopt;
  const CylinderRays rays = RaysFromInputs(cam, x);
  const target::CylinderShape target{x(8), x(9)};
  const CylinderSolveResult res = SolveCylinder(rays, target, options);
  std::optional<CylinderSolution> best;
  double best_angle = std::numeric_limits<double>::infinity();
  for (const CylinderSolution& s : res.solutions) {
    const double e = AxisAngle(s.axis_enu, ref_axis);
    if (e < best_angle) {
      best_angle = e;
      best = s;
    }
  }
  return best;
}

namespace {

struct Nominal {
  CylinderInputs x0;
  CylinderSolution solution;
  io::Json json;
};

Nominal ParseNominal(const io::Json& nominal, const camera::CameraModel& cam, const CylinderSolveOptions& solve,
                     const std::string& where) {
  if (!nominal.is_object()) throw DataError(where, 0, 0, "\"nominal\" must be an object");
  const std::string w = where + ": nominal";
  if (!nominal.contains("target")) throw DataError(where, 0, 0, "nominal: missing \"target\": {\"length_m\", \"diameter_m\"}");
  target::CylinderShape target;
  target.length_m = io::RequireNumber(nominal.at("target"), "length_m", w + ".target");
  target.diameter_m = io::RequireNumber(nominal.at("target"), "diameter_m", w + ".target");
  std::string why;
  if (!target.Check(&why)) throw DataError(where, 0, 0, "nominal: " + why);
  Nominal n;
  n.json = nominal;
  n.x0(8) = target.length_m;
  n.x0(9) = target.diameter_m;
  Eigen::Vector3d ref_axis;
  if (nominal.contains("scenario")) {
    const io::Json& s = nominal.at("scenario");
    const std::string ws = w + ".scenario";
    const double range = io::RequireNumber(s, "range_m", ws);
    const double az = geo::DegToRad(io::RequireNumber(s, "az_deg", ws));
    const double el = geo::DegToRad(io::RequireNumber(s, "el_deg", ws));
    const double yaw = geo::DegToRad(io::RequireNumber(s, "yaw_deg", ws));
    const double pitch = geo::DegToRad(io::RequireNumber(s, "pitch_deg", ws));
    if (!(range > 0.0)) throw DataError(where, 0, 0, "nominal.scenario.range_m must be > 0");
    const target::CylinderPose pose = target::PoseAt(range, az, el, yaw, pitch, target);
    const target::SilhouettePoints3d p = target::SilhouettePointsOf(pose, target);
    n.x0(0) = az;
    n.x0(1) = el;
    const Eigen::Vector3d* pts[3] = {&p.nose, &p.tail1, &p.tail2};
    for (int i = 0; i < 3; ++i) {
      const auto px = cam.ProjectEnu(*pts[i], az, el);
      if (!px) throw DataError(where, 0, 0, "nominal scenario: a point is behind the camera");
      n.x0(2 + 2 * i) = px->x();
      n.x0(3 + 2 * i) = px->y();
    }
    ref_axis = pose.Axis();
    n.json["view_angle_deg"] = geo::RadToDeg(target::ViewAngle(pose));
  } else {
    n.x0(0) = geo::DegToRad(io::RequireNumber(nominal, "boresight_az_deg", w));
    n.x0(1) = geo::DegToRad(io::RequireNumber(nominal, "boresight_el_deg", w));
    if (!nominal.contains("points_px") || !nominal.at("points_px").is_object())
      throw DataError(where, 0, 0, "nominal: give \"scenario\" or \"points_px\": {\"nose\": [x, y], \"tail1\": ..., \"tail2\": ...}");
    const char* ids[3] = {"nose", "tail1", "tail2"};
    for (int i = 0; i < 3; ++i) {
      const auto v = io::RequireNumbers(nominal.at("points_px"), ids[i], 2, 2, w + ".points_px");
      n.x0(2 + 2 * i) = v[0];
      n.x0(3 + 2 * i) = v[1];
    }
    const std::string branch = nominal.contains("branch") && nominal.at("branch").is_string()
                                   ? nominal.at("branch").get<std::string>()
                                   : "nearer";
    if (branch != "nearer" && branch != "farther")
      throw DataError(where, 0, 0, "nominal.branch must be \"nearer\" or \"farther\"");
    const CylinderSolveResult res = SolveCylinder(RaysFromInputs(cam, n.x0), target, solve);
    if (res.solutions.empty()) throw ProcessingError("the nominal points have no cylinder solution");
    ref_axis = (branch == "nearer" ? res.solutions.front() : res.solutions.back()).axis_enu;
  }
  const auto sol = SolveNearest(cam, n.x0, solve, ref_axis);
  if (!sol) throw ProcessingError("the nominal geometry has no cylinder solution");
  n.solution = *sol;
  n.json["points_px"] = {{"nose", {n.x0(2), n.x0(3)}}, {"tail1", {n.x0(4), n.x0(5)}}, {"tail2", {n.x0(6), n.x0(7)}}};
  n.json["boresight_az_deg"] = geo::RadToDeg(n.x0(0));
  n.json["boresight_el_deg"] = geo::RadToDeg(n.x0(1));
  n.json["solution"] = {{"yaw_deg", geo::RadToDeg(sol->yaw_rad)},
                        {"pitch_deg", geo::RadToDeg(sol->pitch_rad)},
                        {"range_m", {sol->range_m(0), sol->range_m(1), sol->range_m(2)}}};
  n.json["camera"] = camera::CameraModelToJson(cam);
  return n;
}

analysis::BudgetQuantity Q(const char* name, analysis::BudgetUnit unit, double nominal, bool wraps = false) {
  return analysis::BudgetQuantity{name, unit, nominal, wraps};
}

class CylinderModel : public analysis::BudgetModel {
 public:
  CylinderModel(const camera::CameraModel& cam, const CylinderSolveOptions& solve, Nominal nominal)
      : cam_(cam), solve_(solve), nominal_(std::move(nominal)) {
    using analysis::BudgetUnit;
    const CylinderInputs& x = nominal_.x0;
    inputs_ = {Q("boresight_az", BudgetUnit::kAngle, x(0), true), Q("boresight_el", BudgetUnit::kAngle, x(1)),
               Q("nose_x", BudgetUnit::kPixel, x(2)),           Q("nose_y", BudgetUnit::kPixel, x(3)),
               Q("tail1_x", BudgetUnit::kPixel, x(4)),          Q("tail1_y", BudgetUnit::kPixel, x(5)),
               Q("tail2_x", BudgetUnit::kPixel, x(6)),          Q("tail2_y", BudgetUnit::kPixel, x(7)),
               Q("length", BudgetUnit::kLength, x(8)),          Q("diameter", BudgetUnit::kLength, x(9))};
    const CylinderSolution& s = nominal_.solution;
    outputs_ = {Q("yaw", BudgetUnit::kAngle, s.yaw_rad, true), Q("pitch", BudgetUnit::kAngle, s.pitch_rad),
                Q("range_nose", BudgetUnit::kLength, s.range_m(0)), Q("range_tail1", BudgetUnit::kLength, s.range_m(1)),
                Q("range_tail2", BudgetUnit::kLength, s.range_m(2))};
    groups_ = {{"boresight", {0, 1}}, {"pixels", {2, 3, 4, 5, 6, 7}}, {"nose", {2, 3}},
               {"tail", {4, 5, 6, 7}}, {"target_size", {8, 9}}};
  }
  std::string Name() const override { return "cylinder"; }
  std::string Description() const override {
    return "theodolite angles + nose/tail1/tail2 pixels + target size -> axis yaw, pitch and ranges (seed 004, "
           "rk-attitude cylinder)";
  }
  bool Evaluate(const Eigen::VectorXd& x, Eigen::VectorXd* y) const override {
    const CylinderInputs xi = x;
    const auto s = SolveNearest(cam_, xi, solve_, nominal_.solution.axis_enu);
    if (!s) return false;
    y->resize(kCylinderOutputs);
    *y << s->yaw_rad, s->pitch_rad, s->range_m;
    return true;
  }
  Eigen::MatrixXd Jacobian() const override {
    CylinderJacobianMatrix J;
    if (!CylinderJacobian(cam_, nominal_.x0, nominal_.solution.range_m, &J))
      return Eigen::MatrixXd::Constant(kCylinderOutputs, kCylinderInputs, std::numeric_limits<double>::quiet_NaN());
    return J;
  }
  io::Json NominalJson() const override { return nominal_.json; }

 private:
  camera::CameraModel cam_;
  CylinderSolveOptions solve_;
  Nominal nominal_;
};

// Paper §4.3: axis from the three ranges and the three points' theodolite angles.
template <typename T>
void RangesToAxis(const T* x, T* yaw, T* pitch) {
  auto dir = [](const T& az, const T& el) {
    using std::cos;
    using std::sin;
    return Vec3<T>(sin(az) * cos(el), cos(az) * cos(el), sin(el));
  };
  AxisYawPitch<T>(x[0] * dir(x[3], x[4]), x[1] * dir(x[5], x[6]), x[2] * dir(x[7], x[8]), yaw, pitch);
}

class CylinderRangesModel : public analysis::BudgetModel {
 public:
  explicit CylinderRangesModel(Nominal nominal, const CylinderRays& rays) : nominal_(std::move(nominal)) {
    using analysis::BudgetUnit;
    const Eigen::Vector3d& R = nominal_.solution.range_m;
    const geo::AzEl a1 = geo::AzElFromEnu(rays.nose), a2 = geo::AzElFromEnu(rays.tail1),
                    a3 = geo::AzElFromEnu(rays.tail2);
    inputs_ = {Q("R1", BudgetUnit::kLength, R(0)),      Q("R2", BudgetUnit::kLength, R(1)),
               Q("R3", BudgetUnit::kLength, R(2)),      Q("A1", BudgetUnit::kAngle, a1.az_rad, true),
               Q("E1", BudgetUnit::kAngle, a1.el_rad),  Q("A2", BudgetUnit::kAngle, a2.az_rad, true),
               Q("E2", BudgetUnit::kAngle, a2.el_rad),  Q("A3", BudgetUnit::kAngle, a3.az_rad, true),
               Q("E3", BudgetUnit::kAngle, a3.el_rad)};
    Eigen::VectorXd y0;
    Evaluate(NominalInputs(), &y0);
    outputs_ = {Q("yaw", BudgetUnit::kAngle, y0(0), true), Q("pitch", BudgetUnit::kAngle, y0(1))};
    groups_ = {{"ranges", {0, 1, 2}}, {"angles", {3, 4, 5, 6, 7, 8}}};
  }
  std::string Name() const override { return "cylinder-ranges"; }
  std::string Description() const override {
    return "ranges R1..R3 + theodolite angles of the three points -> axis yaw, pitch (seed 004 eqs. 5-9)";
  }
  bool Evaluate(const Eigen::VectorXd& x, Eigen::VectorXd* y) const override {
    double yaw = 0, pitch = 0;
    RangesToAxis<double>(x.data(), &yaw, &pitch);
    y->resize(2);
    *y << geo::WrapTwoPi(yaw), pitch;
    return true;
  }
  Eigen::MatrixXd Jacobian() const override {
    using J = ceres::Jet<double, 9>;
    J x[9];
    const Eigen::VectorXd x0 = NominalInputs();
    for (int i = 0; i < 9; ++i) x[i] = J(x0(i), i);
    J yaw, pitch;
    RangesToAxis<J>(x, &yaw, &pitch);
    Eigen::MatrixXd D(2, 9);
    D.row(0) = yaw.v.transpose();
    D.row(1) = pitch.v.transpose();
    return D;
  }
  io::Json NominalJson() const override { return nominal_.json; }

 private:
  Nominal nominal_;
};

}  // namespace

std::unique_ptr<analysis::BudgetModel> MakeCylinderBudgetModel(const io::Json& nominal, const camera::CameraModel& cam,
                                                               const CylinderSolveOptions& solve,
                                                               const std::string& where) {
  return std::make_unique<CylinderModel>(cam, solve, ParseNominal(nominal, cam, solve, where));
}

std::unique_ptr<analysis::BudgetModel> MakeCylinderRangesBudgetModel(const io::Json& nominal,
                                                                     const camera::CameraModel& cam,
                                                                     const CylinderSolveOptions& solve,
                                                                     const std::string& where) {
  Nominal n = ParseNominal(nominal, cam, solve, where);
  const CylinderRays rays = RaysFromInputs(cam, n.x0);
  return std::make_unique<CylinderRangesModel>(std::move(n), rays);
}

}  // namespace rk::attitude

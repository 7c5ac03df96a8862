// Seed 004 geometry; equations in cylinder_geometry.h.
#include "attitude/cylinder_geometry.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geo/angles.h"
#include "geo/line_of_sight.h"

namespace rk::attitude {
namespace {

// 1 − u·v for unit vectors, without cancellation.
double Versine(const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return 0.5 * (u - v).squaredNorm(); }

}  // namespace

RayAngles AnglesOf(const CylinderRays& r) {
  RayAngles a;
  a.k12 = Versine(r.nose, r.tail1);
  a.k13 = Versine(r.nose, r.tail2);
  a.k23 = Versine(r.tail1, r.tail2);
  a.c12 = 1.0 - a.k12;
  a.c13 = 1.0 - a.k13;
  a.c23 = 1.0 - a.k23;
  a.s12 = r.nose.cross(r.tail1).norm();
  a.s13 = r.nose.cross(r.tail2).norm();
  a.s23 = r.tail1.cross(r.tail2).norm();
  return a;
}

Eigen::Vector3d DistanceResiduals(const RayAngles& a, const target::CylinderShape& t,
                                  const Eigen::Vector3d& R) {
  const double L2 = t.SlantM() * t.SlantM();
  const double d2 = t.diameter_m * t.diameter_m;
  auto side2 = [](double x, double y, double k) { return (x - y) * (x - y) + 2.0 * x * y * k; };
  return {side2(R(0), R(1), a.k12) - L2, side2(R(0), R(2), a.k13) - L2, side2(R(1), R(2), a.k23) - d2};
}

double AxisAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

CylinderSolution SolutionFromRanges(const CylinderRays& rays, const RayAngles& a,
                                    const target::CylinderShape& t, const Eigen::Vector3d& R) {
  CylinderSolution s;
  s.range_m = R;
  s.nose_enu = R(0) * rays.nose;
  const Eigen::Vector3d p2 = R(1) * rays.tail1;
  const Eigen::Vector3d p3 = R(2) * rays.tail2;
  s.tail_centre_enu = 0.5 * (p2 + p3);
  // Axis from differences of the ranges along nearly parallel rays: P1 − s0 =
  // R1 u1 − (R2 u2 + R3 u3)/2, evaluated as such (each term is ~1e3 m, the result ~1 m, and double keeps
  // ~1e-13 m absolute: enough).
  const Eigen::Vector3d axis = s.nose_enu - s.tail_centre_enu;
  s.axis_enu = axis.normalized();
  const geo::AzEl ae = geo::AzElFromEnu(axis);
  s.yaw_rad = ae.az_rad;
  s.pitch_rad = ae.el_rad;
  const Eigen::Vector3d F = DistanceResiduals(a, t, R);
  const double L = t.SlantM();
  s.miss_m = std::max({std::abs(F(0)) / (2 * L), std::abs(F(1)) / (2 * L), std::abs(F(2)) / (2 * t.diameter_m)});
  const Eigen::Vector3d bc = p2 - p3;
  const double n = s.tail_centre_enu.norm();
  s.edge_tilt_rad = n > 0 && bc.norm() > 0 ? std::asin(std::min(1.0, std::abs(bc.dot(s.tail_centre_enu)) / (n * bc.norm())))
                                           : 0.0;
  return s;
}

BranchPoint EvaluateBranch(const RayAngles& a, const target::CylinderShape& t, int s2, int s3, double R1) {
  BranchPoint p;
  p.R1 = R1;
  const double L = t.SlantM();
  double q2 = (L - R1 * a.s12) * (L + R1 * a.s12);
  double q3 = (L - R1 * a.s13) * (L + R1 * a.s13);
  // At the end of the real branches (R1 = L'/s) rounding may leave −1e-16 L'²: that is the joint, q = 0.
  const double tiny = 1e-12 * L * L;
  if (q2 < 0.0 && q2 > -tiny) q2 = 0.0;
  if (q3 < 0.0 && q3 > -tiny) q3 = 0.0;
  if (q2 < 0.0 || q3 < 0.0 || !(R1 > 0.0)) return p;
  p.R2 = R1 * a.c12 + s2 * std::sqrt(q2);
  p.R3 = R1 * a.c13 + s3 * std::sqrt(q3);
  if (!(p.R2 > 0.0) || !(p.R3 > 0.0)) return p;
  p.f = (p.R2 - p.R3) * (p.R2 - p.R3) + 2.0 * p.R2 * p.R3 * a.k23 - t.diameter_m * t.diameter_m;
  p.valid = true;
  return p;
}

double MaxNoseRange(const RayAngles& a, const target::CylinderShape& t) {
  const double s = std::max(a.s12, a.s13);
  return s > 0.0 ? t.SlantM() / s : std::numeric_limits<double>::infinity();
}

Eigen::Vector3d PolishRanges(const RayAngles& a, const target::CylinderShape& t, const Eigen::Vector3d& R0,
                             int iterations) {
  Eigen::Vector3d R = R0;
  Eigen::Vector3d F = DistanceResiduals(a, t, R);
  double norm = F.norm();
  for (int it = 0; it < iterations && norm > 0.0; ++it) {
    // d/dRi of (Ri − Rj)² + 2 Ri Rj k = 2(Ri − Rj) + 2 Rj k.
    Eigen::Matrix3d J;
    J << 2 * (R(0) - R(1)) + 2 * R(1) * a.k12, 2 * (R(1) - R(0)) + 2 * R(0) * a.k12, 0.0,
        2 * (R(0) - R(2)) + 2 * R(2) * a.k13, 0.0, 2 * (R(2) - R(0)) + 2 * R(0) * a.k13,
        0.0, 2 * (R(1) - R(2)) + 2 * R(2) * a.k23, 2 * (R(2) - R(1)) + 2 * R(1) * a.k23;
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(J);
    if (!lu.isInvertible()) break;
    const Eigen::Vector3d next = R - lu.solve(F);
    const Eigen::Vector3d Fn = DistanceResiduals(a, t, next);
    if (!(Fn.norm() < norm)) break;
    R = next;
    F = Fn;
    norm = Fn.norm();
  }
  return R;
}

}  // namespace rk::attitude

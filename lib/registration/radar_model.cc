#include "registration/radar_model.h"

#include <Eigen/Householder>
#include <Eigen/QR>
#include <cmath>

#include "geo/angles.h"
#include "geo/wgs84.h"
#include "numeric/golden_section.h"

namespace rk::registration {

const char* BiasColumnSuffix(int index) {
  static const char* const kSuffix[kRadarBiasDim] = {"range_m", "az_deg", "el_deg", "yaw_deg", "pitch_deg",
                                                     "roll_deg"};
  return kSuffix[index];
}
const char* BiasSigmaColumnSuffix(int index) {
  static const char* const kSuffix[kRadarBiasDim] = {"range_sigma_m", "az_sigma_deg",    "el_sigma_deg",
                                                     "yaw_sigma_deg", "pitch_sigma_deg", "roll_sigma_deg"};
  return kSuffix[index];
}
const char* BiasName(int index) {
  static const char* const kName[kRadarBiasDim] = {"range", "az", "el", "yaw", "pitch", "roll"};
  return kName[index];
}
double BiasToFileUnit(int index) { return index == kBiasRange ? 1.0 : geo::RadToDeg(1.0); }

Vec3 PlatformPointFromSpherical(double range_m, double az_rad, double el_rad) {
  const double ce = std::cos(el_rad);
  return Vec3(range_m * std::sin(az_rad) * ce, range_m * std::cos(az_rad) * ce, range_m * std::sin(el_rad));
}

Eigen::Vector3d SphericalFromPlatformPoint(const Vec3& p) {
  const double horiz = std::hypot(p.x(), p.y());
  return Eigen::Vector3d(p.norm(), geo::WrapTwoPi(std::atan2(p.x(), p.y())), std::atan2(p.z(), horiz));
}

Mat3 SphericalBiasJacobian(double r, double th, double ph) {
  const double st = std::sin(th), ct = std::cos(th), sp = std::sin(ph), cp = std::cos(ph);
  Mat3 M;
  M << -st * cp, -r * ct * cp, r * st * sp,  //
      -ct * cp, r * st * cp, r * ct * sp,    //
      -sp, 0.0, -r * cp;
  return M;
}

Mat3 RotationEnuFromPlatform(double yaw, double pitch, double roll) {
  const double cy = std::cos(yaw), sy = std::sin(yaw), cp = std::cos(pitch), sp = std::sin(pitch),
               cr = std::cos(roll), sr = std::sin(roll);
  Mat3 T;
  T << cy * cr + sy * sp * sr, sy * cp, sy * sp * cr - cy * sr,  //
      cy * sp * sr - sy * cr, cy * cp, sy * sr + cy * sp * cr,    //
      cp * sr, -sp, cp * cr;
  return T;
}

Mat3 RotationEcefFromEnu(double lat, double lon) {
  const double sL = std::sin(lat), cL = std::cos(lat), sl = std::sin(lon), cl = std::cos(lon);
  Mat3 T;
  T << -sl, -sL * cl, cL * cl,  //
      cl, -sL * sl, cL * sl,    //
      0.0, cL, sL;
  return T;
}

Mat3 AttitudeBiasJacobian(const Vec3& p, double pitch, double roll) {
  const double cp = std::cos(pitch), sp = std::sin(pitch), cr = std::cos(roll), sr = std::sin(roll);
  const double x = p.x(), y = p.y(), z = p.z();
  Mat3 D;
  D << -y * cp * cr - z * sp, y * sr, z,            //
      x * cp * cr - z * cp * sr, -x * sr - z * cr, 0.0,  //
      x * sp + y * cp * sr, y * cr, -x;
  return D;
}

const io::OptionTable<MeasurementNoise>& MeasurementNoise::Table() {
  // Angles below 1 rad (57.3 deg): a larger 1-sigma makes the linearised model meaningless.
  static const io::OptionTable<MeasurementNoise> table =
      io::OptionTable<MeasurementNoise>()
          .Real("--sigma-range", &MeasurementNoise::sigma_range_m, "m", io::Bounds::Positive().Finite(),
                "Range noise 1-sigma of both radars (m)")
          .Real("--sigma-az", &MeasurementNoise::sigma_az_deg, "deg", io::Bounds::Open(0.0, geo::RadToDeg(1.0)),
                "Azimuth noise 1-sigma of both radars (deg)")
          .Real("--sigma-el", &MeasurementNoise::sigma_el_deg, "deg", io::Bounds::Open(0.0, geo::RadToDeg(1.0)),
                "Elevation noise 1-sigma of both radars (deg)");
  return table;
}

PlatformPose MakePlatformPose(double lat, double lon, double h, double yaw, double pitch, double roll) {
  PlatformPose p;
  p.lat_rad = lat;
  p.lon_rad = lon;
  p.h_m = h;
  p.yaw_rad = yaw;
  p.pitch_rad = pitch;
  p.roll_rad = roll;
  p.p_ecef = geo::EcefFromGeodetic({geo::RadToDeg(lat), geo::RadToDeg(lon), h});
  p.R_ecef_enu = RotationEcefFromEnu(lat, lon);
  return p;
}

Vec3 CorrectedEcefPoint(const RadarMeasurement& m, const PlatformPose& pose, const RadarBias& b) {
  const Vec3 p_platform =
      PlatformPointFromSpherical(m.range_m - b[kBiasRange], m.az_rad - b[kBiasAz], m.el_rad - b[kBiasEl]);
  const Mat3 T_ie = RotationEnuFromPlatform(pose.yaw_rad - b[kBiasYaw], pose.pitch_rad - b[kBiasPitch],
                                            pose.roll_rad - b[kBiasRoll]);
  return pose.p_ecef + pose.R_ecef_enu * (T_ie * p_platform);
}

PlotLinearization LinearizePlot(const RadarMeasurement& m, const PlatformPose& pose, const RadarBias& b0,
                                const MeasurementNoise& noise) {
  PlotLinearization lin;
  lin.b0 = b0;
  const double r = m.range_m - b0[kBiasRange], th = m.az_rad - b0[kBiasAz], ph = m.el_rad - b0[kBiasEl];
  const double pitch = pose.pitch_rad - b0[kBiasPitch], roll = pose.roll_rad - b0[kBiasRoll];
  const Vec3 p_platform = PlatformPointFromSpherical(r, th, ph);
  const Mat3 T = pose.R_ecef_enu * RotationEnuFromPlatform(pose.yaw_rad - b0[kBiasYaw], pitch, roll);
  lin.point_ecef = pose.p_ecef + T * p_platform;
  const Mat3 A = T * SphericalBiasJacobian(r, th, ph);
  lin.J.leftCols<3>() = A;
  lin.J.rightCols<3>() = T * AttitudeBiasJacobian(p_platform, pitch, roll);
  const Vec3 var(noise.sigma_range_m * noise.sigma_range_m, noise.sigma_az_rad() * noise.sigma_az_rad(),
                 m.has_el ? noise.sigma_el_rad() * noise.sigma_el_rad() : 0.0);
  lin.has_el = m.has_el;
  lin.el_direction = -A.col(kBiasEl);
  lin.noise_cov = A * var.asDiagonal() * A.transpose();
  lin.noise_cov = 0.5 * (lin.noise_cov + lin.noise_cov.transpose()).eval();
  return lin;
}

PairMeasurement MakePairMeasurement(const PlotLinearization& a, const PlotLinearization& b) {
  PairMeasurement pm;
  pm.z = (b.point_ecef - b.J * b.b0) - (a.point_ecef - a.J * a.b0);
  pm.H.leftCols<kRadarBiasDim>() = a.J;
  pm.H.rightCols<kRadarBiasDim>() = -b.J;
  pm.R = a.noise_cov + b.noise_cov;
  return pm;
}

double ElevationToward(const Vec3& p_ecef, const RadarMeasurement& m, const PlatformPose& pose, const RadarBias& b) {
  const Mat3 T = pose.R_ecef_enu * RotationEnuFromPlatform(pose.yaw_rad - b[kBiasYaw], pose.pitch_rad - b[kBiasPitch],
                                                           pose.roll_rad - b[kBiasRoll]);
  const Vec3 d = T.transpose() * (p_ecef - pose.p_ecef);
  const double th = m.az_rad - b[kBiasAz];
  return std::atan2(d.z(), d.x() * std::sin(th) + d.y() * std::cos(th)) + b[kBiasEl];
}

namespace {

// Grid step and golden-section iterations of the two-arc closest approach: 2° brackets the minimum of a smooth
// distance (the arcs' curvature radius is the range), 40 iterations shrink the 4° bracket to 1e-8 rad.
constexpr double kArcGridStepRad = 2.0 * geo::kPi / 180.0;
constexpr int kGoldenIterations = 40;

}  // namespace

void FillMissingElevations(RadarMeasurement* a, const PlatformPose& pose_a, const RadarBias& b_a, RadarMeasurement* b,
                           const PlatformPose& pose_b, const RadarBias& b_b) {
  if (a->has_el && b->has_el) return;
  if (a->has_el) {
    b->el_rad = ElevationToward(CorrectedEcefPoint(*a, pose_a, b_a), *b, pose_b, b_b);
    return;
  }
  if (b->has_el) {
    a->el_rad = ElevationToward(CorrectedEcefPoint(*b, pose_b, b_b), *a, pose_a, b_a);
    return;
  }
  // Both 2-D: squared gap between a's arc point at corrected elevation e and b's arc.
  RadarMeasurement ma = *a, mb = *b;
  const auto gap = [&](double e) {
    ma.el_rad = e + b_a[kBiasEl];
    const Vec3 pa = CorrectedEcefPoint(ma, pose_a, b_a);
    mb.el_rad = ElevationToward(pa, mb, pose_b, b_b);
    return (CorrectedEcefPoint(mb, pose_b, b_b) - pa).squaredNorm();
  };
  double best_e = -geo::kPi / 2, best = gap(best_e);
  for (double e = -geo::kPi / 2 + kArcGridStepRad; e <= geo::kPi / 2 + 1e-12; e += kArcGridStepRad) {
    const double g = gap(e);
    if (g < best) {
      best = g;
      best_e = e;
    }
  }
  const double e = numeric::GoldenSectionMinimum(gap, best_e - kArcGridStepRad, best_e + kArcGridStepRad, 0.0,
                                                 kGoldenIterations);
  a->el_rad = e + b_a[kBiasEl];
  b->el_rad = ElevationToward(CorrectedEcefPoint(*a, pose_a, b_a), *b, pose_b, b_b);
}

std::pair<PlotLinearization, PlotLinearization> LinearizePair(const RadarMeasurement& a, const PlatformPose& pose_a,
                                                              const RadarBias& b0_a, const RadarMeasurement& b,
                                                              const PlatformPose& pose_b, const RadarBias& b0_b,
                                                              const MeasurementNoise& noise) {
  RadarMeasurement ma = a, mb = b;
  FillMissingElevations(&ma, pose_a, b0_a, &mb, pose_b, b0_b);
  return {LinearizePlot(ma, pose_a, b0_a, noise), LinearizePlot(mb, pose_b, b0_b, noise)};
}

ReducedPair ReducePair(const PlotLinearization& a, const PlotLinearization& b, const BiasVector& m) {
  ReducedPair rp;
  const Vec3 nu = b.PointAt(m.tail<kRadarBiasDim>()) - a.PointAt(m.head<kRadarBiasDim>());
  Eigen::Matrix<double, 3, kBiasDim> H;
  H.leftCols<kRadarBiasDim>() = a.J;
  H.rightCols<kRadarBiasDim>() = -b.J;
  if (!a.has_el) H.col(kBiasEl).setZero();
  if (!b.has_el) H.col(kRadarBiasDim + kBiasEl).setZero();
  const Mat3 R = a.noise_cov + b.noise_cov;
  Eigen::Matrix<double, 3, 2> N;
  int k = 0;
  if (!a.has_el) N.col(k++) = a.el_direction;
  if (!b.has_el) N.col(k++) = b.el_direction;
  rp.dim = 3 - k;
  if (k == 0) {
    rp.Ut = Mat3::Identity();
  } else {
    // Q's last 3 − k columns are orthogonal to N's columns (to both even when they are parallel).
    const Eigen::HouseholderQR<Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 2>> qr(N.leftCols(k));
    const Mat3 Q = qr.householderQ();
    rp.Ut = Q.rightCols(rp.dim).transpose();
  }
  rp.nu = rp.Ut * nu;
  rp.H = rp.Ut * H;
  rp.R = rp.Ut * R * rp.Ut.transpose();
  rp.R = 0.5 * (rp.R + rp.R.transpose()).eval();
  return rp;
}

namespace {

// χ² distribution functions for 1 to 3 degrees of freedom.
double ChiSquareCdf(double x, int dof) {
  if (!(x > 0)) return 0.0;
  if (dof == 1) return std::erf(std::sqrt(0.5 * x));
  if (dof == 2) return 1.0 - std::exp(-0.5 * x);
  return std::erf(std::sqrt(0.5 * x)) - std::sqrt(2.0 * x / geo::kPi) * std::exp(-0.5 * x);
}

}  // namespace

double GateForDimension(double gate_d2_3dof, int dim) {
  if (dim >= 3) return gate_d2_3dof;
  const double p = ChiSquareCdf(gate_d2_3dof, 3);
  if (!(p < 1.0)) return gate_d2_3dof;  // a gate beyond double precision: "never gate"
  if (dim == 2) return -2.0 * std::log1p(-p);
  double lo = 0.0, hi = gate_d2_3dof;  // the 1-dof quantile is below the 3-dof one
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (ChiSquareCdf(mid, 1) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

bool ParseLinearization(const std::string& name, Linearization* lin) {
  if (name == "estimate") {
    *lin = Linearization::kEstimate;
  } else if (name == "measured") {
    *lin = Linearization::kMeasured;
  } else {
    return false;
  }
  return true;
}

std::string LinearizationName(Linearization lin) {
  return lin == Linearization::kEstimate ? "estimate" : "measured";
}

}  // namespace rk::registration

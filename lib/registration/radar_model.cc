#include "registration/radar_model.h"

#include <cmath>

#include "geo/angles.h"
#include "geo/wgs84.h"

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
                 noise.sigma_el_rad() * noise.sigma_el_rad());
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

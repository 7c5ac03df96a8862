// The cylindrical target; model in cylinder.h.
#include "target/cylinder.h"

#include <Eigen/Geometry>
#include <cmath>

#include "geo/line_of_sight.h"
#include "io/error.h"
#include "io/json_util.h"

namespace rk::target {

double CylinderShape::SlantM() const {
  return std::sqrt(0.25 * diameter_m * diameter_m + length_m * length_m);
}

bool CylinderShape::Check(std::string* why) const {
  if (!(std::isfinite(length_m) && length_m > 0.0)) {
    *why = "target length_m must be a finite number > 0";
    return false;
  }
  if (!(std::isfinite(diameter_m) && diameter_m > 0.0)) {
    *why = "target diameter_m must be a finite number > 0";
    return false;
  }
  return true;
}

CylinderShape LoadCylinderShape(const std::string& path) {
  const io::Json j = io::LoadJson(path);
  if (!j.is_object())
    throw DataError(path, 0, 0, "target model must be a JSON object {\"length_m\", \"diameter_m\"}");
  CylinderShape t;
  t.length_m = io::RequireNumber(j, "length_m", path);
  t.diameter_m = io::RequireNumber(j, "diameter_m", path);
  std::string why;
  if (!t.Check(&why)) throw DataError(path, 0, 0, why);
  return t;
}

Eigen::Vector3d CylinderPose::Axis() const { return geo::DirectionFromAzEl(yaw_rad, pitch_rad); }

SilhouettePoints3d SilhouettePointsOf(const CylinderPose& pose, const CylinderShape& shape) {
  SilhouettePoints3d p;
  const Eigen::Vector3d a = pose.Axis();
  p.tail_centre = pose.tail_centre_enu;
  p.nose = p.tail_centre + shape.length_m * a;
  const Eigen::Vector3d n = a.cross(p.tail_centre).normalized();
  p.tail1 = p.tail_centre + 0.5 * shape.diameter_m * n;
  p.tail2 = p.tail_centre - 0.5 * shape.diameter_m * n;
  return p;
}

CylinderPose PoseAt(double range_m, double az_rad, double el_rad, double yaw_rad, double pitch_rad,
                    const CylinderShape& shape) {
  CylinderPose pose;
  pose.yaw_rad = yaw_rad;
  pose.pitch_rad = pitch_rad;
  const Eigen::Vector3d mid = range_m * geo::DirectionFromAzEl(az_rad, el_rad);
  pose.tail_centre_enu = mid - 0.5 * shape.length_m * pose.Axis();
  return pose;
}

double ViewAngle(const CylinderPose& pose) {
  const Eigen::Vector3d a = pose.Axis();
  const Eigen::Vector3d los = pose.tail_centre_enu.normalized();
  return std::atan2(a.cross(los).norm(), a.dot(los));
}

}  // namespace rk::target

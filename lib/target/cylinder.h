// The cylindrical target of seed 004 (Tang et al. 2004) and rk-sim theodolite: a rocket-like solid of
// revolution, its pose, and the three silhouette points of SPEC.md §3. One description shared by the
// simulator (rk-sim theodolite) and the estimators (rk-attitude cylinder, rk-analyze budget).
//
// Shape. A cylinder of diameter d from the tail plane to the base of a conical nose whose tip is at distance
// l (length, nose tip to tail plane) from the tail plane; nose cone length l_c (< l). A target file (SPEC.md
// §3, rk-attitude cylinder --target) gives only l and d: l_c matters only to the outline
// (target/silhouette_image.h), where the simulator sets it and the image fit estimates it.
// Pose: tail-rim centre s0 (station ENU, m) and axis a = (sin ψ cos θ, cos ψ cos θ, sin θ) for yaw ψ
// (clockwise from north) and pitch θ (up positive), SPEC.md §3. Silhouette points (SPEC.md §3, seed 004
// §3.1): nose P1 = s0 + l a; tail1/tail2 = s0 ± (d/2) n with
//   n = unit(a × s0)   (perpendicular to the axis and to the line of sight to the tail centre),
// i.e. the ends of the tail-rim diameter seen edge-on; tail1 = s0 + (d/2) n lies to the LEFT of the
// tail → nose direction in the image (x right, y down) and tail2 to the right. (The true silhouette
// tangent points of the rim differ from these by a fraction (d/2)²/|s0|² of d: < 1e-7 px at seed 004's
// range.)
#pragma once

#include <Eigen/Core>
#include <string>

namespace rk::target {

struct CylinderShape {
  double length_m = 2.5;       // nose tip to tail plane, > 0
  double diameter_m = 0.25;    // > 0
  double nose_length_m = 0.6;  // conical nose, (0, length); not in a target file (see above)
  // L' = sqrt((d/2)² + l²): nose tip to either tail point (seed 004 eq. 2).
  double SlantM() const;
  // Length and diameter finite and > 0 (the target file's contract; the nose length is checked by whoever
  // sets it: rk-sim theodolite's options).
  bool Check(std::string* why) const;
};

// Reads a target file {"length_m", "diameter_m"} (both > 0, finite; more keys allowed; the nose length keeps
// its default). Errors name the file (DataError, exit 3).
CylinderShape LoadCylinderShape(const std::string& path);

struct CylinderPose {
  Eigen::Vector3d tail_centre_enu{0, 1000, 0};  // s0 (m)
  double yaw_rad = 0.0;
  double pitch_rad = 0.0;
  Eigen::Vector3d Axis() const;  // unit, tail → nose
};

struct SilhouettePoints3d {
  Eigen::Vector3d nose, tail1, tail2, tail_centre;  // station ENU (m)
};
// Points of SPEC.md §3 for a pose (station at the origin). Requires s0 not along the axis.
SilhouettePoints3d SilhouettePointsOf(const CylinderPose& pose, const CylinderShape& shape);

// Pose whose mid-point is at range R, azimuth/elevation (A, E) from the station, with axis (yaw, pitch).
CylinderPose PoseAt(double range_m, double az_rad, double el_rad, double yaw_rad, double pitch_rad,
                    const CylinderShape& shape);

// Angle between the axis and the line of sight to the tail centre (rad, [0, π]): π/2 = side-on view,
// 0 = tail chase (axis pointing away), π = head-on.
double ViewAngle(const CylinderPose& pose);

}  // namespace rk::target

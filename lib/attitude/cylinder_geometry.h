// Geometry of seed 004 (Tang et al. 2004, "A approach of determination of object's 3D pose from
// mono-view"): a cylindrical target seen from one station, three silhouette points.
//
//   P1 = nose tip (id `nose`), P2, P3 = the two ends of the tail-rim diameter seen edge-on
//   (ids `tail1`, `tail2`, SPEC.md §3). With length l (nose to tail plane) and diameter d
//   (target::CylinderShape, target/cylinder.h; L' = SlantM()):
//     |P2 − P3| = d,   |P1 − P2| = |P1 − P3| = L' = sqrt((d/2)² + l²)        (paper eq. 2)
//   Each point lies on its line of sight from the station: P_i = R_i u_i, |u_i| = 1 (station ENU, origin at
//   the theodolite rotation centre, u_i from SPEC.md §3's exact pixel → ray geometry, never the paper's
//   small-angle eq. 3). Finding R1, R2, R3 is a perspective-three-point (P3P) problem with a known isosceles
//   triangle:
//     F1 = R1² + R2² − 2 R1 R2 c12 − L'² = 0
//     F2 = R1² + R3² − 2 R1 R3 c13 − L'² = 0
//     F3 = R2² + R3² − 2 R2 R3 c23 − d²  = 0,      c_ij = u_i · u_j.
//   The rays of one target are 1e-4 … 1e-2 rad apart, so 1 − c_ij is computed as |u_i − u_j|²/2 and every
//   equation is evaluated in the cancellation-free form (R_i − R_j)² + 2 R_i R_j (1 − c_ij).
//
// Axis (paper eq. 5, in ENU instead of the paper's x east / y up / z north): tail-rim centre
// s0 = (P2 + P3)/2, axis = P1 − s0, yaw = atan2(axis_e, axis_n) ∈ [0, 2π) clockwise from north,
// pitch = atan2(axis_u, hypot(axis_e, axis_n)). (The paper's yaw atan[(X1−X0)/(Z1−Z0)] with x east and
// z north is the same angle.)
//
// Edge-on consistency. tail1/tail2 are the ends of the diameter perpendicular to the axis AND to the line of
// sight, so for the true configuration R2 = R3 and the nose ray is equidistant from the two tail rays
// (c12 = c13). The P3P system ignores this; its solutions with R2 = R3 are the two the paper means (nose
// nearer or farther than the tail, SPEC.md §3); the others (up to two more) tilt the diameter BC out of the
// plane perpendicular to the line of sight. `edge_tilt_rad` measures that tilt.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "target/cylinder.h"

namespace rk::attitude {

// Unit lines of sight (station ENU) to the three silhouette points.
struct CylinderRays {
  Eigen::Vector3d nose{0, 1, 0};
  Eigen::Vector3d tail1{0, 1, 0};
  Eigen::Vector3d tail2{0, 1, 0};
};

// Pairwise cosines c_ij = u_i·u_j, versines k_ij = 1 − c_ij (= |u_i − u_j|²/2, no cancellation) and sines
// s_ij = |u_i × u_j| of the three rays; index 12 = nose–tail1, 13 = nose–tail2, 23 = tail1–tail2.
struct RayAngles {
  double c12 = 1, c13 = 1, c23 = 1;
  double k12 = 0, k13 = 0, k23 = 0;
  double s12 = 0, s13 = 0, s23 = 0;
};
RayAngles AnglesOf(const CylinderRays& rays);

// Residuals (m²) F1, F2, F3 of the three distance equations for ranges R = (R1, R2, R3).
Eigen::Vector3d DistanceResiduals(const RayAngles& a, const target::CylinderShape& target,
                                  const Eigen::Vector3d& R);

// One solution of the isosceles P3P, with the axis it implies.
struct CylinderSolution {
  Eigen::Vector3d range_m{0, 0, 0};  // R1 (nose), R2 (tail1), R3 (tail2), station to point (m)
  Eigen::Vector3d nose_enu{0, 0, 0};
  Eigen::Vector3d tail_centre_enu{0, 0, 0};
  Eigen::Vector3d axis_enu{0, 1, 0};  // unit, tail centre → nose
  double yaw_rad = 0.0;               // [0, 2π), clockwise from north
  double pitch_rad = 0.0;             // [−π/2, π/2], nose up positive
  // Largest violation of the three distance constraints, expressed as a length: max_i |F_i| / (2·side_i) (m).
  // ~1e-12 m for an exact root; larger for a near miss (a pair of roots that noise has made complex).
  double miss_m = 0.0;
  bool exact = true;                  // false: closest approach of a vanished root pair (see miss_m)
  // Tilt of the diameter P2P3 out of the plane perpendicular to the line of sight to the tail centre
  // (rad): 0 for the edge-on solutions SPEC.md §3 describes.
  double edge_tilt_rad = 0.0;
};

// Completes a solution from its ranges: points, tail centre, axis, yaw, pitch, residual, tilt.
CylinderSolution SolutionFromRanges(const CylinderRays& rays, const RayAngles& a,
                                    const target::CylinderShape& target, const Eigen::Vector3d& range_m);

// Angle between two unit axes (rad), in [0, π].
double AxisAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// The branch functions of the paper's search (§3.2): for a nose range R1, the law of cosines gives
//   R2 = R1 c12 + s2 sqrt(L'² − R1² s12²),   R3 = R1 c13 + s3 sqrt(L'² − R1² s13²),   s2, s3 ∈ {+1, −1},
// and f(R1) = |P2 − P3|² − d² = (R2 − R3)² + 2 R2 R3 k23 − d² measures the mismatch of the third side.
// Valid() is false where a square root is imaginary or a range is not positive.
struct BranchPoint {
  double R1 = 0, R2 = 0, R3 = 0, f = 0;
  bool valid = false;
};
BranchPoint EvaluateBranch(const RayAngles& a, const target::CylinderShape& target, int s2, int s3,
                           double R1);

// Largest nose range for which both tail ranges are real: L' / max(s12, s13) (m); +inf if the rays coincide.
double MaxNoseRange(const RayAngles& a, const target::CylinderShape& target);

// Newton polish of (R1, R2, R3) on F1..F3 (at most `iterations` steps, stops when a step no longer reduces
// the residual). Returns the polished ranges.
Eigen::Vector3d PolishRanges(const RayAngles& a, const target::CylinderShape& target,
                             const Eigen::Vector3d& R, int iterations = 8);

}  // namespace rk::attitude

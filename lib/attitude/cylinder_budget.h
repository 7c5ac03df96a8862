// Error propagation for the seed 004 cylinder attitude: Jacobians by automatic differentiation (ceres::Jet)
// and the rk-analyze budget models "cylinder" and "cylinder-ranges".
//
// Inputs of the full computation (SI):
//   x = [A, E, x1, y1, x2, y2, x3, y3, l, d]
//        theodolite boresight azimuth and elevation (rad); pixels of nose, tail1, tail2; length, diameter (m)
// Outputs y = [yaw, pitch, R1, R2, R3] (rad, m): the axis of the chosen solution and its three ranges.
// Derivatives through the solver by the implicit function theorem: the ranges R solve F(R, x) = 0
// (cylinder_geometry.h), so ∂R/∂x = −(∂F/∂R)⁻¹ ∂F/∂x. This is computed as ONE Newton step in jet
// arithmetic from the converged double solution R0: R = R0 − (∂F/∂R)⁻¹ F(R0, x) with F evaluated on jets
// (F(R0, x0) = 0, so the value stays R0 and the derivative part is exactly the implicit derivative). The
// rays' jets come from camera::RayEnuT (camera/projection.h: SPEC.md §3 geometry, the undistortion's derivative
// by the implicit-function theorem at the nominal pixel), yaw/pitch from the axis by atan2. The solver itself (search or closed form) is never
// differentiated, so the Jacobian does not depend on which one found R0. At a double root (side-on view)
// ∂F/∂R is singular and the Jacobian is infinite: CylinderJacobian returns false.
//
// Model "cylinder-ranges" is the paper's own error model (§4.3, eqs. 5–9): the axis from the three ranges
// and the theodolite angles of the three points, inputs [R1, R2, R3, A1, E1, A2, E2, A3, E3] (m, rad),
// outputs [yaw, pitch]; the paper's hand-expanded partials ∂θ/∂R_i, ∂φ/∂R_i (eqs. 6–7, garbled in the
// extracted text) are replaced by automatic differentiation.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "analysis/budget.h"
#include "attitude/cylinder_geometry.h"
#include "attitude/cylinder_solve.h"
#include "camera/camera_model.h"

namespace rk::attitude {

inline constexpr int kCylinderInputs = 10;
inline constexpr int kCylinderOutputs = 5;
using CylinderInputs = Eigen::Matrix<double, kCylinderInputs, 1>;
using CylinderJacobianMatrix = Eigen::Matrix<double, kCylinderOutputs, kCylinderInputs>;

// Rays of the three points from the inputs (exact SPEC.md §3 line of sight).
CylinderRays RaysFromInputs(const camera::CameraModel& camera, const CylinderInputs& x);

// dy/dx at x0 for the solution with ranges `range_m` (a converged root at x0). False at a singular point.
bool CylinderJacobian(const camera::CameraModel& camera, const CylinderInputs& x0, const Eigen::Vector3d& range_m,
                      CylinderJacobianMatrix* J);

// Solves at x and returns the admissible solution whose axis is nearest `reference_axis`; nullopt if none.
std::optional<CylinderSolution> SolveNearest(const camera::CameraModel& camera, const CylinderInputs& x,
                                             const CylinderSolveOptions& options,
                                             const Eigen::Vector3d& reference_axis);

// Budget models (see header comment). `nominal` (budget file) is either
//   {"scenario": {"range_m", "az_deg", "el_deg", "yaw_deg", "pitch_deg"}, "target": {"length_m", "diameter_m"}}
//     target mid-point at (range, az, el), boresight on it, pixels by exact projection, nominal solution =
//     the true one; or
//   {"boresight_az_deg", "boresight_el_deg", "points_px": {"nose": [x, y], "tail1": [..], "tail2": [..]},
//    "target": {...}, "branch": "nearer" | "farther"}   (default nearer, the SPEC.md §3 no-history rule).
// `solve` gives the solver used by Monte Carlo (and the nominal solve).
std::unique_ptr<analysis::BudgetModel> MakeCylinderBudgetModel(const io::Json& nominal,
                                                               const camera::CameraModel& camera,
                                                               const CylinderSolveOptions& solve,
                                                               const std::string& where);
std::unique_ptr<analysis::BudgetModel> MakeCylinderRangesBudgetModel(const io::Json& nominal,
                                                                     const camera::CameraModel& camera,
                                                                     const CylinderSolveOptions& solve,
                                                                     const std::string& where);

}  // namespace rk::attitude

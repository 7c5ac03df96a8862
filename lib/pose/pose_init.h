// Initial rotations for orthogonal iteration from a scaled-orthographic (weak-perspective)
// view of the target, and the second start of a near-planar target.
//
// 1. Virtual camera: rotate the camera frame by R_virt_cam (the smallest rotation taking the
//    mean ray direction to the optical axis), so the target lies on the virtual axis and the
//    weak-perspective approximation is as good as it can be; m̃_i = R_virt_cam m_i / z.
// 2. Scaled orthographic projection: x̃_i − x̄ ≈ s · P · R̃ · (p_i − p̄), P = [I₂ 0], with the
//    model in its principal axes (eigenvectors e_k of the scatter Σ p'p'ᵀ, λ1 ≥ λ2 ≥ λ3).
//    Least squares for the 2×3 matrix A = sPR̃: B = Σ (x̃_i − x̄) q_iᵀ, A = B diag(1/λ).
//    Non-planar (λ3 ≥ planar_ratio · λ1): rows r1, r2 = the orthonormal factor of A (SVD),
//    r3 = r1 × r2. Planar: only the in-plane 2×2 block A₂ of A is observed; the out-of-plane
//    entries (c1, c2) follow from |r1| = |r2| and r1 ⊥ r2:
//      c1² = (−u + √(u² + 4k²)) / 2,  c2 = −k / c1,  u = |a1|² − |a2|², k = a1·a2,
//    with the sign of (c1, c2) free: the two classic solutions of a plane seen in weak
//    perspective.
// 3. The second start is the weak-perspective mirror ("Necker reversal") of the first: the
//    depth reflection S = diag(1, 1, −1) applied on both sides, R̃₂ = S R̃ S (in the principal
//    frame: the target's tilt out of its best-fit plane is mirrored about the image plane).
//    For a planar target it is exactly the second weak-perspective solution; for a
//    near-planar one it starts OI in the basin of the other local minimum.
// Output: R_cam_body = R_virt_camᵀ · R̃ · E ᵀ for each start. Degenerate inputs (fewer than 3
// points, rays behind the camera, collinear model) give no start.
//
// Planar and near-planar targets: HomographyInit uses the full perspective instead. The model
// in its principal axes, q_i = Eᵀ(p_i − p̄) with the out-of-plane coordinate dropped, maps to
// the normalised image by a homography x_i ~ H (q_i1, q_i2, 1) with H = λ [r1 r2 t] (r_k =
// columns of R_cam_principal). H from n ≥ 4 points by the normalised DLT (Hartley 1997:
// both point sets centred and scaled to mean distance √2; h = eigenvector of AᵀA with the
// smallest eigenvalue), λ = ±2 / (‖h1‖ + ‖h2‖) with the sign giving t_z > 0, R = the
// rotation nearest [r1 r2 r1×r2]. Exact for a planar target without noise; the second start
// is its weak-perspective mirror as above.
#pragma once

#include <Eigen/Core>
#include <span>

namespace rk::pose {

struct WeakPerspectiveStart {
  bool ok = false;
  Eigen::Matrix3d R_cam_body[2];  // [0] primary, [1] mirrored (second start)
  double scale = 0.0;             // s ≈ 1 / depth (1/m)
  bool planar = false;            // the model was treated as planar
};

// rays: normalised image rays (z > 0); p_body: model points (m). planar_ratio: λ3/λ1 below
// which the model is treated as planar (default 1e-6: only exactly coplanar models).
WeakPerspectiveStart WeakPerspectiveInit(std::span<const Eigen::Vector3d> rays,
                                         std::span<const Eigen::Vector3d> p_body, double planar_ratio = 1e-6);

// Homography start for a (near-)planar model; needs n ≥ 4 and no three of the in-plane points
// collinear. `planar` is set; `scale` = 1/t_z.
WeakPerspectiveStart HomographyInit(std::span<const Eigen::Vector3d> rays, std::span<const Eigen::Vector3d> p_body);

// Smallest rotation taking unit vector `from` to unit vector `to` (Rodrigues).
Eigen::Matrix3d RotationBetween(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

}  // namespace rk::pose

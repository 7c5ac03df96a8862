// Solvers of the isosceles P3P of seed 004 (equations in cylinder_geometry.h): all admissible
// (R1, R2, R3) for three silhouette rays and a cylinder model.
//
// kSearch — the paper's iterative search (§3.2), done completely. For a nose range R1 the law of cosines
//   gives R2 and R3, each with TWO roots (s2, s3 = ±, see EvaluateBranch); the paper keeps one and stops at
//   the first |d'23 − d23| < ε with ε = 0.1 mm. Here every one of the four branches is scanned on a grid of
//   step L'/32 over the band of nose ranges that admissible solutions can occupy:
//     R_edge = d / |u2 − u3|   (the range at which the two tail rays are d apart edge-on)
//     R1 ∈ [R_edge cos(max tilt) − d − L',  min(R_edge + d + L', L'/max(s12, s13))]
//   (any solution with |R2 − R3| ≤ d sin(max tilt) has sqrt(R2 R3) ≥ R_edge cos(max tilt), and
//   |R2 − R3| ≤ d, |R1 − R2| ≤ L'), with the end of the real branches added as a grid point. Each sign
//   change of f(R1) = |P2 − P3|² − d² is bisected to machine precision (until the bracket no longer
//   shrinks); each grid minimum of |f| without a sign change is searched by golden section for a hidden
//   pair of roots (then bisected) or, if the pair has vanished under noise, kept as a near miss (below).
//   Finally (R1, R2, R3) is Newton-polished on all three equations.
// kP3P — closed form. With x = R2/R1 = 1 + ξ, y = R3/R1 = 1 + η, F1 = F2 and F3/F1 = d²/L'² are two conics
//   in (ξ, η):
//     Q1: η² + 2 k13 η − (ξ² + 2 k12 ξ + 2 (k12 − k13)) = 0
//     Q2: η² + (2 k23 (1 + ξ) − 2 ξ) η + (1 − κ) ξ² + 2 (k23 − κ k12)(1 + ξ) = 0,   κ = d²/L'²,
//   (k_ij = 1 − c_ij; these forms are free of the cancellation in 1 − c). Both are monic in η, so their
//   resultant (C1 − C2)² − (B1 − B2)(B2 C1 − B1 C2) is a quartic in ξ, solved by Ferrari's method
//   (polynomial.h) after scaling ξ by α = sqrt(2 max(k12, k13)) so that its coefficients are O(1). Then
//   η = (C2 − C1)/(B1 − B2), R1 = L'/sqrt(ξ² + 2 k12 (1 + ξ)), R2 = x R1, R3 = y R1, and a Newton polish on
//   F1..F3. A complex pair of quartic roots is a root pair that measurement noise has made vanish; its real
//   part seeds the same near-miss refinement as the search.
//
// Near misses. Where the view is almost perpendicular to the axis the two edge-on solutions nearly coincide
// and pixel noise can make them complex: no exact solution exists. The closest approach (the extremum of
// f along the branch, golden section) is returned with exact = false when its miss, measured as the
// distance error over the tail range (rad), is at most max_miss_rad, and only when no exact admissible
// solution exists; 0 disables near misses.
//
// Admissible: all ranges > 0 and edge tilt ≤ max_edge_tilt_deg (the diameter P2P3 nearly perpendicular to
// the line of sight, as SPEC.md §3 defines tail1/tail2); the P3P roots that tilt it further are dropped
// and counted. Solutions are returned sorted by nose range, nearer first.
#pragma once

#include <string>
#include <vector>

#include "attitude/cylinder_geometry.h"
#include "io/options.h"

namespace rk::attitude {

enum class CylinderMethod { kSearch, kP3P };
bool ParseCylinderMethod(const std::string& name, CylinderMethod* method);  // "search" | "p3p"
std::string CylinderMethodName(CylinderMethod method);

struct CylinderSolveOptions {
  // Default by measurement (bench/cylinder_tables.cc, bench/bench_cylinder.cc, docs/benchmarks.md): on exact
  // pixels both reach 3e-9° and agree to 2e-11°; the closed form takes ~1 µs per frame, the search ~0.5 ms.
  CylinderMethod method = CylinderMethod::kP3P;
  // Edge tilt limit (deg): larger tilts are not edge-on tail points; (0, 90]. 60°: under 1-pixel
  // quantisation the true solution tilts by up to ~30° at a 10-pixel tail diameter (bench/cylinder_tables.cc).
  double max_edge_tilt_deg = 60.0;
  double max_miss_rad = 0.0;                       // near-miss acceptance (rad); 0 = exact roots only
  int search_steps_per_slant = 32;                 // kSearch grid step L'/N, [4, 4096]
  int search_max_samples = 200000;                 // kSearch: cap on grid points per branch, [100, 1e7]

  // The command-line option --method (rk-attitude cylinder; io/options.h).
  static const io::OptionTable<CylinderSolveOptions>& Table();
  bool Check(std::string* why) const;
};

struct CylinderSolveResult {
  std::vector<CylinderSolution> solutions;  // admissible, deduplicated, nearer nose first
  int rejected_tilted = 0;                  // real positive roots dropped for their edge tilt
  long function_evaluations = 0;            // kSearch: branch evaluations (cost figure)
};

CylinderSolveResult SolveCylinder(const CylinderRays& rays, const target::CylinderShape& target,
                                  const CylinderSolveOptions& options);
CylinderSolveResult SolveCylinderSearch(const CylinderRays& rays, const target::CylinderShape& target,
                                        const CylinderSolveOptions& options);
CylinderSolveResult SolveCylinderP3P(const CylinderRays& rays, const target::CylinderShape& target,
                                     const CylinderSolveOptions& options);

}  // namespace rk::attitude

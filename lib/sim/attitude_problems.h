// Random perspective-n-point problems with truth, for tests and benchmarks of the attitude
// solver (rk-attitude oi, seed 001): a pinhole camera, a rigid point set in body metres,
// a pose (R_cam_body, t_cam) and noisy pixels.
//
// Geometries:
//   box          the usual PnP benchmark (EPnP, SQPnP papers): camera 640×480, f = 800 px,
//                principal point (319.5, 239.5); points uniform in [−2, 2]×[−2, 2]×[4, 8] m of
//                the camera frame, the body frame a uniformly random rotation about their
//                centroid (body origin = centroid).
//   planar       points uniform in the body square [−2, 2]² (z = 0), plane normal tilted by [min_tilt, max_tilt]
//                from the line of sight, body origin at depth uniform in [4, 8] m on a
//                ray within 0.1 rad of the axis; same camera.
//   narrow       seed 001's attitude camera: 2448×2048, 3.45 µm pixels, 100 mm lens
//                (f = 28 985.5 px); a target of points uniform in the body box
//                [−0.35, 0.35]×[−0.35, 0.35]×[−0.15, 0.15] m, uniformly random attitude, at a
//                range uniform in [15, 25] m near the optical axis.
//   narrow-planar  the same camera; points uniform in the body square [−0.35, 0.35]² (z = 0),
//                normal tilted up to max_tilt from the line of sight, range [15, 25] m.
// Pixel noise: independent Gaussian, σ drawn per problem uniform in [noise_min, noise_max] px.
// Every point is in front of the camera and inside the image (problems are redrawn until so).
// Determinism: problem k of seed s is drawn from std::mt19937_64(seed_seq{s, k}).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace rk::sim {

enum class PnpGeometry { kBox, kPlanar, kNarrow, kNarrowPlanar };
bool ParsePnpGeometry(const std::string& name, PnpGeometry* g);  // box | planar | narrow | narrow-planar
std::string PnpGeometryName(PnpGeometry g);

struct PnpProblemOptions {
  PnpGeometry geometry = PnpGeometry::kBox;
  int min_points = 4;          // n uniform in [min_points, max_points], ≥ 3
  int max_points = 12;
  double noise_min_px = 0.1;   // σ range (px), 0 ≤ min ≤ max
  double noise_max_px = 1.0;
  double min_tilt_rad = 0.0;                 // planar geometries: tilt of the plane normal from the
  double max_tilt_rad = 1.2217304763960306;  // line of sight, uniform in [min, max] (default 0–70°)
  std::uint64_t seed = 1;

  bool Check(std::string* why) const;
};

struct PnpProblem {
  double fx = 800, fy = 800, cx = 319.5, cy = 239.5;
  int width_px = 640, height_px = 480;
  Eigen::Matrix3d R_cam_body = Eigen::Matrix3d::Identity();  // truth
  Eigen::Vector3d t_cam = Eigen::Vector3d::Zero();           // truth: body origin in the camera (m)
  double noise_px = 0.0;                                     // σ used
  std::vector<Eigen::Vector3d> p_body;                       // model points (m)
  std::vector<Eigen::Vector2d> px_true, px;                  // exact and noisy pixels
};

// Problem number `index` of the stream defined by the options.
PnpProblem MakePnpProblem(const PnpProblemOptions& options, std::uint64_t index);

// Uniformly distributed random rotation (from a uniform unit quaternion).
Eigen::Matrix3d RandomRotation(std::uint64_t seed, std::uint64_t index);

}  // namespace rk::sim

// Synthetic non-cooperative target with exact image truth (rk-sim points, issue 31): the scene that
// rk-extract points is measured on.
//
// Scene. A 2-D body (px at scale 1) is mapped to the image by a similarity per frame,
//   x_img = c(t) + s(t) R(theta(t)) x_body,
// with c the body origin in the image (px), theta the rotation (rad, image axes: x right, y down) and s
// the growth. The body is a dark aircraft-like silhouette (fuselage, swept wings, tailplane) in front of a
// vertical sky gradient; on it sit the markers, each with the method that suits it:
//   q1, q2   quadrant: a black/white checker square (half side 8 px); truth = its saddle point;
//   c1       circle: a light disc (radius 8 px) with a bright highlight inside (< 0.1 DN at the rim); truth =
//            the disc's centre;
//   b1       centroid-bright: a symmetric Gaussian lamp (std 1.5 px);
//   d1       centroid-dark: a dark disc (radius 6 px) on the sky ahead of the wing, carried by the body;
//   t1, t2   correlation: textured squares (band-limited: a sum of random sinusoids fixed in body
//            coordinates); truth = the patch centre mapped by the similarity.
// Clouds are soft-edged discs in image coordinates composited in front of everything (opacity 1 in the
// core, a smooth ramp over their edge). Scenarios: kStatic (no motion); kMoving (translation, rotation
// by 20 deg and growth 1.0 -> 1.3 over the run; a cloud hides c1 for an interval); kReversal (the motion
// slows, reverses and comes back while a cloud hides q2); kLookalike (kReversal plus a second identical
// quadrant on a dark plate, off the body, moving on q2's constant-velocity prediction from the time q2
// was last clear, 3 px beside it, shown only while q2 is fully hidden and the look-alike itself is clear).
// Motion is defined over the run (normalised time u = k / (frames - 1)), so a longer run moves slower.
//
// Imaging. Isotropic Gaussian PSF (std psf_sigma_px), pixel-area integration, motion blur (the mean of
// blur_steps renders over exposure_s centred on the frame time; truth = the mean of the positions at the
// sub-exposures: the mid-exposure position for uniform motion), sensor noise (shot + read, Gaussian), 8-bit or 16-bit (12-bit DN range: 8-bit DN x 16).
// Truth accuracy: the markers are analytic functions of the PSF-blurred scene, each exactly symmetric
// about its truth (quadrant: b + a erf(u/(sqrt2 sigma)) erf(v/(sqrt2 sigma)) in the marker's rotated
// axes, with its finite square's blurred box, separable and exact under a similarity; the lamp a
// Gaussian convolved with the PSF; the discs a radial profile Phi((R - r)/sigma)). Pixels are integrated
// by an n x n sample lattice: a symmetric pixel aperture (n points instead of the box), which changes pixel
// values slightly but moves no centre, up to aliasing of the Gaussian-band-limited image at 2 pi n
// (exp(-(2 pi n sigma)^2 / 2) < 1e-20 for the default n). The silhouette's edges (not a truth) are
// rendered by a supersampled polygon fill, blurred and area-averaged. tests/sim/test_points_scene.cc
// measures the truth against a 16 x 16 lattice and by symmetric centroids (docs/rk-sim.md "rk-sim points").
// Only the target's region (and the clouds') is rendered densely; the rest of a frame is the gradient.
// Determinism: frame k's noise is drawn from RandomStream(seed, kPointsNoiseStream, k); the scene layout
// (textures) from RandomStream(seed, kPointsSceneStream), so any frame renders alone, identically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "io/json_util.h"
#include "io/options.h"

namespace rk::sim {

enum class PointsScenario { kStatic, kMoving, kReversal, kLookalike };
std::string PointsScenarioName(PointsScenario s);

struct PointsSceneOptions {
  PointsScenario scenario = PointsScenario::kMoving;
  int width = 640, height = 480;   // frame size (px), [128, 2448] x [128, 2048]
  int frames = 200;                // [2, 100000]
  int bits = 8;                    // 8 or 16 (16-bit frames hold 12-bit DN: 8-bit scale x 16)
  double fps = 1000.0;             // frame rate (Hz), (0, 1e6]
  double psf_sigma_px = 0.8;       // Gaussian PSF std (px), [0.3, 5]
  double exposure_s = 0.0005;      // motion-blur exposure (s), [0, 1/fps]; 0 = none
  int blur_steps = 0;              // sub-exposure renders; 0 = enough that nothing moves > 0.25 px between them
  int supersample = 0;             // n x n samples per pixel; 0 = max(2, ceil(1.6 / psf_sigma_px))
  double read_noise_dn = 1.5;      // read noise std (8-bit DN)
  double gain_e_per_dn = 40.0;     // photo-electrons per 8-bit DN (shot noise); 0 = none (both 0: no noise)
  double scale = 1.0;              // body and marker size multiplier, [0.5, 4]
  std::uint64_t seed = 1;
  bool clouds = true;              // false: no clouds (--no-clouds)

  // --scenario ... --gain-e-per-dn, --scale, --seed (--no-clouds is the app's: the member defaults to true).
  static const io::OptionTable<PointsSceneOptions>& Table();
  // Table().Check, then exposure within a frame interval.
  bool Check(std::string* why) const;
  io::Json ToJson() const;
  int SupersampleN() const;
};

// Truth of one marker at one frame (PointsSimulator::Truth: the exposure's mean position).
struct PointTruth {
  std::string id;      // q1, q2, c1, b1, d1, t1, t2; "lookalike" (kLookalike only)
  std::string method;  // SPEC.md §2.1 seeds method: quadrant, circle, centroid-bright, centroid-dark, correlation
  double x_px = 0, y_px = 0;  // SPEC.md §3 pixel coordinates (pixel (i, j) covers x in [j-0.5, j+0.5))
  double occlusion = 0;       // mean cloud opacity over the marker's support (half diagonal or radius + 3 sigma),
                              // [0, 1]: 1 = fully hidden
  bool visible = true;        // inside the image and every point of the support clear (opacity below
                              // kPointVisibleOcclusion); the look-alike: shown
  double size_px = 0;         // the marker's side or diameter in the image (px)
};
constexpr double kPointVisibleOcclusion = 0.01;
// Random streams of the points simulator (sim_common.h RandomStream).
constexpr std::uint64_t kPointsSceneStream = 1;     // texture waves
constexpr std::uint64_t kPointsNoiseStream = 1000;  // frame k's noise: (1000, k)

class PointsSimulator {
 public:
  // Throws UsageError if the options fail Check().
  explicit PointsSimulator(PointsSceneOptions opt);

  const PointsSceneOptions& options() const { return opt_; }
  int frames() const { return opt_.frames; }
  double TimeS(int k) const { return k / opt_.fps; }

  // Frame k: CV_8UC1 or CV_16UC1, with its own seeded noise.
  cv::Mat Frame(int k) const;
  // Frame k without noise or quantisation (CV_32FC1, 8-bit DN scale).
  cv::Mat Signal(int k) const;
  // Signal with an explicit n x n lattice (tests: compare with a finer one).
  cv::Mat Signal(int k, int supersample) const;

  // Every marker (also hidden ones; the look-alike in kLookalike only, visible only while shown). x, y: the
  // mean of the marker's positions at ExposureTimes(k), which the motion-blurred image shows (the position at
  // the frame time, mid-exposure, for uniform motion; within 0.003 px of it at kReversal's turn).
  std::vector<PointTruth> Truth(int k) const;
  // The sub-exposure times of frame k (s): blur_steps evenly inside the exposure, centred on TimeS(k).
  std::vector<double> ExposureTimes(int k) const;

  struct Seed {
    std::string id, method;
    int frame = 0;
    double x_px = 0, y_px = 0, size_px = 0;
  };
  // Frame-0 seeds of every visible marker (not the look-alike).
  std::vector<Seed> Seeds() const;
  // A seed of `id` at its truth at `frame` (re-seeding); throws UsageError for an unknown id or frame.
  Seed SeedAt(const std::string& id, int frame) const;

  // The similarity at time t: image = centre + s R(theta) body.
  struct Pose {
    Eigen::Vector2d centre_px{0, 0};
    double theta_rad = 0, scale = 1;
    Eigen::Vector2d Apply(const Eigen::Vector2d& body) const;
  };
  Pose PoseAt(double t_s) const;

  // Scene elements (points_scene.cc), public for the renderer's free functions.
  struct Marker {
    std::string id, method;
    Eigen::Vector2d body{0, 0};   // position in the body (px at scale 1)
    double half_px = 8;           // quadrant/texture half side, disc radius, lamp std (body px)
    double support_px = 12;       // radius of what the marker touches (body px), for occlusion
    std::vector<Eigen::Vector4d> waves;  // texture: (kx, ky, phase, amplitude) in body px
  };
  struct Cloud {
    Eigen::Vector2d centre_px{0, 0};    // at t = 0 (image px)
    Eigen::Vector2d velocity_px_s{0, 0};
    double core_px = 20, edge_px = 8;   // opacity 1 within core, smooth ramp to 0 at core + edge
    double Opacity(const Eigen::Vector2d& p, double t_s) const;
  };
  const std::vector<Marker>& markers() const { return markers_; }
  const std::vector<Cloud>& clouds() const { return clouds_; }
  // The look-alike's centre at t and whether it is shown in frame k (kLookalike).
  Eigen::Vector2d LookalikeAt(double t_s) const;
  bool LookalikeShown(int k) const;

 private:
  void BuildMarkers();
  void BuildClouds();
  void BuildLookalike();
  double MotionU(double t_s) const;
  struct Cover {
    double max = 0, min = 0, mean = 0;  // cloud opacity over a disc: largest, smallest (of the most opaque cloud), mean
  };
  Cover Occlusion(const Eigen::Vector2d& p, double radius_px, double t_s) const;
  Eigen::Vector2d MarkerAt(const Marker& m, double t_s) const;
  // Signal of frame k with an n x n lattice into `out` (reused when it has the frame's size and type).
  void RenderSignal(int k, int n, cv::Mat* out) const;

  PointsSceneOptions opt_;
  std::vector<Marker> markers_;
  std::vector<Cloud> clouds_;
  // kLookalike: the path start, velocity (px/s), side offset, and the frames it is shown.
  Eigen::Vector2d look_start_{0, 0}, look_velocity_{0, 0};
  double look_t0_ = 0;
  std::vector<char> look_shown_;
};

struct PointsWriteOptions {
  bool force = false;                                  // replace a non-empty out_dir
  std::vector<std::pair<std::string, int>> reseeds;    // extra seeds rows: id at its truth at frame
  std::function<void(int done, int total)> progress;   // optional, per frame
};

struct PointsTrialSummary {
  int frames = 0;
  int markers = 0;
  int hidden_rows = 0;        // truth rows with visible = 0 (markers only)
  int lookalike_frames = 0;   // frames with the look-alike shown
  int seeds = 0;              // rows of seeds.csv
  io::Json ToJson() const;
};

// Writes DIR (atomically, sim::TrialFolder): video.mkv (8-bit FFV1) or video/%06d.png (16-bit),
// frames.csv (frame,t_s), seeds.csv (SPEC.md §2.1: id,frame,x_px,y_px,method,size_px), truth/points.csv
// (frame,t_s,id,x_px,y_px,visible,occlusion; x, y with 6 decimals). Throws UsageError (options, refusing
// to replace, bad re-seed), IoError.
PointsTrialSummary WritePointsTrial(const PointsSceneOptions& opt, const std::filesystem::path& out_dir,
                                    const PointsWriteOptions& w = {});

}  // namespace rk::sim

// Cramér–Rao bound of single-frame cylinder attitude from the image itself (seed 004's set-up), next to the
// paper's printed errors, ¼ of them, and what rk-extract silhouette + rk-attitude cylinder achieve
// (docs/benchmarks.md, issue 4). Prints figures; asserts nothing.
//
//   build/bench/cylinder_crlb [--phases N] [--read-noise DN] [--gain E_PER_DN]
//
// The bound: Fisher information of the whole frame with respect to the target's five pose parameters (tail
// centre ENU, yaw, pitch) and three radiometric nuisances (body level, sky level, sky gradient), from the
// noise-free image of rk-sim theodolite's renderer (exact area sampling, Gaussian PSF; rendered at 16 bits so
// that quantisation does not disturb the central differences) and its noise model (read noise² + shot
// noise per pixel, 8-bit rounding added as 1/12 DN²). J = Σ_pixels ∂s/∂θ ∂s/∂θᵀ / σ²; σ(yaw) = √(J⁻¹)₃₃.
// No unbiased estimator working on one frame — whatever points it extracts — has a smaller RMS error. Mean over
// N random sub-pixel phases. Theodolite pointing errors are excluded (they are Table 2's, not the image's).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "sim/theodolite_render.h"
#include "sim/theodolite_scene.h"
#include "target/silhouette_image.h"

using namespace rk;
using geo::DegToRad;
using geo::RadToDeg;

namespace {

constexpr double kAz = 326.2, kYaw = 76.211, kPitch = 31.257;  // as bench/cylinder_tables.cc
// tail ENU (3), yaw, pitch, body DN, sky DN, sky gradient DN | nose-cone length | PSF σ, body shading DN
constexpr int kParams = 11;

struct Scene {
  sim::TheodoliteFrameTruth truth;
  sim::SilhouetteRenderOptions render;
  target::CylinderShape shape;
};

double ImageLength(double R, double E_deg, const camera::CameraModel& cam) {
  const target::CylinderShape s;
  const target::CylinderPose pose = target::PoseAt(R, DegToRad(kAz), DegToRad(E_deg), DegToRad(kYaw), DegToRad(kPitch), s);
  const target::SilhouettePoints3d p = target::SilhouettePointsOf(pose, s);
  const double A = DegToRad(kAz), E = DegToRad(E_deg);
  return (*cam.ProjectEnu(p.nose, A, E) - 0.5 * (*cam.ProjectEnu(p.tail1, A, E) + *cam.ProjectEnu(p.tail2, A, E))).norm();
}

double RangeForLength(double n_px, double E_deg, const camera::CameraModel& cam) {
  double lo = 100, hi = 20000;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ImageLength(mid, E_deg, cam) > n_px ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Pose θ[0..4] and radiometry θ[5..7] applied to a scene; image points recomputed (they steer the shading).
Scene Apply(const Scene& base, const double* d, const camera::CameraModel& cam) {
  Scene s = base;
  s.truth.pose.tail_centre_enu += Eigen::Vector3d(d[0], d[1], d[2]);
  s.truth.pose.yaw_rad += d[3];
  s.truth.pose.pitch_rad += d[4];
  s.render.body_dn += d[5];
  s.render.sky_dn += d[6];
  s.render.sky_gradient_dn += d[7];
  s.shape.nose_length_m += d[8];
  s.render.psf_sigma_px += d[9];
  s.render.shading_dn += d[10];
  s.truth.points = target::SilhouettePointsOf(s.truth.pose, s.shape);
  const double A = s.truth.boresight_az_rad, E = s.truth.boresight_el_rad;
  s.truth.nose_px = *cam.ProjectEnu(s.truth.points.nose, A, E);
  s.truth.tail1_px = *cam.ProjectEnu(s.truth.points.tail1, A, E);
  s.truth.tail2_px = *cam.ProjectEnu(s.truth.points.tail2, A, E);
  return s;
}

// Noise-free signal in DN: rk-sim theodolite's renderer without the sensor (target::SilhouetteSignal in double,
// 8-bit DN scale; in float the bound moves by up to 1 % at 100 px). (Digitising, even at 16 bits, puts rounding steps into the central differences that read as
// spurious information: the bound then moves with the step size.)
cv::Mat Signal(const Scene& s, const camera::CameraModel& cam) {
  sim::SilhouetteRenderOptions o = s.render;
  o.sensor.bit_depth = 8;
  return target::SilhouetteSignal(cam, s.truth.pose, s.shape, s.truth.boresight_az_rad, s.truth.boresight_el_rad, o,
                                  1.0, CV_64F);
}

// σ(yaw), σ(pitch) in degrees for one scene: nose shape known; nose-cone length unknown; also the PSF σ and
// a body shading unknown (what rk-attitude cylinder --video faces: it fits both).
Eigen::Matrix<double, 6, 1> Bound(const Scene& s, const camera::CameraModel& cam, double read_dn, double gain) {
  const double R = s.truth.pose.tail_centre_enu.norm();
  // Steps move the outline by ≤ 0.02 px (as rk-attitude cylinder's image fit, whose own Fisher information is
  // stable for 0.2–5× its steps): the bound agrees to 4 % between 0.2× and 1× these; from ~5× up the
  // differences stop being derivatives of the outline and the "bound" falls (by 25 % at 5×; the 0.27-px
  // steps of the 2026-11-22 version gave 0.039° instead of 0.053° at 276 px).
  const double px = 0.02 * R / cam.fx();
  const double step[kParams] = {px, px, px, px / 2.5, px / 2.5, 0.5, 0.5, 0.5, px, 0.02, 0.5};
  const cv::Mat s0 = Signal(s, cam);
  std::vector<cv::Mat> g(kParams);
  for (int k = 0; k < kParams; ++k) {
    double d[kParams] = {0};
    d[k] = step[k];
    const cv::Mat p = Signal(Apply(s, d, cam), cam);
    d[k] = -step[k];
    const cv::Mat m = Signal(Apply(s, d, cam), cam);
    g[k] = (p - m) / (2.0 * step[k]);
  }
  Eigen::Matrix<double, kParams, kParams> J = Eigen::Matrix<double, kParams, kParams>::Zero();
  for (int y = 0; y < s0.rows; ++y) {
    const double* sig = s0.ptr<double>(y);
    for (int x = 0; x < s0.cols; ++x) {
      const double var = read_dn * read_dn + (gain > 0 ? sig[x] / gain : 0.0) + 1.0 / 12.0;
      Eigen::Matrix<double, kParams, 1> v;
      for (int k = 0; k < kParams; ++k) v(k) = g[k].ptr<double>(y)[x];
      J.noalias() += v * v.transpose() / var;
    }
  }
  Eigen::Matrix<double, 6, 1> out;
  int col = 0;
  for (int n : {8, 9, 11}) {  // the first n parameters unknown, the others known
    const Eigen::MatrixXd C = J.topLeftCorner(n, n).inverse();
    out(col++) = RadToDeg(std::sqrt(C(3, 3)));
    out(col++) = RadToDeg(std::sqrt(C(4, 4)));
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int phases = 4;
  sim::SilhouetteRenderOptions ro;  // rk-sim theodolite's defaults: sky 180, body 60 DN, PSF 0.8 px
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--phases") && i + 1 < argc) phases = std::atoi(argv[++i]);
    if (!std::strcmp(argv[i], "--read-noise") && i + 1 < argc) ro.sensor.read_noise_dn = std::atof(argv[++i]);
    if (!std::strcmp(argv[i], "--gain") && i + 1 < argc) ro.sensor.gain_e_per_dn = std::atof(argv[++i]);
  }
  camera::CameraModel cam = sim::Seed004Camera();
  cam.width_px = cam.height_px = 640;  // the 640×640 crop of bench/cylinder_tables.cc, same optics
  cam.principal_point_px = {319.5, 319.5};
  const camera::CameraModel full = sim::Seed004Camera();

  struct Row {
    std::string name;
    double R, E, p_th, p_ph;
  };
  std::vector<Row> rows;
  const double t4_n[5] = {100, 106, 116, 254, 276};
  const double t4_p[5][2] = {{4.859, 0.107}, {3.468, 0.081}, {1.210, 0.031}, {0.555, 0.201}, {0.197, 0.054}};
  for (int i = 0; i < 5; ++i)
    rows.push_back({"T4 n=" + std::to_string(static_cast<int>(t4_n[i])), RangeForLength(t4_n[i], 16.274, full), 16.274,
                    t4_p[i][0], t4_p[i][1]});
  const double r276 = rows.back().R;
  const double t5_E[6] = {16.274, 20.125, 30.298, 30.727, 31.054, 34.204};
  const double t5_p[6][2] = {{0.121, 0.048}, {0.201, 0.098}, {0.544, 0.339}, {1.019, 0.647}, {1.384, 0.891}, {4.640, 3.412}};
  for (int i = 0; i < 6; ++i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "T5 E=%.3f", t5_E[i]);
    rows.push_back({buf, r276, t5_E[i], t5_p[i][0], t5_p[i][1]});
  }

  std::printf("Single-frame Cramer-Rao bound of yaw, pitch from the rendered image (read %.2f DN, %.0f e-/DN, PSF %.2f px, "
              "8 bit; %d sub-pixel phases)\n", ro.sensor.read_noise_dn, ro.sensor.gain_e_per_dn, ro.psf_sigma_px, phases);
  std::printf("%-14s %7s | %-13s | %-13s | %-15s | %-15s | %-15s | %s\n", "row", "R m", "paper dth dph", "1/4 paper",
              "nose known", "nose unknown", "+PSF, shading", "1/4 paper reachable, nose unknown (yaw, pitch)");
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> U(-0.5, 0.5);
  for (const Row& r : rows) {
    Eigen::Matrix<double, 6, 1> var = Eigen::Matrix<double, 6, 1>::Zero();
    for (int k = 0; k < phases; ++k) {
      Scene s;
      s.render = ro;
      const target::CylinderShape shape;
      s.truth.pose = target::PoseAt(r.R, DegToRad(kAz), DegToRad(r.E), DegToRad(kYaw), DegToRad(kPitch), shape);
      const Eigen::Vector3d mid = s.truth.pose.tail_centre_enu + 0.5 * shape.length_m * s.truth.pose.Axis();
      const geo::AzEl ae = geo::AzElFromEnu(mid);
      s.truth.boresight_az_rad = ae.az_rad + U(rng) * 20 / cam.fx() / std::cos(ae.el_rad);
      s.truth.boresight_el_rad = ae.el_rad - U(rng) * 20 / cam.fy();
      const double zero[kParams] = {0};
      s = Apply(s, zero, cam);
      const Eigen::Matrix<double, 6, 1> b = Bound(s, cam, ro.sensor.read_noise_dn, ro.sensor.gain_e_per_dn);
      var += b.cwiseProduct(b);
    }
    const Eigen::Matrix<double, 6, 1> b = (var / phases).cwiseSqrt();
    std::printf("%-14s %7.0f | %6.3f %6.3f | %6.3f %6.3f | %7.4f %7.4f | %7.4f %7.4f | %7.4f %7.4f | %s, %s\n", r.name.c_str(), r.R,
                r.p_th, r.p_ph, r.p_th / 4, r.p_ph / 4, b(0), b(1), b(2), b(3), b(4), b(5), b(2) <= r.p_th / 4 ? "yes" : "NO",
                b(3) <= r.p_ph / 4 ? "yes" : "NO");
  }
  return 0;
}

// Single-station theodolite scene of seed 004; model in theodolite_scene.h.
#include "sim/theodolite_scene.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace {


std::string Num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace

camera::CameraModel Seed004Camera() {
  camera::CameraModel c;
  c.width_px = 1536;  // 16.9 mm / 0.011 mm
  c.height_px = 1536;
  c.pixel_size_mm = {0.011, 0.011};
  c.focal_length_mm = 1500.0;
  c.principal_point_px = {767.5, 767.5};
  return c;
}

const io::OptionTable<TheodoliteSimOptions>& TheodoliteSimOptions::Table() {
  using O = TheodoliteSimOptions;
  using io::Bounds;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--length-m", [](O& o) -> double& { return o.shape.length_m; }, "m", Bounds::Positive(),
                "Target length, nose tip to tail plane (m)")
          .Real("--diameter-m", [](O& o) -> double& { return o.shape.diameter_m; }, "m", Bounds::Positive(),
                "Target diameter (m)")
          .Real("--nose-length-m", [](O& o) -> double& { return o.shape.nose_length_m; }, "m", Bounds::Positive(),
                "Conical nose length (m), for the images")
          .Real("--range-m", &O::range_m, "m", Bounds::Closed(10, 1e6), "Range to the target mid-point at mid-trial (m)")
          .Real("--az-deg", &O::az_deg, "deg", Bounds::Any(), "Azimuth of the target at mid-trial (deg)")
          .Real("--el-deg", &O::el_deg, "deg", Bounds::Closed(-10, 89),
                "Elevation of the target at mid-trial = theodolite elevation (deg)")
          .Real("--yaw-deg", &O::yaw_deg, "deg", Bounds::Any(), "Axis yaw at mid-trial (deg, clockwise from north)")
          .Real("--pitch-deg", &O::pitch_deg, "deg", Bounds::Closed(-90, 90), "Axis pitch at mid-trial (deg)")
          .Real("--speed-mps", &O::speed_mps, "m/s", Bounds::Any(), "Speed along the axis (m/s)")
          .Real("--yaw-rate-deg-s", &O::yaw_rate_deg_s, "deg/s", Bounds::Any(), "Yaw rate (deg/s)")
          .Real("--pitch-rate-deg-s", &O::pitch_rate_deg_s, "deg/s", Bounds::Any(), "Pitch rate (deg/s)")
          .Real("--duration", &O::duration_s, "s", Bounds::Closed(0, 3600),
                "Trial length (s); frames at t0 + k/fps over [t0, t0 + duration]")
          .Real("--fps", &O::fps, "Hz", Bounds::LeftOpen(0, 1000), "Frame rate (Hz)")
          .Real("--t0", &O::t0_s, "s", Bounds::Any(), "Time of frame 0 since the epoch (s)")
          .Real("--track-error-px", &O::track_error_px, "px", Bounds::Closed(0, 1e4),
                "Amplitude of the theodolite tracking error in the image (px)")
          .Real("--theodolite-rate-hz", &O::theodolite_rate_hz, "Hz", Bounds::LeftOpen(0, 10000),
                "Theodolite log rate (Hz)")
          .Real("--theodolite-offset", &O::theodolite_offset_s, "s", Bounds::Any(),
                "Theodolite log time offset from the frame grid (s)")
          .Real("--angle-bias-arcsec", &O::angle_bias_arcsec, "arcsec", Bounds::AtLeast(0),
                "Std of the per-trial bias of each theodolite angle (arcsec)")
          .Real("--angle-noise-arcsec", &O::angle_noise_arcsec, "arcsec", Bounds::AtLeast(0),
                "Std of the per-sample noise of each angle (arcsec)")
          .Real("--encoder-step-arcsec", &O::encoder_step_arcsec, "arcsec", Bounds::AtLeast(0),
                "Quantisation of the recorded angles (arcsec); 0 = none")
          .Real("--point-noise-px", &O::point_noise_px, "px", Bounds::AtLeast(0),
                "Gaussian noise added to the written image points (px)")
          .Flag("--quantise", &O::quantise,
                "Round the written image points to whole pixels (the paper's 1-pixel reading)")
          .Count("--seed", &O::seed, "", Bounds::Any(), "Random seed (same seed, same files)");
  return table;
}

bool TheodoliteSimOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    *why = w;
    return false;
  };
  if (!Table().Check(*this, why)) return false;
  for (double v : {shape.length_m, shape.diameter_m, az_deg, yaw_deg, speed_mps, yaw_rate_deg_s, pitch_rate_deg_s,
                   t0_s, theodolite_offset_s, angle_bias_arcsec, angle_noise_arcsec, encoder_step_arcsec,
                   point_noise_px}) {
    if (!std::isfinite(v)) return fail("sizes, angles, rates, speed, times, noise and step options must be finite");
  }
  if (!(shape.nose_length_m < shape.length_m)) return fail("--nose-length-m must be in (0, length)");
  return true;
}

io::Json TheodoliteSimOptionsToJson(const TheodoliteSimOptions& o) {
  return io::Json{{"camera", camera::CameraModelToJson(o.camera)},
                  {"target", {{"length_m", o.shape.length_m},
                              {"diameter_m", o.shape.diameter_m},
                              {"nose_length_m", o.shape.nose_length_m}}},
                  {"range_m", o.range_m},
                  {"az_deg", o.az_deg},
                  {"el_deg", o.el_deg},
                  {"yaw_deg", o.yaw_deg},
                  {"pitch_deg", o.pitch_deg},
                  {"speed_mps", o.speed_mps},
                  {"yaw_rate_deg_s", o.yaw_rate_deg_s},
                  {"pitch_rate_deg_s", o.pitch_rate_deg_s},
                  {"duration_s", o.duration_s},
                  {"fps", o.fps},
                  {"t0_s", o.t0_s},
                  {"track_error_px", o.track_error_px},
                  {"theodolite_rate_hz", o.theodolite_rate_hz},
                  {"theodolite_offset_s", o.theodolite_offset_s},
                  {"angle_bias_arcsec", o.angle_bias_arcsec},
                  {"angle_noise_arcsec", o.angle_noise_arcsec},
                  {"encoder_step_arcsec", o.encoder_step_arcsec},
                  {"point_noise_px", o.point_noise_px},
                  {"quantise", o.quantise},
                  {"seed", o.seed}};
}

TheodoliteSimulator::TheodoliteSimulator(TheodoliteSimOptions opt) : opt_(std::move(opt)) {
  std::string why;
  if (!opt_.Check(&why)) throw UsageError(why);
  using geo::DegToRad;
  t_ref_ = opt_.t0_s + 0.5 * opt_.duration_s;
  pose_ref_ = target::PoseAt(opt_.range_m, DegToRad(opt_.az_deg), DegToRad(opt_.el_deg),
                             DegToRad(opt_.yaw_deg), DegToRad(opt_.pitch_deg), opt_.shape);
  {
    std::mt19937_64 rng = RandomStream(opt_.seed, 1);
    std::uniform_real_distribution<double> phase(0.0, geo::kTwoPi);
    std::normal_distribution<double> normal(0.0, 1.0);
    phase_x_ = phase(rng);
    phase_y_ = phase(rng);
    const double bias = opt_.angle_bias_arcsec / geo::kArcsecPerRad;
    bias_az_ = bias * normal(rng);
    bias_el_ = bias * normal(rng);
  }
  std::mt19937_64 point_rng = RandomStream(opt_.seed, 3);
  std::normal_distribution<double> normal(0.0, 1.0);
  const camera::CameraModel& cam = opt_.camera;
  const auto n_frames = static_cast<std::int64_t>(std::floor(opt_.duration_s * opt_.fps + 1e-9)) + 1;
  frames_.reserve(static_cast<std::size_t>(n_frames));
  for (std::int64_t k = 0; k < n_frames; ++k) {
    TheodoliteFrameTruth f;
    f.frame = k;
    f.t_s = opt_.t0_s + static_cast<double>(k) / opt_.fps;
    f.pose = PoseAtTime(f.t_s);
    if (f.pose.Axis().cross(f.pose.tail_centre_enu.normalized()).norm() < 1e-9) {
      throw UsageError("the axis points exactly along the line of sight at frame " + std::to_string(k) +
                       " (tail-chase view): tail1/tail2 are undefined");
    }
    f.points = target::SilhouettePointsOf(f.pose, opt_.shape);
    TrueBoresight(f.t_s, &f.boresight_az_rad, &f.boresight_el_rad);
    const Eigen::Vector3d* pts[3] = {&f.points.nose, &f.points.tail1, &f.points.tail2};
    Eigen::Vector2d* px[3] = {&f.nose_px, &f.tail1_px, &f.tail2_px};
    for (int i = 0; i < 3; ++i) {
      const auto p = cam.ProjectEnu(*pts[i], f.boresight_az_rad, f.boresight_el_rad);
      if (!p) throw UsageError("a silhouette point is behind the camera at frame " + std::to_string(k));
      *px[i] = *p;
      if (p->x() < 0.0 || p->y() < 0.0 || p->x() > cam.width_px - 1 ||
          p->y() > cam.height_px - 1) {
        f.in_image = false;
      }
      Eigen::Vector2d m = *p;
      if (opt_.point_noise_px > 0.0) {
        m.x() += opt_.point_noise_px * normal(point_rng);
        m.y() += opt_.point_noise_px * normal(point_rng);
      }
      if (opt_.quantise) m = Eigen::Vector2d(std::round(m.x()), std::round(m.y()));
      f.measured_px[static_cast<std::size_t>(i)] = m;
    }
    if (!f.in_image) {
      throw UsageError("the target leaves the " + std::to_string(cam.width_px) + "x" + std::to_string(cam.height_px) +
                       " image at frame " + std::to_string(k) + " (t = " + Num(f.t_s) +
                       " s); reduce --track-error-px, the speed or the duration, or increase --range-m");
    }
    f.view_angle_rad = target::ViewAngle(f.pose);
    f.image_length_px = (f.nose_px - 0.5 * (f.tail1_px + f.tail2_px)).norm();
    // Mirror solution on the exact rays: R2 = R3 = R, c = c12 = c13, R1 = R c ± sqrt(L'² − R² (1 − c²)).
    {
      const Eigen::Vector3d u1 = f.points.nose.normalized();
      const Eigen::Vector3d u2 = f.points.tail1.normalized();
      const double R = f.points.tail1.norm();
      const double k = 0.5 * (u1 - u2).squaredNorm();
      const double c = 1.0 - k;
      const double s = u1.cross(u2).norm();
      const double L = std::sqrt(0.25 * opt_.shape.diameter_m * opt_.shape.diameter_m +
                                 opt_.shape.length_m * opt_.shape.length_m);
      const double q = L * L - R * R * s * s;
      if (q > 0.0) {
        const double r_true = f.points.nose.norm();
        const double r_a = R * c + std::sqrt(q), r_b = R * c - std::sqrt(q);
        const double r_alt = std::abs(r_a - r_true) > std::abs(r_b - r_true) ? r_a : r_b;
        if (r_alt > 0.0) {
          const geo::AzEl ae = geo::AzElFromEnu(r_alt * u1 - f.points.tail_centre);
          f.alt_yaw_rad = ae.az_rad;
          f.alt_pitch_rad = ae.el_rad;
        }
      }
    }
    frames_.push_back(f);
  }
}

target::CylinderPose TheodoliteSimulator::PoseAtTime(double t_s) const {
  using geo::DegToRad;
  const double dt = t_s - t_ref_;
  const Eigen::Vector3d a_ref = pose_ref_.Axis();
  const Eigen::Vector3d mid_ref = pose_ref_.tail_centre_enu + 0.5 * opt_.shape.length_m * a_ref;
  target::CylinderPose pose;
  pose.yaw_rad = geo::WrapTwoPi(DegToRad(opt_.yaw_deg + opt_.yaw_rate_deg_s * dt));
  pose.pitch_rad = DegToRad(std::clamp(opt_.pitch_deg + opt_.pitch_rate_deg_s * dt, -90.0, 90.0));
  const Eigen::Vector3d mid = mid_ref + opt_.speed_mps * dt * a_ref;
  pose.tail_centre_enu = mid - 0.5 * opt_.shape.length_m * pose.Axis();
  return pose;
}

void TheodoliteSimulator::TrueBoresight(double t_s, double* az_rad, double* el_rad) const {
  const target::CylinderPose pose = PoseAtTime(t_s);
  const Eigen::Vector3d mid = pose.tail_centre_enu + 0.5 * opt_.shape.length_m * pose.Axis();
  const camera::CameraModel& cam = opt_.camera;
  const Eigen::Vector2d want =
      cam.principal_point_px + opt_.track_error_px * Eigen::Vector2d(std::sin(2 * geo::kPi * 0.37 * t_s + phase_x_),
                                                                     std::cos(2 * geo::kPi * 0.23 * t_s + phase_y_));
  const geo::AzEl ae = geo::AzElFromEnu(mid);
  double A = ae.az_rad, E = ae.el_rad;
  // Fixed-point iteration on the exact projection: moving the boresight right (A up) moves the image left.
  for (int it = 0; it < 50; ++it) {
    const auto p = cam.ProjectEnu(mid, A, E);
    if (!p) break;
    const Eigen::Vector2d err = *p - want;
    if (err.norm() < 1e-11) break;
    A += err.x() / cam.fx() / std::max(std::cos(E), 1e-6);
    E -= err.y() / cam.fy();
  }
  *az_rad = geo::WrapTwoPi(A);
  *el_rad = E;
}

std::vector<TheodoliteSample> TheodoliteSimulator::TheodoliteLog() const {
  std::vector<TheodoliteSample> log;
  const double t_first = opt_.t0_s - 0.5 + opt_.theodolite_offset_s;
  const double t_last = frames_.back().t_s + 0.5;
  const auto n = static_cast<std::int64_t>(std::floor((t_last - t_first) * opt_.theodolite_rate_hz)) + 1;
  std::mt19937_64 rng = RandomStream(opt_.seed, 2);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double noise = opt_.angle_noise_arcsec / geo::kArcsecPerRad;
  const double step = opt_.encoder_step_arcsec / geo::kArcsecPerRad;
  log.reserve(static_cast<std::size_t>(n));
  for (std::int64_t j = 0; j < n; ++j) {
    TheodoliteSample s;
    s.t_s = t_first + static_cast<double>(j) / opt_.theodolite_rate_hz;
    TrueBoresight(s.t_s, &s.true_az_rad, &s.true_el_rad);
    double az = s.true_az_rad + bias_az_ + noise * normal(rng);
    double el = s.true_el_rad + bias_el_ + noise * normal(rng);
    if (step > 0.0) {
      az = std::round(az / step) * step;
      el = std::round(el / step) * step;
    }
    s.az_rad = geo::WrapTwoPi(az);
    s.el_rad = el;
    log.push_back(s);
  }
  return log;
}

}  // namespace rk::sim

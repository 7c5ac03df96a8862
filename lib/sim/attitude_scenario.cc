// rk-sim attitude scene; model in attitude_scenario.h.
#include "sim/attitude_scenario.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geo/angles.h"
#include "io/error.h"
#include "sim/attitude_render.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace {



double Ramp(double tau) {
  if (tau <= 0) return 0.0;
  if (tau >= 1) return 1.0;
  return 0.5 * (1.0 - std::cos(M_PI * tau));
}

std::int64_t FrameCount(const AttitudeSimOptions& o) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(o.duration_s * o.fps + 1e-9)));
}

double LastFrameTime(const AttitudeSimOptions& o) {
  return o.t0_s + static_cast<double>(FrameCount(o) - 1) / o.fps;
}

std::string Fmt(double v, int prec = 3) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(prec);
  s << v;
  return s.str();
}

AttitudeSimOptions Prepared(AttitudeSimOptions o) {
  if (o.marker_ids.empty()) DefaultAttitudeMarkers(&o.marker_ids, &o.markers_body);
  std::string why;
  if (!o.Check(&why)) throw UsageError(why);
  return o;
}

}  // namespace

camera::CameraModel AttitudeCamera() {
  camera::CameraModel c;
  c.focal_length_mm = 100.0;
  return c;
}

void DefaultAttitudeMarkers(std::vector<std::string>* ids, std::vector<Eigen::Vector3d>* p) {
  *ids = {"belly", "canopy", "fin", "ltail", "lwing", "nose", "rwing", "tail"};
  *p = {{0.05, 0.02, 0.14},   {0.22, -0.03, -0.09}, {-0.30, 0.00, -0.26}, {-0.28, -0.18, 0.03},
        {-0.06, -0.36, -0.01}, {0.42, 0.00, 0.02},   {0.10, 0.33, 0.03},   {-0.38, 0.03, -0.04}};
}

bool ParseMarkerHide(const std::string& text, MarkerHide* h, std::string* why) {
  const std::size_t a = text.find(':');
  const std::size_t b = a == std::string::npos ? a : text.find(':', a + 1);
  if (a == std::string::npos || b == std::string::npos || a == 0) {
    *why = "--hide must be ID:START_S:DURATION_S, not '" + text + "'";
    return false;
  }
  h->id = text.substr(0, a);
  try {
    std::size_t used = 0;
    const std::string s0 = text.substr(a + 1, b - a - 1), s1 = text.substr(b + 1);
    h->start_s = std::stod(s0, &used);
    if (used != s0.size()) throw std::invalid_argument(s0);
    h->duration_s = std::stod(s1, &used);
    if (used != s1.size()) throw std::invalid_argument(s1);
  } catch (const std::exception&) {
    *why = "--hide must be ID:START_S:DURATION_S with numbers, not '" + text + "'";
    return false;
  }
  if (!(h->duration_s > 0) || !std::isfinite(h->start_s)) {
    *why = "--hide duration must be > 0 s";
    return false;
  }
  return true;
}

const io::OptionTable<AttitudeSimOptions>& AttitudeSimOptions::Table() {
  using O = AttitudeSimOptions;
  using io::Bounds;
  using geo::RadToDeg;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--duration", &O::duration_s, "s", Bounds::LeftOpen(0, 3600),
                "Trial length (s); the default 22 s covers the approach and the return")
          .Real("--fps", &O::fps, "Hz", Bounds::LeftOpen(0, 1000), "Frame rate (Hz)")
          .Real("--t0", &O::t0_s, "s", Bounds::Any(), "Time of frame 0 since the epoch (s)")
          .Count("--seed", &O::seed, "", Bounds::Any(), "Random seed (same seed, same trial)")
          .Real("--range-m", &O::range_m, "m", Bounds::Closed(2, 10000), "Initial range of the body origin (m)")
          .Real("--azimuth-deg", &O::azimuth_deg, "deg", Bounds::Any(), "Initial azimuth of the target (deg)")
          .Real("--elevation-deg", &O::elevation_deg, "deg", Bounds::Closed(RadToDeg(-0.2), RadToDeg(1.4)),
                "Initial elevation of the target (deg)")
          .Real("--approach-m", &O::approach_m, "m", Bounds::AtLeast(0),
                "Distance moved toward the station on the way in (m)")
          .Real("--return-m", &O::return_m, "m", Bounds::AtLeast(0), "Distance moved back on the way out (m)")
          .Real("--leg-in-s", &O::leg_in_s, "s", Bounds::Positive(), "Duration of the approach (s), from the first frame")
          .Real("--leg-out-s", &O::leg_out_s, "s", Bounds::Positive(), "Duration of the return (s), after the approach")
          .Real("--path-angle-deg", &O::path_angle_deg, "deg", Bounds::Closed(-RadToDeg(1.5), RadToDeg(1.5)),
                "Angle of the (horizontal) motion from the line of sight to the station (deg)")
          .Real("--yaw0-deg", &O::yaw0_deg, "deg", Bounds::Any(), "Initial yaw (deg, clockwise from north)")
          .Real("--pitch0-deg", &O::pitch0_deg, "deg", Bounds::Any(), "Initial pitch (deg)")
          .Real("--roll0-deg", &O::roll0_deg, "deg", Bounds::Any(), "Initial roll (deg)")
          .Real("--dyaw-deg", &O::dyaw_deg, "deg", Bounds::Any(), "Yaw change on the way in (deg), undone on the way out")
          .Real("--dpitch-deg", &O::dpitch_deg, "deg", Bounds::Any(), "Pitch change on the way in (deg)")
          .Real("--droll-deg", &O::droll_deg, "deg", Bounds::Any(), "Roll change on the way in (deg)")
          .Real("--marker-radius-m", &O::marker_radius_m, "m", Bounds::LeftOpen(0, 1), "Marker sphere radius (m)")
          .Real("--marker-dn", &O::marker_dn, "DN", Bounds::LeftOpen(0, 255), "Marker level above background (8-bit DN)")
          .Real("--body-dn", &O::body_dn, "DN", Bounds::Closed(0, 255),
                "Target body level above background (8-bit DN); 0 = no body")
          .Real("--psf-sigma-px", &O::psf_sigma_px, "px", Bounds::Closed(0.3, 10), "PSF std (px)")
          .Sub(&O::sensor, SensorOptions::Table())
          .Real("--turret-rate-hz", &O::turret_rate_hz, "Hz", Bounds::LeftOpen(0, 10000), "Turret log rate (Hz)")
          .Real("--turret-offset-s", &O::turret_offset_s, "s", Bounds::Any(),
                "Turret sample time offset from the frame grid (s)")
          .Real("--turret-noise-deg", &O::turret_resolution_deg, "deg", Bounds::AtLeast(0),
                "Turret encoder step (deg): recorded angles are quantised to it; 0 = exact (as rk-sim beacon)")
          .Real("--turret-noise-std-deg", &O::turret_noise_deg, "deg", Bounds::AtLeast(0),
                "Extra Gaussian turret angle noise std (deg)")
          .Sub(&O::servo, TurretServoOptions::Table());
  return table;
}

bool AttitudeSimOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    *why = w;
    return false;
  };
  if (marker_ids.size() != markers_body.size()) return fail("marker ids and points differ in number");
  if (!marker_ids.empty() && marker_ids.size() < 4) return fail("the target needs at least 4 markers");
  if (!Table().Check(*this, why) || !sensor.Check(why) || !servo.Check(why)) return false;
  for (double v : {t0_s, azimuth_deg, leg_in_s + leg_out_s}) {
    if (!std::isfinite(v)) return fail("--t0, --azimuth-deg, --leg-in-s and --leg-out-s must be finite");
  }
  if (!(approach_m <= 0.9 * range_m)) return fail("--approach-m must be in [0, 0.9 range]");
  if (!(return_m <= approach_m + 0.5 * range_m)) return fail("--return-m out of range");
  for (double a : {yaw0_deg, pitch0_deg, roll0_deg, dyaw_deg, dpitch_deg, droll_deg}) {
    if (!std::isfinite(a)) return fail("attitude angles must be finite");
  }
  if (std::abs(pitch0_rad()) > 1.5 || std::abs(pitch0_rad() + dpitch_rad()) > 1.5) {
    return fail("pitch must stay within ±86 degrees");
  }
  for (const auto& h : hides) {
    if (std::find(marker_ids.begin(), marker_ids.end(), h.id) == marker_ids.end() && !marker_ids.empty()) {
      return fail("--hide names marker '" + h.id + "', which the target does not have");
    }
    if (!(h.duration_s > 0)) return fail("--hide duration must be > 0 s");
  }
  for (std::size_t i = 0; i < marker_ids.size(); ++i) {
    if (!markers_body[i].allFinite()) return fail("marker coordinates must be finite");
  }
  return true;
}

io::Json AttitudeSimOptions::ToJson() const {
  const io::Json sim = AttitudeSimOptionsToJson(*this);
  io::Json j = Table().ToJson(*this);
  for (const char* key : {"camera", "markers_body_m", "hide"}) j[key] = sim[key];
  return j;
}

io::Json AttitudeSimOptionsToJson(const AttitudeSimOptions& o) {
  using geo::RadToDeg;
  io::Json j;
  j["camera"] = camera::CameraModelToJson(o.camera);
  io::Json m = io::Json::object();
  for (std::size_t i = 0; i < o.marker_ids.size(); ++i) {
    m[o.marker_ids[i]] = {o.markers_body[i].x(), o.markers_body[i].y(), o.markers_body[i].z()};
  }
  j["markers_body_m"] = m;
  j["marker_radius_m"] = o.marker_radius_m;
  j["marker_dn"] = o.marker_dn;
  j["psf_sigma_px"] = o.psf_sigma_px;
  j["body_dn"] = o.body_dn;
  j["sensor"] = {{"background_dn", o.sensor.background_dn},
                 {"read_noise_dn", o.sensor.read_noise_dn},
                 {"gain_e_per_dn", o.sensor.gain_e_per_dn},
                 {"bit_depth", o.sensor.bit_depth}};
  j["duration_s"] = o.duration_s;
  j["fps"] = o.fps;
  j["t0_s"] = o.t0_s;
  j["range_m"] = o.range_m;
  j["azimuth_deg"] = RadToDeg(o.azimuth_rad());
  j["elevation_deg"] = RadToDeg(o.elevation_rad());
  j["approach_m"] = o.approach_m;
  j["return_m"] = o.return_m;
  j["leg_in_s"] = o.leg_in_s;
  j["leg_out_s"] = o.leg_out_s;
  j["path_angle_deg"] = RadToDeg(o.path_angle_rad());
  j["attitude0_deg"] = {RadToDeg(o.yaw0_rad()), RadToDeg(o.pitch0_rad()), RadToDeg(o.roll0_rad())};
  j["attitude_change_deg"] = {RadToDeg(o.dyaw_rad()), RadToDeg(o.dpitch_rad()), RadToDeg(o.droll_rad())};
  j["turret"] = {{"lag_s", o.servo.lag_s},
                 {"jitter_arcsec", o.servo.jitter_rms_rad() * geo::kArcsecPerRad},
                 {"rate_hz", o.turret_rate_hz},
                 {"offset_s", o.turret_offset_s},
                 {"resolution_deg", RadToDeg(o.turret_resolution_rad())},
                 {"noise_deg", RadToDeg(o.turret_noise_rad())}};
  io::Json hides = io::Json::array();
  for (const auto& h : o.hides) hides.push_back({{"id", h.id}, {"start_s", h.start_s}, {"duration_s", h.duration_s}});
  j["hide"] = hides;
  j["seed"] = o.seed;
  return j;
}

void AttitudeSimulator::Ramps(double t, double* u1, double* u2) const {
  const double T1 = opt_.leg_in_s, T2 = opt_.leg_out_s;
  *u1 = Ramp((t - opt_.t0_s) / T1);
  *u2 = Ramp((t - opt_.t0_s - T1) / T2);
}

double AttitudeSimulator::Progress(double t) const {
  double u1, u2;
  Ramps(t, &u1, &u2);
  return u1 - u2;
}

Eigen::Vector3d AttitudeSimulator::PositionEnu(double t) const {
  double u1, u2;
  Ramps(t, &u1, &u2);
  return p0_enu_ + dir_enu_ * (opt_.approach_m * u1 - opt_.return_m * u2);
}

geo::EulerZyx AttitudeSimulator::Attitude(double t) const {
  const double a = Progress(t);
  // Through the rotation matrix so that the angles come back in their SPEC ranges.
  const Eigen::Matrix3d R = geo::RotationNedFromBody(opt_.yaw0_rad() + opt_.dyaw_rad() * a,
                                                     opt_.pitch0_rad() + opt_.dpitch_rad() * a,
                                                     opt_.roll0_rad() + opt_.droll_rad() * a);
  return geo::EulerFromRotationNedBody(R);
}

AttitudeSimulator::AttitudeSimulator(AttitudeSimOptions opt) : opt_(Prepared(std::move(opt))) {
  p0_enu_ = opt_.range_m * geo::DirectionFromAzEl(opt_.azimuth_rad(), opt_.elevation_rad());
  const Eigen::Vector3d toward(-std::sin(opt_.azimuth_rad()), -std::cos(opt_.azimuth_rad()), 0.0);
  const double c = std::cos(opt_.path_angle_rad()), s = std::sin(opt_.path_angle_rad());
  // Clockwise (seen from above) rotation of `toward` by path_angle.
  dir_enu_ = Eigen::Vector3d(c * toward.x() + s * toward.y(), -s * toward.x() + c * toward.y(), 0.0);
  const std::int64_t n = FrameCount(opt_);
  servo_.emplace(opt_.servo, [this](double t) { return PositionEnu(t); }, opt_.t0_s - kServoMarginS,
                 LastFrameTime(opt_) + kServoMarginS, opt_.seed);
  const camera::CameraModel& cam = opt_.camera;
  const std::size_t m = opt_.marker_ids.size();
  frames_.reserve(static_cast<std::size_t>(n));
  for (std::int64_t k = 0; k < n; ++k) {
    AttitudeFrameTruth f;
    f.frame = k;
    f.t_s = opt_.t0_s + static_cast<double>(k) / opt_.fps;
    f.p_enu = PositionEnu(f.t_s);
    f.attitude = Attitude(f.t_s);
    f.R_enu_body = geo::RotationEnuFromBody(f.attitude);
    f.boresight = servo_->Boresight(f.t_s);
    f.min_separation_px = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < m; ++i) {
      const Eigen::Vector3d p = f.p_enu + f.R_enu_body * opt_.markers_body[i];
      const auto uv = cam.ProjectEnu(p, f.boresight.az_rad, f.boresight.el_rad);
      const double d = p.norm();
      if (!uv || d <= opt_.marker_radius_m) {
        throw UsageError("marker '" + opt_.marker_ids[i] + "' is behind the camera in frame " + std::to_string(k));
      }
      const double rho = cam.fx() * std::asin(std::min(1.0, opt_.marker_radius_m / d));
      const double reach = rho + 3.0 * opt_.psf_sigma_px + 1.0;
      if (uv->x() < reach - 0.5 || uv->y() < reach - 0.5 || uv->x() > cam.width_px - 0.5 - reach ||
          uv->y() > cam.height_px - 0.5 - reach) {
        throw UsageError("marker '" + opt_.marker_ids[i] + "' leaves the " + std::to_string(cam.width_px) + "x" +
                         std::to_string(cam.height_px) + " image in frame " + std::to_string(k) + " (at " +
                         Fmt(uv->x(), 1) + ", " + Fmt(uv->y(), 1) +
                         " px): the target is too large or too close for the lens, or the turret lags too much");
      }
      f.marker_px.push_back(*uv);
      f.marker_radius_px.push_back(rho);
      bool visible = true;
      for (const auto& h : opt_.hides) {
        const double s0 = opt_.t0_s + h.start_s;
        if (h.id == opt_.marker_ids[i] && f.t_s >= s0 && f.t_s < s0 + h.duration_s) visible = false;
      }
      f.visible.push_back(visible);
    }
    for (std::size_t a = 0; a < m; ++a) {
      for (std::size_t b = a + 1; b < m; ++b) {
        if (f.visible[a] && f.visible[b]) {
          f.min_separation_px = std::min(f.min_separation_px, (f.marker_px[a] - f.marker_px[b]).norm());
        }
      }
    }
    frames_.push_back(std::move(f));
  }
}

cv::Mat AttitudeSimulator::RenderSignal(std::size_t k) const {
  const AttitudeFrameTruth& f = frames_.at(k);
  cv::Mat signal = cv::Mat::zeros(opt_.camera.height_px, opt_.camera.width_px, CV_32FC1);
  if (opt_.body_dn > 0) {
    // Body outline: the markers' hull grown outward from its centroid by 3 radii + 10 px.
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : f.marker_px) c += p;
    c /= static_cast<double>(f.marker_px.size());
    std::vector<Eigen::Vector2d> grown;
    for (std::size_t i = 0; i < f.marker_px.size(); ++i) {
      const Eigen::Vector2d d = f.marker_px[i] - c;
      const double len = d.norm();
      const double grow = 3.0 * f.marker_radius_px[i] + 10.0;
      grown.push_back(len > 0 ? f.marker_px[i] + d * (grow / len) : f.marker_px[i]);
      // Also grow sideways so that a marker on a hull edge is well inside.
      grown.push_back(f.marker_px[i] + Eigen::Vector2d(grow, 0));
      grown.push_back(f.marker_px[i] - Eigen::Vector2d(grow, 0));
      grown.push_back(f.marker_px[i] + Eigen::Vector2d(0, grow));
      grown.push_back(f.marker_px[i] - Eigen::Vector2d(0, grow));
    }
    AddConvexHull(&signal, grown, opt_.body_dn);
  }
  std::vector<Disc> discs;
  for (std::size_t i = 0; i < f.marker_px.size(); ++i) {
    if (!f.visible[i]) continue;
    Disc d;
    d.x_px = f.marker_px[i].x();
    d.y_px = f.marker_px[i].y();
    d.radius_px = f.marker_radius_px[i];
    d.psf_sigma_px = opt_.psf_sigma_px;
    d.amplitude_dn = opt_.marker_dn;
    discs.push_back(d);
  }
  AddDiscs(&signal, discs);
  return signal;
}

cv::Mat AttitudeSimulator::RenderFrame(std::size_t k) const {
  cv::Mat signal = RenderSignal(k);
  SensorOptions s = opt_.sensor;
  if (s.bit_depth == 16) {
    signal *= 256.0;
    s.background_dn *= 256.0;
    s.read_noise_dn *= 256.0;
    s.gain_e_per_dn /= 256.0;
  }
  std::mt19937_64 rng = RandomStream(opt_.seed, 1000, static_cast<std::uint64_t>(k));
  return Digitise(signal, s, rng);
}

std::vector<AttitudeTurretSample> AttitudeSimulator::TurretLog() const {
  std::mt19937_64 rng = RandomStream(opt_.seed, 4);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double q = opt_.turret_resolution_rad();
  auto record = [&](double v) {
    if (opt_.turret_noise_rad() > 0) v += opt_.turret_noise_rad() * normal(rng);
    if (q > 0) v = q * std::round(v / q);
    return v;
  };
  std::vector<AttitudeTurretSample> out;
  const double begin = opt_.t0_s - kSampleMarginS + opt_.turret_offset_s;
  const double end = LastFrameTime(opt_) + kSampleMarginS;
  for (std::int64_t i = 0;; ++i) {
    const double t = begin + static_cast<double>(i) / opt_.turret_rate_hz;
    if (t > end) break;
    AttitudeTurretSample s;
    s.t_s = t;
    const geo::AzEl b = servo_->Boresight(t);
    s.true_az_rad = b.az_rad;
    s.true_el_rad = b.el_rad;
    s.az_rad = geo::WrapTwoPi(record(b.az_rad));
    s.el_rad = record(b.el_rad);
    out.push_back(s);
  }
  return out;
}

}  // namespace rk::sim

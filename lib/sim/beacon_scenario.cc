#include "sim/beacon_scenario.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "camera/station_view.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace {

constexpr double kGlintSigmaPx = 1.0;
constexpr double kGlintClearancePx = 30.0;  // glint never nearer than cluster radius + this
constexpr double kGlintEdgePx = 10.0;       // glints stay this far inside the image


// Reflects x into [lo, hi] (a glint bouncing off the image borders).
double Fold(double x, double lo, double hi) {
  const double len = hi - lo;
  if (len <= 0) return lo;
  double y = std::fmod(x - lo, 2 * len);
  if (y < 0) y += 2 * len;
  return lo + (y <= len ? y : 2 * len - y);
}

BeaconSimOptions Prepared(BeaconSimOptions opt) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  opt.trajectory.t_mid_s = opt.t0_s + 0.5 * opt.duration_s;
  return opt;
}

std::int64_t FrameCount(const BeaconSimOptions& o) {
  return static_cast<std::int64_t>(std::floor(o.duration_s * o.fps + 1e-9));
}

double LastFrameTime(const BeaconSimOptions& o) {
  return o.t0_s + static_cast<double>(std::max<std::int64_t>(FrameCount(o) - 1, 0)) / o.fps;
}

// Sample times t0 − margin + offset + i / rate up to t_last + margin.
std::vector<double> SampleTimes(const BeaconSimOptions& o, double rate_hz, double offset_s) {
  std::vector<double> t;
  const double begin = o.t0_s - kSampleMarginS + offset_s;
  const double end = LastFrameTime(o) + kSampleMarginS;
  for (std::int64_t i = 0;; ++i) {
    const double ti = begin + static_cast<double>(i) / rate_hz;
    if (ti > end) break;
    t.push_back(ti);
  }
  return t;
}

}  // namespace

bool CameraPreset(const std::string& name, camera::CameraModel* cam) {
  camera::CameraModel c = camera::DefaultCamera();
  if (name == "default") {
    c.width_px = 2448;
    c.height_px = 2048;
  } else if (name == "small") {
    c.width_px = 640;
    c.height_px = 512;
  } else {
    return false;
  }
  c.pixel_size_mm = {0.00345, 0.00345};
  c.focal_length_mm = 50.0;
  c.principal_point_px = {0.5 * (c.width_px - 1), 0.5 * (c.height_px - 1)};
  *cam = c;
  return true;
}

TrajectoryOptions DefaultTrajectoryOptions(TrajectoryKind kind, double range_m) {
  TrajectoryOptions t = DefaultTrajectoryOptions(kind);
  if (!std::isfinite(range_m)) return t;
  // Keep the angular rate of the default geometry: speed proportional to range.
  const double scale = range_m / t.range_m;
  t.range_m = range_m;
  switch (kind) {
    case TrajectoryKind::kDefault: t.speed_mps *= std::min(1.0, scale); break;
    case TrajectoryKind::kStraight:
    case TrajectoryKind::kTurning:
    case TrajectoryKind::kOverhead: t.speed_mps = std::min(300.0, t.speed_mps * scale); break;
    case TrajectoryKind::kStatic: break;
  }
  return t;
}

TrajectoryOptions DefaultTrajectoryOptions(TrajectoryKind kind) {
  TrajectoryOptions t;
  t.kind = kind;
  t.azimuth_rad = geo::DegToRad(30.0);
  t.elevation_rad = geo::DegToRad(5.0);
  switch (kind) {
    case TrajectoryKind::kDefault: t.range_m = 80.0; t.speed_mps = 2.7; break;
    case TrajectoryKind::kStraight: t.range_m = 500.0; t.speed_mps = 30.0; break;
    case TrajectoryKind::kTurning: t.range_m = 600.0; t.speed_mps = 15.0; t.turn_rate_rad_s = 0.1; break;
    case TrajectoryKind::kOverhead: t.range_m = 150.0; t.speed_mps = 10.0; break;
    case TrajectoryKind::kStatic: t.range_m = 80.0; t.speed_mps = 0.0; break;
  }
  return t;
}

bool ParseOcclusion(const std::string& text, OcclusionInterval* occ, std::string* why) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) {
    *why = "'" + text + "' must be START_S:DURATION_S (DURATION_S may be 'short' or 'long')";
    return false;
  }
  const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
  auto number = [](const std::string& s, double* v) {
    if (s.empty()) return false;
    std::size_t used = 0;
    try {
      *v = std::stod(s, &used);
    } catch (...) {
      return false;
    }
    return used == s.size() && std::isfinite(*v);
  };
  OcclusionInterval o;
  if (!number(a, &o.start_s) || o.start_s < 0) {
    *why = "start '" + a + "' must be a number of seconds >= 0";
    return false;
  }
  if (b == "short") {
    o.duration_s = 0.5;
  } else if (b == "long") {
    o.duration_s = 5.0;
  } else if (!number(b, &o.duration_s) || !(o.duration_s > 0)) {
    *why = "duration '" + b + "' must be a number of seconds > 0, 'short' or 'long'";
    return false;
  }
  *occ = o;
  return true;
}

const io::OptionTable<BeaconSimOptions>& BeaconSimOptions::Table() {
  using O = BeaconSimOptions;
  using io::Bounds;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--duration", &O::duration_s, "s", Bounds::LeftOpen(0, 3600), "Trial length (s)")
          .Real("--fps", &O::fps, "Hz", Bounds::LeftOpen(0, 1000), "Frame rate (Hz)")
          .Real("--t0", &O::t0_s, "s", Bounds::Closed(-1e7, 1e7), "Time of frame 0 since the epoch (s)")
          .Sub(&O::trajectory, TrajectoryOptions::Table())
          .Count("--seed", &O::seed, "", Bounds::Any(), "Random seed (same seed, same trial)")
          .Sub(&O::sensor, SensorOptions::Table())
          .Real("--peak-dn", &O::peak_dn, "DN", Bounds::LeftOpen(0, 255),
                "Brightest lamp amplitude above background (8-bit DN)")
          .Real("--psf-sigma-px", &O::psf_sigma_px, "px", Bounds::Closed(0.3, 10), "Lamp PSF std (px)")
          .Integer("--lamps", &O::lamps, "", Bounds::Closed(5, 64), "Lamps in the cluster (>= 5)")
          .Real("--cluster-span-m", &O::cluster_span_m, "m", Bounds::Closed(0.001, 10), "Lamp cluster diameter (m)")
          .Integer("--distractors", &O::distractors, "", Bounds::Closed(0, 50), "Bright glints in the image")
          .Real("--distractor-margin-px", &O::distractor_margin_px, "px", Bounds::AtLeast(0),
                "Glints start at least this far from the beacon (px)")
          .Real("--range-noise-mm", &O::range_noise_mm, "mm", Bounds::Closed(0, 10000), "Range noise std (mm)")
          .Real("--range-error-rate", &O::range_error_rate, "", Bounds::RightOpen(0, 1),
                "Probability of a device-error row (status 255)")
          .Real("--range-rate-hz", &O::range_rate_hz, "Hz", Bounds::LeftOpen(0, 1000), "Range log rate (Hz)")
          .Real("--range-offset-s", &O::range_offset_s, "s", Bounds::Closed(-kSampleMarginS, kSampleMarginS),
                "Range sample time offset from the frame grid (s)")
          .Real("--turret-rate-hz", &O::turret_rate_hz, "Hz", Bounds::LeftOpen(0, 10000), "Turret log rate (Hz)")
          .Real("--turret-offset-s", &O::turret_offset_s, "s", Bounds::Closed(-kSampleMarginS, kSampleMarginS),
                "Turret sample time offset from the frame grid (s)")
          .Real("--turret-noise-deg", &O::turret_resolution_deg, "deg", Bounds::Closed(0, geo::RadToDeg(0.01)),
                "Turret encoder quantisation step (deg), PTU-D48E 0.003; 0 = exact angles")
          .Real("--turret-noise-std-deg", &O::turret_noise_deg, "deg", Bounds::Closed(0, geo::RadToDeg(0.01)),
                "Extra Gaussian encoder noise std (deg)")
          .Sub(&O::servo, TurretServoOptions::Table());
  return table;
}

bool BeaconSimOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!Table().Check(*this, why)) return false;
  if (camera.width_px < 32 || camera.height_px < 32) return fail("image must be at least 32x32 px");
  if (!trajectory.Check(why) || !sensor.Check(why) || !servo.Check(why)) return false;
  if (duration_s * fps < 1.0 - 1e-9) return fail("duration x fps must give at least one frame");
  for (const auto& o : occlusions) {
    if (!(o.start_s >= 0 && o.duration_s > 0 && std::isfinite(o.start_s + o.duration_s))) {
      return fail("occlusion intervals need start >= 0 and duration > 0");
    }
  }
  for (const auto& o : servo_holds) {
    if (!(o.start_s >= 0 && o.duration_s > 0 && o.start_s + o.duration_s <= duration_s + kServoMarginS)) {
      return fail("servo holds need start >= 0, duration > 0 and must end within 1 s after the trial");
    }
  }
  const geo::PointingTerms& p = station_pointing;
  if (!(std::abs(p.az_offset_rad) <= geo::kTwoPi)) return fail("--az-offset-deg must be within ±360");
  for (double tilt : {p.tilt_north_rad, p.tilt_east_rad, p.el_axis_tilt_rad}) {
    if (!(std::abs(tilt) <= geo::DegToRad(10.0))) {
      return fail("--tilt-north-deg, --tilt-east-deg and --el-axis-tilt-deg must be within ±10");
    }
  }
  if (!(std::abs(camera.time_offset_s) <= 1.0)) return fail("--time-offset-s must be within ±1 s");
  return true;
}

io::Json BeaconSimOptions::ToJson() const {
  const io::Json sim = BeaconSimOptionsToJson(*this);
  io::Json j = Table().ToJson(*this);
  for (const char* key : {"camera_preset", "camera", "trajectory", "occlusions", "servo_holds"}) j[key] = sim[key];
  if (sim.contains("station_pointing")) j["station_pointing"] = sim["station_pointing"];
  return j;
}

io::Json BeaconSimOptionsToJson(const BeaconSimOptions& o) {
  using geo::RadToDeg;
  io::Json j;
  j["camera_preset"] = o.camera_preset;
  j["camera"] = camera::CameraModelToJson(o.camera);
  j["trajectory"] = {{"kind", TrajectoryKindName(o.trajectory.kind)},
                     {"range_m", o.trajectory.range_m},
                     {"speed_mps", o.trajectory.speed_mps},
                     {"azimuth_deg", RadToDeg(o.trajectory.azimuth_rad)},
                     {"elevation_deg", RadToDeg(o.trajectory.elevation_rad)},
                     {"max_elevation_deg", RadToDeg(o.trajectory.max_elevation_rad())},
                     {"turn_rate_deg_s", RadToDeg(o.trajectory.turn_rate_rad_s)},
                     {"t_mid_s", o.t0_s + 0.5 * o.duration_s}};
  j["duration_s"] = o.duration_s;
  j["fps"] = o.fps;
  j["t0_s"] = o.t0_s;
  j["lamps"] = o.lamps;
  j["cluster_span_m"] = o.cluster_span_m;
  j["psf_sigma_px"] = o.psf_sigma_px;
  j["peak_dn"] = o.peak_dn;
  j["background_dn"] = o.sensor.background_dn;
  j["read_noise_dn"] = o.sensor.read_noise_dn;
  j["gain_e_per_dn"] = o.sensor.gain_e_per_dn;
  j["bit_depth"] = o.sensor.bit_depth;
  j["distractors"] = o.distractors;
  j["distractor_margin_px"] = o.distractor_margin_px;
  io::Json occ = io::Json::array();
  for (const auto& x : o.occlusions) occ.push_back({{"start_s", x.start_s}, {"duration_s", x.duration_s}});
  j["occlusions"] = occ;
  io::Json holds = io::Json::array();
  for (const auto& x : o.servo_holds) holds.push_back({{"start_s", x.start_s}, {"duration_s", x.duration_s}});
  j["servo_holds"] = holds;
  j["turret_lag_s"] = o.servo.lag_s;
  j["jitter_arcsec"] = o.servo.jitter_rms_rad() * geo::kArcsecPerRad;
  j["jitter_band_hz"] = {o.servo.jitter_min_hz, o.servo.jitter_max_hz};
  j["turret_rate_hz"] = o.turret_rate_hz;
  j["turret_offset_s"] = o.turret_offset_s;
  j["turret_resolution_deg"] = RadToDeg(o.turret_resolution_rad());
  j["turret_noise_deg"] = RadToDeg(o.turret_noise_rad());
  j["range_rate_hz"] = o.range_rate_hz;
  j["range_offset_s"] = o.range_offset_s;
  j["range_noise_mm"] = o.range_noise_m() * 1e3;
  j["range_error_rate"] = o.range_error_rate;
  j["seed"] = o.seed;
  if (!o.station_pointing.IsZero()) {
    const geo::PointingTerms& p = o.station_pointing;
    j["station_pointing"] = {{"az_offset_deg", RadToDeg(p.az_offset_rad)},
                             {"tilt_north_deg", RadToDeg(p.tilt_north_rad)},
                             {"tilt_east_deg", RadToDeg(p.tilt_east_rad)},
                             {"el_axis_tilt_deg", RadToDeg(p.el_axis_tilt_rad)}};
  }
  return j;
}

BeaconSimulator::BeaconSimulator(BeaconSimOptions opt)
    : opt_(Prepared(std::move(opt))),
      trajectory_(opt_.trajectory),
      servo_(opt_.servo, [this](double t) { return TargetEnu(CommandTime(t)); }, opt_.t0_s - kServoMarginS,
             LastFrameTime(opt_) + kServoMarginS, opt_.seed) {
  // Lamp layout (a_i, b_i) and relative intensities w_i.
  lamp_unit_.push_back({0.0, 0.0});
  lamp_weight_.push_back(1.0);
  for (int i = 1; i < opt_.lamps; ++i) {
    const double ang = 0.3 + geo::kTwoPi * (i - 1) / (opt_.lamps - 1);
    lamp_unit_.push_back({std::cos(ang), std::sin(ang)});
    const double frac = 0.618034 * i - std::floor(0.618034 * i);
    lamp_weight_.push_back(1.0 - 0.3 * frac);
  }

  const std::int64_t n = FrameCount(opt_);
  const double edge = 3.0 * opt_.psf_sigma_px + 1.0;
  frames_.reserve(static_cast<std::size_t>(n));
  for (std::int64_t k = 0; k < n; ++k) {
    FrameTruth f;
    f.frame = k;
    f.t_s = opt_.t0_s + static_cast<double>(k) / opt_.fps;
    // The physical boresight follows the target; the camera's orientation there is that of the encoder
    // angles under the station's pointing model (camera/station_view.h; the servo's boresight and the
    // camera itself for a perfect station).
    const camera::StationView view = camera::ApplyPointing(opt_.camera, EncoderAngles(servo_.Boresight(f.t_s)),
                                                           opt_.station_pointing);
    const camera::CameraModel cam = camera::CameraInView(opt_.camera, view);
    const geo::AzEl bore = view.boresight;
    f.boresight_az_rad = bore.az_rad;
    f.boresight_el_rad = bore.el_rad;
    f.p_enu = TargetEnu(f.t_s);
    f.range_m = f.p_enu.norm();
    const Eigen::Vector3d los = f.p_enu / f.range_m;
    const Eigen::Vector3d right = los.cross(Eigen::Vector3d::UnitZ()).normalized();
    const Eigen::Vector3d up = right.cross(los);
    std::vector<Spot> all;
    for (std::size_t i = 0; i < lamp_unit_.size(); ++i) {
      const Eigen::Vector3d lamp =
          f.p_enu + 0.5 * opt_.cluster_span_m * (lamp_unit_[i].x() * right + lamp_unit_[i].y() * up);
      const auto px = cam.ProjectEnu(lamp.normalized(), bore.az_rad, bore.el_rad);
      if (!px || px->x() < edge || px->y() < edge || px->x() > cam.width_px - 1 - edge ||
          px->y() > cam.height_px - 1 - edge) {
        std::ostringstream ss;
        ss << "the target leaves the image at frame " << k << " (t = " << f.t_s
           << " s): the turret lags too far behind; lower --speed-mps or --turret-lag-s, or raise --range-m";
        throw UsageError(ss.str());
      }
      all.push_back(Spot{px->x(), px->y(), opt_.psf_sigma_px, opt_.peak_dn * lamp_weight_[i]});
    }
    const cv::Point2d c = FluxWeightedCentre(all);
    f.centre_px = {c.x, c.y};
    for (const Spot& s : all) f.cluster_radius_px = std::max(f.cluster_radius_px, std::hypot(s.x_px - c.x, s.y_px - c.y));
    const geo::AzEl ae = geo::AzElFromEnu(cam.RayEnu(f.centre_px, bore.az_rad, bore.el_rad));
    f.az_rad = ae.az_rad;
    f.el_rad = ae.el_rad;
    f.visible = !Occluded(f.t_s);
    if (f.visible) f.lamps = std::move(all);
    frames_.push_back(std::move(f));
  }
  PlaceDistractors();
}

geo::AzEl BeaconSimulator::EncoderAngles(const geo::AzEl& boresight) const {
  const geo::PointingTerms& p = opt_.station_pointing;
  if (p.IsZero()) return boresight;
  // Solve b(A, E) = target boresight for (A, E): Newton on the boresight's az/el, numerical Jacobian. The
  // terms are small rotations, so it converges from (A − az_offset, E) in a few steps to rounding.
  const auto bore = [&](double a, double e) { return geo::AzElFromEnu(geo::RotationEnuFromTurret(a, e, p).col(2)); };
  const auto residual = [&](double a, double e) {
    const geo::AzEl b = bore(a, e);
    return Eigen::Vector2d(geo::WrapPi(b.az_rad - boresight.az_rad), b.el_rad - boresight.el_rad);
  };
  Eigen::Vector2d x(boresight.az_rad - p.az_offset_rad, boresight.el_rad);
  constexpr double kStep = 1e-7;
  for (int it = 0; it < 20; ++it) {
    const Eigen::Vector2d r = residual(x(0), x(1));
    if (r.norm() < 1e-15) break;
    Eigen::Matrix2d J;
    J.col(0) = (residual(x(0) + kStep, x(1)) - r) / kStep;
    J.col(1) = (residual(x(0), x(1) + kStep) - r) / kStep;
    x -= J.partialPivLu().solve(r);
  }
  return {geo::WrapTwoPi(x(0)), x(1)};
}

bool BeaconSimulator::Occluded(double t_s) const {
  const double rel = t_s - opt_.t0_s;
  for (const auto& o : opt_.occlusions) {
    if (rel >= o.start_s - 1e-9 && rel < o.start_s + o.duration_s - 1e-9) return true;
  }
  return false;
}

double BeaconSimulator::CommandTime(double t_s) const {
  const double rel = t_s - opt_.t0_s;
  for (const auto& h : opt_.servo_holds) {
    if (rel >= h.start_s && rel < h.start_s + h.duration_s) return opt_.t0_s + h.start_s;
  }
  return t_s;
}

void BeaconSimulator::PlaceDistractors() {
  if (opt_.distractors == 0 || frames_.empty()) return;
  std::mt19937_64 rng = RandomStream(opt_.seed, 3);
  const double w = opt_.camera.width_px, h = opt_.camera.height_px;
  std::uniform_real_distribution<double> ux(kGlintEdgePx, w - 1 - kGlintEdgePx), uy(kGlintEdgePx, h - 1 - kGlintEdgePx);
  std::uniform_real_distribution<double> speed(3.0, 15.0), dir(0.0, geo::kTwoPi), amp(0.5, 1.5);
  auto position = [&](const Glint& g, double dt) {
    return Eigen::Vector2d(Fold(g.p0_px.x() + g.v_pxps.x() * dt, kGlintEdgePx, w - 1 - kGlintEdgePx),
                           Fold(g.p0_px.y() + g.v_pxps.y() * dt, kGlintEdgePx, h - 1 - kGlintEdgePx));
  };
  for (int i = 0; i < opt_.distractors; ++i) {
    bool placed = false;
    for (int attempt = 0; attempt < 5000 && !placed; ++attempt) {
      Glint g;
      g.p0_px = {ux(rng), uy(rng)};
      const double v = (i % 2 == 0) ? speed(rng) : 0.0;  // even glints drift, odd ones are fixed
      const double a = dir(rng);
      g.v_pxps = {v * std::cos(a), v * std::sin(a)};
      g.amplitude_dn = opt_.peak_dn * amp(rng);
      g.sigma_px = kGlintSigmaPx;
      if ((g.p0_px - frames_[0].centre_px).norm() < opt_.distractor_margin_px) continue;
      placed = true;
      for (const FrameTruth& f : frames_) {
        const Eigen::Vector2d p = position(g, f.t_s - opt_.t0_s);
        if ((p - f.centre_px).norm() < f.cluster_radius_px + kGlintClearancePx + 3 * opt_.psf_sigma_px) {
          placed = false;
          break;
        }
      }
      if (placed) glints_.push_back(g);
    }
    if (!placed) {
      throw UsageError("cannot place " + std::to_string(opt_.distractors) +
                       " distractors away from the beacon; use fewer, a smaller --distractor-margin-px or a larger image");
    }
  }
  for (FrameTruth& f : frames_) {
    double dmin = -1.0;
    for (const Glint& g : glints_) {
      const Eigen::Vector2d p = position(g, f.t_s - opt_.t0_s);
      f.distractors.push_back(Spot{p.x(), p.y(), g.sigma_px, g.amplitude_dn});
      const double d = (p - f.centre_px).norm();
      dmin = dmin < 0 ? d : std::min(dmin, d);
    }
    f.distractor_min_dist_px = dmin;
  }
}

cv::Mat BeaconSimulator::RenderSignal(std::size_t k) const {
  const FrameTruth& f = frames_.at(k);
  cv::Mat signal = cv::Mat::zeros(opt_.camera.height_px, opt_.camera.width_px, CV_32FC1);
  AddSpots(&signal, f.lamps);
  AddSpots(&signal, f.distractors);
  return signal;
}

cv::Mat BeaconSimulator::RenderFrame(std::size_t k, std::mt19937_64& rng) const {
  cv::Mat signal = RenderSignal(k);
  SensorOptions s = opt_.sensor;
  if (s.bit_depth == 16) {
    // Same electrons, DN ×256: full scale 65535 ≈ 8-bit 256.
    constexpr double kScale = 256.0;
    signal *= kScale;
    s.background_dn *= kScale;
    s.read_noise_dn *= kScale;
    s.gain_e_per_dn /= kScale;
  }
  return Digitise(signal, s, rng);
}

cv::Mat BeaconSimulator::RenderFrame(std::size_t k) const {
  std::mt19937_64 rng = RandomStream(opt_.seed, 1000, k);
  return RenderFrame(k, rng);
}

std::vector<TurretSample> BeaconSimulator::TurretLog() const {
  std::mt19937_64 rng = RandomStream(opt_.seed, 4);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double q = opt_.turret_resolution_rad();
  auto record = [&](double v) {
    if (opt_.turret_noise_rad() > 0) v += opt_.turret_noise_rad() * normal(rng);
    if (q > 0) v = q * std::round(v / q);
    return v;
  };
  std::vector<TurretSample> out;
  for (double t : SampleTimes(opt_, opt_.turret_rate_hz, opt_.turret_offset_s)) {
    TurretSample s;
    s.t_s = t;
    const geo::AzEl b = EncoderAngles(servo_.Boresight(t));
    s.true_az_rad = b.az_rad;
    s.true_el_rad = b.el_rad;
    s.az_rad = geo::WrapTwoPi(record(b.az_rad));
    s.el_rad = record(b.el_rad);
    out.push_back(s);
  }
  return out;
}

std::vector<RangeSample> BeaconSimulator::RangeLog() const {
  std::mt19937_64 rng = RandomStream(opt_.seed, 5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<RangeSample> out;
  for (double t : SampleTimes(opt_, opt_.range_rate_hz, opt_.range_offset_s)) {
    RangeSample s;
    s.t_s = t;
    s.true_range_m = TargetEnu(t).norm();
    const double noise = opt_.range_noise_m() * normal(rng);  // drawn every row: error rows do not shift the stream
    if (uniform(rng) < opt_.range_error_rate) {
      s.range_m = std::nan("");
      s.status = 255;
    } else {
      s.range_m = s.true_range_m + noise;
      s.status = 0;
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace rk::sim

// Calibration-session simulator; model in pointing_scenario.h.
#include "sim/pointing_scenario.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "geo/angles.h"
#include "io/error.h"
#include "geo/line_of_sight.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace {

constexpr double kImageMarginPx = 10.0;      // observations only this far inside the image
constexpr double kMaxImageOffset = 0.4;      // dwell aim: target within 40 % of the half field of the centre
constexpr double kStarGridS = 10.0;          // stars' directions tabulated this often (linear error < 0.02″)
constexpr double kMinSlewS = 0.5;            // shortest slew
constexpr std::uint64_t kStreamTargets = 1, kStreamAim = 2, kStreamNoise = 3;

// One piece of the commanded turret motion: a cosine (S-curve) move from (a0, e0) to (a1, e1) over
// [t0, t1]; a dwell is a move with equal ends. Peak rate = |Δ| π / (2 (t1 − t0)).
struct Move {
  double t0, t1, a0, e0, a1, e1;  // radians (azimuth unwrapped)
};

class TurretCommand {
 public:
  void Add(const Move& m) { moves_.push_back(m); }
  double end() const { return moves_.empty() ? 0.0 : moves_.back().t1; }
  Eigen::Vector2d last() const { return moves_.empty() ? Eigen::Vector2d::Zero() : Eigen::Vector2d(moves_.back().a1, moves_.back().e1); }
  // Commanded (A, E) at t (clamped to the first and last move).
  Eigen::Vector2d At(double t) const {
    auto it = std::lower_bound(moves_.begin(), moves_.end(), t, [](const Move& m, double v) { return m.t1 < v; });
    if (it == moves_.end()) return last();
    const double s = std::clamp((t - it->t0) / (it->t1 - it->t0), 0.0, 1.0);
    const double w = 0.5 * (1.0 - std::cos(geo::kPi * s));
    return {it->a0 + w * (it->a1 - it->a0), it->e0 + w * (it->e1 - it->e0)};
  }

 private:
  std::vector<Move> moves_;
};

// A target of the session: a landmark (constant direction) or a star (tabulated direction).
struct SimTarget {
  std::string id;
  bool star = false;
  double az0 = 0.0;                                // azimuth at the epoch (visiting order)
  Eigen::Vector3d dir = Eigen::Vector3d::UnitY();  // landmark
  std::vector<Eigen::Vector3d> table;              // star, every kStarGridS from t = 0
  Eigen::Vector3d At(double t) const {
    if (!star) return dir;
    const double u = std::clamp(t / kStarGridS, 0.0, static_cast<double>(table.size() - 1) - 1e-9);
    const std::size_t k = static_cast<std::size_t>(u);
    return (table[k] + (u - static_cast<double>(k)) * (table[k + 1] - table[k])).normalized();
  }
};

double Uniform(std::mt19937_64& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

void MakePointingTargets(const PointingSimOptions& o, PointingSession* s, std::vector<SimTarget>* targets) {
  std::mt19937_64 rng = RandomStream(o.seed, kStreamTargets);
  const target::Atmosphere atm;
  for (int i = 0; i < o.landmarks; ++i) {
    const double az = Uniform(rng, 0, geo::kTwoPi);
    const double el = geo::DegToRad(Uniform(rng, o.landmark_min_el_deg, o.landmark_max_el_deg));
    const double range = Uniform(rng, 500.0, 3000.0);
    target::Landmark l;
    l.id = "L" + std::to_string(i + 1);
    l.p_enu = range * target::DirectionEnu(az, el);
    s->landmarks.push_back(l);
    targets->push_back({l.id, false, az, l.p_enu.normalized(), {}});
  }
  for (int i = 0; i < o.stars; ++i) {
    const target::ObservedPlace p{Uniform(rng, 0, geo::kTwoPi),
                                  geo::DegToRad(Uniform(rng, o.star_min_el_deg, o.star_max_el_deg))};
    s->stars.push_back(target::StarFromObservedPlace("S" + std::to_string(i + 1), p, s->station, s->epoch, 0.0, atm));
    targets->push_back({s->stars.back().id, true, p.az_rad, {}, {}});
  }
  // Landmarks round the horizon, then the stars round the sky: short slews.
  std::stable_sort(targets->begin(), targets->end(), [](const SimTarget& a, const SimTarget& b) {
    return a.star != b.star ? b.star : a.az0 < b.az0;
  });
}

// Tabulates the stars' directions over [0, duration].
void TabulateStars(const PointingSession& s, double duration, std::vector<SimTarget>* targets) {
  const target::Atmosphere atm;
  const int n = static_cast<int>(std::ceil(duration / kStarGridS)) + 2;
  for (SimTarget& t : *targets) {
    if (!t.star) continue;
    const auto it = std::find_if(s.stars.begin(), s.stars.end(), [&](const target::Star& st) { return st.id == t.id; });
    t.table.clear();
    for (int k = 0; k < n; ++k) {
      const target::ObservedPlace p = target::StarObservedPlace(*it, s.station, s.epoch.Plus(k * kStarGridS), 0.0, atm);
      t.table.push_back(target::DirectionEnu(p.az_rad, p.el_rad));
    }
  }
}

// The commanded angles that put direction d at a random image offset (approximately: the pointing terms
// are small against the field).
Eigen::Vector2d Aim(const PointingSimOptions& o, const Eigen::Vector3d& d, double half_fov, std::mt19937_64& rng) {
  const double az = std::atan2(d.x(), d.y()), el = std::asin(std::clamp(d.z(), -1.0, 1.0));
  const double ox = Uniform(rng, -kMaxImageOffset, kMaxImageOffset) * half_fov;
  const double oy = Uniform(rng, -kMaxImageOffset, kMaxImageOffset) * half_fov;
  return {az - geo::DegToRad(o.az_offset_deg) + ox / std::cos(el), el + oy};
}

TurretCommand Schedule(const PointingSimOptions& o, const std::vector<SimTarget>& targets, double half_fov,
                       PointingSession* s) {
  std::mt19937_64 rng = RandomStream(o.seed, kStreamAim);
  TurretCommand cmd;
  const double rate = geo::DegToRad(o.slew_rate_deg_s);
  double now = kSampleMarginS;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    Eigen::Vector2d aim = Aim(o, targets[i].At(now), half_fov, rng);
    if (i > 0) {
      const Eigen::Vector2d from = cmd.last();
      aim.x() = from.x() + geo::WrapPi(aim.x() - from.x());
      const double span = (aim - from).cwiseAbs().maxCoeff();
      const double T = std::max(kMinSlewS, span * geo::kPi / (2.0 * rate));
      cmd.Add({now, now + T, from.x(), from.y(), aim.x(), aim.y()});
      now += T;
    }
    cmd.Add({now, now + o.dwell_s, aim.x(), aim.y(), aim.x(), aim.y()});
    now += o.dwell_s;
    ++s->dwells;
  }
  return cmd;
}

void LogTurret(const PointingSimOptions& o, const TurretCommand& cmd, double end, PointingSession* s) {
  const double step = o.encoder_step_deg;
  auto quantise = [step](double v) { return step > 0 ? std::round(v / step) * step : v; };
  const auto n = static_cast<std::size_t>(std::floor(end * o.turret_rate_hz)) + 1;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / o.turret_rate_hz;
    const Eigen::Vector2d c = cmd.At(t);
    s->turret_t_s.push_back(t);
    s->turret_az_deg.push_back(geo::WrapDeg360(quantise(geo::WrapDeg360(geo::RadToDeg(c.x())))));
    s->turret_el_deg.push_back(quantise(geo::RadToDeg(c.y())));
  }
}

void Observe(const PointingSimOptions& o, const TurretCommand& cmd, const std::vector<SimTarget>& targets,
             double first, double last, PointingSession* s) {
  std::mt19937_64 rng = RandomStream(o.seed, kStreamNoise);
  std::normal_distribution<double> noise(0.0, o.centroid_sigma_px);
  const camera::CameraModel& cam = s->camera_truth;
  const Eigen::Matrix3d R_turret_cam = cam.RotationTurretFromCamera();
  std::int64_t frame = 0;
  for (double t = first; t <= last; t = first + static_cast<double>(++frame) / o.frame_rate_hz) {
    const double t_true = t + o.time_offset_s;
    const Eigen::Vector2d c = cmd.At(t_true);
    const Eigen::Matrix3d R_enu_cam = geo::RotationEnuFromTurret(c.x(), c.y(), s->truth) * R_turret_cam;
    for (const SimTarget& tg : targets) {
      const Eigen::Vector3d v = R_enu_cam.transpose() * tg.At(t_true);
      if (v.z() <= 0.0) continue;
      const auto px = cam.Project(v);
      if (!px || px->x() < kImageMarginPx || px->y() < kImageMarginPx || px->x() > cam.width_px - 1 - kImageMarginPx ||
          px->y() > cam.height_px - 1 - kImageMarginPx) {
        continue;
      }
      PointingObservationRow r;
      r.frame = frame;
      r.t_s = t;
      r.id = tg.id;
      r.truth_px = *px;
      r.px = *px + Eigen::Vector2d(noise(rng), noise(rng));
      s->observations.push_back(r);
    }
  }
  s->frames = static_cast<std::size_t>(frame);
}

// The validation target: straight flight 3 km out at 60 m/s crossing from azimuth 200° upward, turret
// commanded at its true direction (minus az_offset), logged quantised; 20 Hz frames.
constexpr double kValidationRateHz = 20.0, kValidationRangeM = 3000.0, kValidationSpeedMps = 60.0;
constexpr std::uint64_t kStreamValidation = 4;

Eigen::Vector3d ValidationPosition(double t) {
  const Eigen::Vector3d p0 = kValidationRangeM * target::DirectionEnu(geo::DegToRad(200.0), geo::DegToRad(15.0));
  const Eigen::Vector3d v = kValidationSpeedMps * Eigen::Vector3d(0.8, -0.3, 0.52).normalized();
  return p0 + v * t;
}

void SimulateValidation(const PointingSimOptions& o, PointingSession* s) {
  if (!(o.validation_s > 0.0)) return;
  ValidationTrack& v = s->validation;
  auto command = [&](double t) {
    const geo::AzEl d = geo::AzElFromEnu(ValidationPosition(t));
    return Eigen::Vector2d(d.az_rad - s->truth.az_offset_rad, d.el_rad);
  };
  const double step = o.encoder_step_deg;
  auto quantise = [step](double x) { return step > 0 ? std::round(x / step) * step : x; };
  for (double t = 0.0; t <= o.validation_s + 2 * kSampleMarginS + 1e-9; t += 1.0 / o.turret_rate_hz) {
    const Eigen::Vector2d c = command(t);
    v.turret_t_s.push_back(t);
    v.turret_az_deg.push_back(geo::WrapDeg360(quantise(geo::WrapDeg360(geo::RadToDeg(c.x())))));
    v.turret_el_deg.push_back(quantise(geo::RadToDeg(c.y())));
  }
  std::mt19937_64 rng = RandomStream(o.seed, kStreamValidation);
  std::normal_distribution<double> noise(0.0, o.centroid_sigma_px);
  const camera::CameraModel& cam = s->camera_truth;
  for (double t = kSampleMarginS; t <= o.validation_s + kSampleMarginS; t += 1.0 / kValidationRateHz) {
    const double t_true = t + o.time_offset_s;
    const Eigen::Vector2d c = command(t_true);
    const Eigen::Matrix3d R_enu_cam = geo::RotationEnuFromTurret(c.x(), c.y(), s->truth) * cam.RotationTurretFromCamera();
    const Eigen::Vector3d p = ValidationPosition(t_true);
    const auto px = cam.Project(R_enu_cam.transpose() * p.normalized());
    if (!px) continue;
    v.frame_t_s.push_back(t);
    v.px.push_back(*px + Eigen::Vector2d(noise(rng), noise(rng)));
    v.p_enu.push_back(p);
    v.true_t_s.push_back(t_true);
  }
}

}  // namespace

const io::OptionTable<PointingSimOptions>& PointingSimOptions::Table() {
  using O = PointingSimOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Count("--seed", &O::seed, "", io::Bounds::Any(), "Random seed")
          .Integer("--landmarks", &O::landmarks, "", io::Bounds::Closed(0, 1000), "Number of landmarks")
          .Integer("--stars", &O::stars, "", io::Bounds::Closed(0, 1000), "Number of stars")
          .Real("--landmark-min-el", &O::landmark_min_el_deg, "deg", io::Bounds::Closed(-5, 85), "Lowest landmark elevation (deg)")
          .Real("--landmark-max-el", &O::landmark_max_el_deg, "deg", io::Bounds::Closed(-5, 85), "Highest landmark elevation (deg)")
          .Real("--star-min-el", &O::star_min_el_deg, "deg", io::Bounds::Closed(5, 85), "Lowest star elevation at the epoch (deg)")
          .Real("--star-max-el", &O::star_max_el_deg, "deg", io::Bounds::Closed(5, 85), "Highest star elevation at the epoch (deg)")
          .Real("--focal-mm", &O::focal_length_mm, "mm", io::Bounds::Positive().Finite(), "Nominal focal length (mm)")
          .Real("--encoder-step-deg", &O::encoder_step_deg, "deg", io::Bounds::AtLeast(0).Finite(), "Turret encoder quantum (deg); 0 = exact log")
          .Real("--centroid-sigma-px", &O::centroid_sigma_px, "px", io::Bounds::AtLeast(0).Finite(), "Image point noise 1-sigma (px)")
          .Real("--dwell", &O::dwell_s, "s", io::Bounds::Positive().Finite(), "Dwell on each target (s)")
          .Real("--slew-rate", &O::slew_rate_deg_s, "deg/s", io::Bounds::Positive().Finite(), "Peak slew rate (deg/s)")
          .Real("--fps", &O::frame_rate_hz, "Hz", io::Bounds::Positive().Finite(), "Frame rate (Hz)")
          .Real("--turret-rate", &O::turret_rate_hz, "Hz", io::Bounds::Positive().Finite(), "Turret log rate (Hz)")
          .Real("--az-offset-deg", &O::az_offset_deg, "deg", io::Bounds::Closed(-360, 360), "True azimuth offset (deg)")
          .Real("--tilt-north-deg", &O::tilt_north_deg, "deg", io::Bounds::Closed(-1, 1), "True tilt toward north (deg)")
          .Real("--tilt-east-deg", &O::tilt_east_deg, "deg", io::Bounds::Closed(-1, 1), "True tilt toward east (deg)")
          .Real("--el-axis-tilt-deg", &O::el_axis_tilt_deg, "deg", io::Bounds::Closed(-1, 1), "True elevation-axis tilt (deg)")
          .Real("--mount-yaw-deg", &O::mount_yaw_deg, "deg", io::Bounds::Closed(-2, 2), "True camera mount yaw (deg)")
          .Real("--mount-pitch-deg", &O::mount_pitch_deg, "deg", io::Bounds::Closed(-2, 2), "True camera mount pitch (deg)")
          .Real("--mount-roll-deg", &O::mount_roll_deg, "deg", io::Bounds::Closed(-5, 5), "True camera mount roll (deg)")
          .Real("--focal-error", &O::focal_error, "", io::Bounds::Closed(-0.05, 0.05), "True focal length / nominal - 1")
          .Real("--time-offset", &O::time_offset_s, "s", io::Bounds::Closed(-1, 1), "True camera time offset (s)")
          .Real("--validation", &O::validation_s, "s", io::Bounds::Closed(0, 3600),
                "Length of the tracked validation target (s); 0 = none");
  return table;
}

bool PointingSimOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (landmarks + stars < 3) return *why = "--landmarks + --stars must be >= 3", false;
  if (landmark_min_el_deg > landmark_max_el_deg || star_min_el_deg > star_max_el_deg) {
    return *why = "each --*-min-el must be <= its --*-max-el", false;
  }
  return true;
}

io::Json PointingSimOptions::ToJson() const {
  io::Json j = Table().ToJson(*this);
  j["epoch_utc"] = epoch_utc;
  j["station"] = {lat_deg, lon_deg, h_m};
  return j;
}

PointingSession SimulatePointingSession(const PointingSimOptions& o) {
  std::string why;
  if (!o.Check(&why)) throw UsageError(why);
  PointingSession s;
  s.station = {o.lat_deg, o.lon_deg, o.h_m};
  s.epoch = target::ParseUtc(o.epoch_utc, "epoch");
  s.camera_nominal.width_px = o.width_px;
  s.camera_nominal.height_px = o.height_px;
  s.camera_nominal.pixel_size_mm = {o.pixel_size_mm, o.pixel_size_mm};
  s.camera_nominal.focal_length_mm = o.focal_length_mm;
  s.camera_nominal.principal_point_px = {(o.width_px - 1) / 2.0, (o.height_px - 1) / 2.0};
  s.camera_truth = s.camera_nominal;
  s.camera_truth.focal_length_mm *= 1.0 + o.focal_error;
  s.camera_truth.mount_yaw_rad = geo::DegToRad(o.mount_yaw_deg);
  s.camera_truth.mount_pitch_rad = geo::DegToRad(o.mount_pitch_deg);
  s.camera_truth.mount_roll_rad = geo::DegToRad(o.mount_roll_deg);
  s.camera_truth.time_offset_s = o.time_offset_s;
  s.truth = {geo::DegToRad(o.az_offset_deg), geo::DegToRad(o.tilt_north_deg), geo::DegToRad(o.tilt_east_deg),
             geo::DegToRad(o.el_axis_tilt_deg)};
  std::vector<SimTarget> targets;
  MakePointingTargets(o, &s, &targets);
  const double half_fov = std::atan(0.5 * o.width_px * o.pixel_size_mm / o.focal_length_mm);
  // Star directions for aiming: tabulated over a generous bound of the session, then again exactly.
  double bound = kSampleMarginS + static_cast<double>(targets.size()) * (o.dwell_s + 40.0 / o.slew_rate_deg_s);
  TabulateStars(s, bound, &targets);
  TurretCommand cmd = Schedule(o, targets, half_fov, &s);
  if (cmd.end() + kSampleMarginS > bound) {  // a long session: tabulate far enough and schedule again
    bound = cmd.end() + 2 * kSampleMarginS;
    TabulateStars(s, bound, &targets);
    s.dwells = 0;
    cmd = Schedule(o, targets, half_fov, &s);
  }
  const double end = cmd.end() + kSampleMarginS;
  s.duration_s = end;
  LogTurret(o, cmd, end, &s);
  Observe(o, cmd, targets, kSampleMarginS, cmd.end() - std::abs(o.time_offset_s), &s);
  SimulateValidation(o, &s);
  return s;
}

}  // namespace rk::sim

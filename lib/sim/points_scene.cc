// The points scene: options, motion, markers, clouds, the look-alike and the truth (sim/points_scene.h).
#include "sim/points_scene.h"

#include <algorithm>
#include <cmath>

#include "io/error.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace points_detail {

constexpr double kDeg = M_PI / 180.0;
// Reversal: the motion's normalised time of reversal, its smoothing time and the half-width of q2's hide.
constexpr double kReversalU = 0.5, kReversalTauU = 0.03, kHideHalfU = 0.17;
constexpr double kReversalSpeedPx = 330.0;  // translation speed before the reversal (body px per run)
constexpr double kLookalikeSidePx = 3.0;    // the look-alike's offset beside q2's predicted path (body px)

// log(cosh(x)) without overflow.
double LogCosh(double x) {
  const double a = std::abs(x);
  return a + std::log1p(std::exp(-2.0 * a)) - std::log(2.0);
}

// ∫_0^u tanh((ur - u') / tau) du' / (ur - tau ln 2): the reversal's normalised excursion (1 at the reversal).
double ReversalProfile(double u) {
  const double peak = kReversalTauU * LogCosh(kReversalU / kReversalTauU);
  return kReversalTauU * (LogCosh(kReversalU / kReversalTauU) - LogCosh((kReversalU - u) / kReversalTauU)) / peak;
}

}  // namespace points_detail

std::string PointsScenarioName(PointsScenario s) {
  switch (s) {
    case PointsScenario::kStatic:
      return "static";
    case PointsScenario::kMoving:
      return "moving";
    case PointsScenario::kReversal:
      return "reversal";
    case PointsScenario::kLookalike:
      return "lookalike";
  }
  return "?";
}

const io::OptionTable<PointsSceneOptions>& PointsSceneOptions::Table() {
  using O = PointsSceneOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Choice("--scenario", &O::scenario,
                  {{PointsScenario::kStatic, "static"},
                   {PointsScenario::kMoving, "moving"},
                   {PointsScenario::kReversal, "reversal"},
                   {PointsScenario::kLookalike, "lookalike"}},
                  "static, moving (translate, rotate, grow), reversal (reverses while q2 is hidden), lookalike")
          .Integer("--frames", &O::frames, "", io::Bounds::Closed(2, 100000), "Number of frames")
          .Integer("--width", &O::width, "px", io::Bounds::Closed(128, 2448), "Frame width (px)")
          .Integer("--height", &O::height, "px", io::Bounds::Closed(128, 2048), "Frame height (px)")
          .Real("--fps", &O::fps, "Hz", io::Bounds::LeftOpen(0.0, 1e6), "Frame rate (Hz)")
          .Choice("--bits", &O::bits, {{8, "8"}, {16, "16"}}, "8 (FFV1 video.mkv) or 16 (12-bit DN, video/%06d.png)")
          .Real("--psf-sigma", &O::psf_sigma_px, "px", io::Bounds::Closed(0.3, 5.0), "Gaussian PSF std (px)")
          .Real("--exposure", &O::exposure_s, "s", io::Bounds::Closed(0.0, 1.0),
                "Exposure for motion blur (s), at most 1/fps; 0 = none")
          .Integer("--blur-steps", &O::blur_steps, "", io::Bounds::Closed(0, 64),
                   "Renders averaged over the exposure; 0 = auto (<= 0.25 px motion between them)")
          .Integer("--supersample", &O::supersample, "", io::Bounds::Closed(0, 16),
                   "n x n samples per pixel; 0 = auto (max(2, ceil(1.6 / psf-sigma)))")
          .Real("--read-noise-dn", &O::read_noise_dn, "DN", io::Bounds::Closed(0.0, 100.0), "Read noise std (8-bit DN)")
          .Real("--gain-e-per-dn", &O::gain_e_per_dn, "e-/DN", io::Bounds::Closed(0.0, 1e6),
                "Photo-electrons per 8-bit DN (shot noise); 0 = none")
          .Real("--scale", &O::scale, "", io::Bounds::Closed(0.5, 4.0), "Target and marker size multiplier")
          .Count("--seed", &O::seed, "", io::Bounds::Any(), "Random seed (textures, noise)");
  return table;
}

bool PointsSceneOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (bits != 8 && bits != 16) {
    if (why) *why = "--bits must be 8 or 16";
    return false;
  }
  if (exposure_s > 1.0 / fps) {
    if (why) *why = "--exposure must be at most one frame interval (1/fps s)";
    return false;
  }
  return true;
}

io::Json PointsSceneOptions::ToJson() const {
  io::Json j = Table().ToJson(*this);
  j["clouds"] = clouds;
  return j;
}

int PointsSceneOptions::SupersampleN() const {
  if (supersample > 0) return supersample;
  return std::max(2, static_cast<int>(std::ceil(1.6 / psf_sigma_px)));
}

Eigen::Vector2d PointsSimulator::Pose::Apply(const Eigen::Vector2d& body) const {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  return centre_px + scale * Eigen::Vector2d(c * body.x() - s * body.y(), s * body.x() + c * body.y());
}

double PointsSimulator::Cloud::Opacity(const Eigen::Vector2d& p, double t_s) const {
  const double d = (p - centre_px - velocity_px_s * t_s).norm();
  if (d <= core_px) return 1.0;
  if (d >= core_px + edge_px) return 0.0;
  const double x = (d - core_px) / edge_px;
  return 1.0 - x * x * (3.0 - 2.0 * x);
}

PointsSimulator::PointsSimulator(PointsSceneOptions opt) : opt_(std::move(opt)) {
  std::string why;
  if (!opt_.Check(&why)) throw UsageError(why);
  BuildMarkers();
  if (opt_.clouds) BuildClouds();
  if (opt_.scenario == PointsScenario::kLookalike) BuildLookalike();
}

double PointsSimulator::MotionU(double t_s) const { return t_s * opt_.fps / (opt_.frames - 1); }

PointsSimulator::Pose PointsSimulator::PoseAt(double t_s) const {
  using namespace points_detail;
  const double u = MotionU(t_s);
  const double w = opt_.width, h = opt_.height;
  Pose p;
  switch (opt_.scenario) {
    case PointsScenario::kStatic:
      p.centre_px = {0.5 * w + 0.37, 0.5 * h - 0.21};
      p.theta_rad = 7.0 * kDeg;
      p.scale = opt_.scale;
      break;
    case PointsScenario::kMoving:
      p.centre_px = {0.38 * w + 0.24 * w * u, 0.45 * h + 0.08 * h * u};
      p.theta_rad = (6.0 + 20.0 * u) * kDeg;
      p.scale = opt_.scale * (1.0 + 0.3 * u);
      break;
    case PointsScenario::kReversal:
    case PointsScenario::kLookalike: {
      const double heading = 8.0 * kDeg;
      const double excursion = kReversalSpeedPx * opt_.scale * (kReversalU - kReversalTauU * std::log(2.0));
      const double along = excursion * ReversalProfile(u);
      const Eigen::Vector2d e(std::cos(heading), std::sin(heading));
      p.centre_px = Eigen::Vector2d(0.5 * w - 0.6 * excursion, 0.5 * h) + along * e;
      p.theta_rad = heading + 4.0 * kDeg * ReversalProfile(u);
      p.scale = opt_.scale * (1.0 + 0.15 * u);
      break;
    }
  }
  return p;
}

void PointsSimulator::BuildMarkers() {
  const auto add = [this](std::string id, std::string method, double x, double y, double half, double support) {
    Marker m;
    m.id = std::move(id), m.method = std::move(method), m.body = {x, y}, m.half_px = half, m.support_px = support;
    markers_.push_back(std::move(m));
  };
  add("q1", "quadrant", -60, 0, 8, 8 * M_SQRT2);
  add("q2", "quadrant", 85, 0, 8, 8 * M_SQRT2);
  add("c1", "circle", -12, -60, 8, 8);
  add("b1", "centroid-bright", -12, 60, 1.5, 6);
  add("d1", "centroid-dark", 60, -70, 6, 6);
  add("t1", "correlation", 0, 0, 11, 11 * M_SQRT2);
  add("t2", "correlation", -100, 0, 11, 11 * M_SQRT2);
  // Textures: 24 sinusoids each, wavelengths 3.5..10 body px, random directions and phases, 28 DN std.
  std::mt19937_64 rng = RandomStream(opt_.seed, kPointsSceneStream);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr int kWaves = 24;
  for (Marker& m : markers_) {
    if (m.method != "correlation") continue;
    for (int i = 0; i < kWaves; ++i) {
      const double lambda = 3.5 + 6.5 * unit(rng), dir = 2.0 * M_PI * unit(rng), phase = 2.0 * M_PI * unit(rng);
      const double k = 2.0 * M_PI / lambda;
      m.waves.emplace_back(k * std::cos(dir), k * std::sin(dir), phase, 28.0 * std::sqrt(2.0 / kWaves));
    }
  }
}

Eigen::Vector2d PointsSimulator::MarkerAt(const Marker& m, double t_s) const { return PoseAt(t_s).Apply(m.body); }

// kMoving: a cloud drifting across c1, which hides it fully for 12 % of the run around its middle.
// kReversal, kLookalike: a cloud standing where q2 reverses, hiding it from 0.1 of the run before the
// reversal to 0.1 after (its core holds q2's whole excursion in that time).
void PointsSimulator::BuildClouds() {
  using namespace points_detail;
  const double run_s = (opt_.frames - 1) / opt_.fps;
  const auto find = [this](const std::string& id) -> const Marker& {
    return *std::find_if(markers_.begin(), markers_.end(), [&](const Marker& m) { return m.id == id; });
  };
  const double blur_px = 3.0 * opt_.psf_sigma_px;
  if (opt_.scenario == PointsScenario::kMoving) {
    const Marker& c1 = find("c1");
    const double um = 0.5, half_u = 0.06, margin = 16.0 * opt_.scale;
    const double tm = um * run_s, dt = 1e-3 * run_s;
    const Eigen::Vector2d pm = MarkerAt(c1, tm);
    const Eigen::Vector2d vm = (MarkerAt(c1, tm + dt) - MarkerAt(c1, tm - dt)) / (2 * dt);
    const Eigen::Vector2d across = Eigen::Vector2d(0.6, -0.8) * (margin / (half_u * run_s));
    Cloud c;
    c.velocity_px_s = vm - across;
    c.centre_px = pm - c.velocity_px_s * tm;
    c.core_px = c1.support_px * opt_.scale * 1.3 + blur_px + margin;
    c.edge_px = 10.0 * opt_.scale;
    clouds_.push_back(c);
  } else if (opt_.scenario == PointsScenario::kReversal || opt_.scenario == PointsScenario::kLookalike) {
    const Marker& q2 = find("q2");
    const double th = (kReversalU - kHideHalfU) * run_s, te = (kReversalU + kHideHalfU) * run_s;
    const Eigen::Vector2d entry = MarkerAt(q2, th);
    const Eigen::Vector2d dir = (MarkerAt(q2, th + 1e-3 * run_s) - entry).normalized();
    double deepest = 0;
    for (int i = 0; i <= 200; ++i) deepest = std::max(deepest, (MarkerAt(q2, th + (te - th) * i / 200.0) - entry).dot(dir));
    Cloud c;
    c.centre_px = entry + 0.5 * deepest * dir;
    double reach = 0;
    for (int i = 0; i <= 200; ++i) reach = std::max(reach, (MarkerAt(q2, th + (te - th) * i / 200.0) - c.centre_px).norm());
    c.core_px = reach + q2.support_px * opt_.scale * 1.15 + blur_px + 1.0;
    c.edge_px = 8.0 * opt_.scale;
    clouds_.push_back(c);
  }
}

PointsSimulator::Cover PointsSimulator::Occlusion(const Eigen::Vector2d& p, double radius_px, double t_s) const {
  // Over a disc: the largest and smallest opacity at its points nearest to and farthest from each cloud's
  // centre (opacity falls with the distance), the mean by 6 equal-area rings of 16 points.
  constexpr int kRings = 6, kSpokes = 16;
  Cover cover;
  std::vector<double> clear(kRings * kSpokes, 1.0);
  for (const Cloud& c : clouds_) {
    const double d = (p - c.centre_px - c.velocity_px_s * t_s).norm();
    const Eigen::Vector2d centre = c.centre_px + c.velocity_px_s * t_s;
    cover.max = std::max(cover.max, c.Opacity(centre + Eigen::Vector2d(std::max(0.0, d - radius_px), 0), t_s));
    cover.min = std::max(cover.min, c.Opacity(centre + Eigen::Vector2d(d + radius_px, 0), t_s));
    for (int i = 0; i < kRings; ++i) {
      const double r = radius_px * std::sqrt((i + 0.5) / kRings);
      for (int j = 0; j < kSpokes; ++j) {
        const double a = 2.0 * M_PI * j / kSpokes;
        clear[i * kSpokes + j] *= 1.0 - c.Opacity(p + r * Eigen::Vector2d(std::cos(a), std::sin(a)), t_s);
      }
    }
  }
  double sum = 0;
  for (double v : clear) sum += 1.0 - v;
  cover.mean = clouds_.empty() ? 0.0 : sum / static_cast<double>(clear.size());
  return cover;
}

// The look-alike moves on q2's constant-velocity prediction from the frame where q2 was last fully clear,
// kLookalikeSidePx beside it; shown in the frames where q2 is fully hidden and the look-alike is clear of
// every cloud and inside the image.
void PointsSimulator::BuildLookalike() {
  using namespace points_detail;
  const Marker& q2 = markers_[1];
  const double radius_px = q2.support_px * opt_.scale * 1.15 + 3.0 * opt_.psf_sigma_px;
  int last_clear = 0;
  for (int k = 0; k < opt_.frames; ++k) {
    if (Occlusion(MarkerAt(q2, TimeS(k)), radius_px, TimeS(k)).max > 0) break;
    last_clear = k;
  }
  look_t0_ = TimeS(last_clear);
  const double dt = 1.0 / opt_.fps;
  look_velocity_ = (MarkerAt(q2, look_t0_ + dt) - MarkerAt(q2, look_t0_ - dt)) / (2 * dt);
  const Eigen::Vector2d side = Eigen::Vector2d(-look_velocity_.y(), look_velocity_.x()).normalized();
  look_start_ = MarkerAt(q2, look_t0_) + side * (kLookalikeSidePx * opt_.scale);
  look_shown_.assign(static_cast<std::size_t>(opt_.frames), 0);
  const double plate_px = (q2.half_px + 6.0) * M_SQRT2 * opt_.scale * 1.15 + 3.0 * opt_.psf_sigma_px;
  for (int k = last_clear + 1; k < opt_.frames; ++k) {
    const double t = TimeS(k);
    const Eigen::Vector2d p = LookalikeAt(t);
    const bool inside = p.x() > plate_px && p.y() > plate_px && p.x() < opt_.width - 1 - plate_px &&
                        p.y() < opt_.height - 1 - plate_px;
    const bool q2_hidden = Occlusion(MarkerAt(q2, t), radius_px, t).min >= 1.0;
    look_shown_[static_cast<std::size_t>(k)] = inside && q2_hidden && Occlusion(p, plate_px, t).max == 0.0;
  }
}

Eigen::Vector2d PointsSimulator::LookalikeAt(double t_s) const { return look_start_ + look_velocity_ * (t_s - look_t0_); }

bool PointsSimulator::LookalikeShown(int k) const {
  return k >= 0 && static_cast<std::size_t>(k) < look_shown_.size() && look_shown_[static_cast<std::size_t>(k)];
}

std::vector<PointTruth> PointsSimulator::Truth(int k) const {
  const double t = TimeS(k);
  const Pose pose = PoseAt(t);
  std::vector<Pose> poses;
  for (double ts : ExposureTimes(k)) poses.push_back(PoseAt(ts));
  std::vector<PointTruth> out;
  const auto inside = [this](const Eigen::Vector2d& p, double margin) {
    return p.x() >= margin && p.y() >= margin && p.x() <= opt_.width - 1 - margin && p.y() <= opt_.height - 1 - margin;
  };
  for (const Marker& m : markers_) {
    PointTruth r;
    r.id = m.id;
    r.method = m.method;
    Eigen::Vector2d p(0, 0);
    for (const Pose& ps : poses) p += ps.Apply(m.body) / static_cast<double>(poses.size());
    r.x_px = p.x(), r.y_px = p.y();
    const double support = m.support_px * pose.scale + 3.0 * opt_.psf_sigma_px;
    const Cover cover = Occlusion(p, support, t);
    r.occlusion = cover.mean;
    r.visible = inside(p, support) && cover.max < kPointVisibleOcclusion;
    r.size_px = 2.0 * (m.method == "centroid-bright" ? 2.0 * m.half_px : m.half_px) * pose.scale;
    out.push_back(std::move(r));
  }
  if (opt_.scenario == PointsScenario::kLookalike) {
    PointTruth r;
    r.id = "lookalike";
    r.method = "quadrant";
    const Eigen::Vector2d p = LookalikeAt(t);
    r.x_px = p.x(), r.y_px = p.y();
    r.visible = LookalikeShown(k);
    r.occlusion = r.visible ? 0.0 : 1.0;
    r.size_px = 2.0 * markers_[1].half_px * pose.scale;
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<PointsSimulator::Seed> PointsSimulator::Seeds() const {
  std::vector<Seed> out;
  for (const PointTruth& r : Truth(0)) {
    if (r.id == "lookalike" || !r.visible) continue;
    out.push_back({r.id, r.method, 0, r.x_px, r.y_px, r.size_px});
  }
  return out;
}

PointsSimulator::Seed PointsSimulator::SeedAt(const std::string& id, int frame) const {
  if (frame < 0 || frame >= opt_.frames) {
    throw UsageError("re-seed frame " + std::to_string(frame) + " is outside 0.." + std::to_string(opt_.frames - 1));
  }
  for (const PointTruth& r : Truth(frame)) {
    if (r.id == id && id != "lookalike") return {r.id, r.method, frame, r.x_px, r.y_px, r.size_px};
  }
  throw UsageError("re-seed id '" + id + "' is not a marker (q1, q2, c1, b1, d1, t1, t2)");
}

}  // namespace rk::sim

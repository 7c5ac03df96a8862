#include "calibrate/pointing_observations.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::calibrate {
namespace {

constexpr double kRateStepS = 0.005;  // half-width of the central difference for star rates and log motion
// Half-width of the central difference for the turret's rate (pointing_observations.h "Turret rate"):
// 2.5 log intervals of a 50 Hz log, short against a slew's S-curve (≥ 0.5 s).
constexpr double kTurretRateHalfWindowS = 0.05;
// Two consecutive log samples of an axis moving fewer than this many encoder steps between them do not
// have independent quantisation errors: below one step per sample the error is a sawtooth drifting with
// the motion (e_k+1 = e_k − Δθ + ΔL), at a few steps it decorrelates. Interpolating between such samples
// does not average their errors down, so the reading keeps the full σ = step/√12 (with √(2/3) there the
// Monte Carlo of tests/calibrate/test_pointing_mc.cc found mean NEES up to 1.5, σ 15–20 % optimistic:
// most image points of a slew are taken near its S-curve ends, where the turret is slow).
constexpr double kSlowStepsPerSample = 3.0;

std::string PointingFixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// Where an id names a target: index into landmarks (>= 0) or stars (encoded as -1 - index).
struct TargetIndex {
  std::map<std::string, int> by_id;
  explicit TargetIndex(const TargetCatalogue& c) {
    for (std::size_t i = 0; i < c.landmarks.size(); ++i) by_id[c.landmarks[i].id] = static_cast<int>(i);
    for (std::size_t i = 0; i < c.stars.size(); ++i) by_id.emplace(c.stars[i].id, -1 - static_cast<int>(i));
  }
};

// Unit ENU direction of target `code` at trial time t (s).
Eigen::Vector3d TargetDirection(const TargetCatalogue& c, int code, double t_s) {
  if (code >= 0) return c.landmarks[static_cast<std::size_t>(code)].p_enu.normalized();
  const target::Star& s = c.stars[static_cast<std::size_t>(-1 - code)];
  const target::ObservedPlace o = target::StarObservedPlace(s, c.station, c.epoch_utc->Plus(t_s), c.dut1_s, c.atmosphere);
  return target::DirectionEnu(o.az_rad, o.el_rad);
}

// Boresight at t and its rate, or an error naming the observation.
void TurretAt(const track::BoresightSource& turret, const ImagePoints& pts, const ImagePoint& p, double t,
              PointingObservation* o) {
  track::InterpStatus status = track::InterpStatus::kOk;
  const std::optional<geo::AzEl> b = turret.At(t, &status);
  if (!b) {
    throw DataError(pts.source, p.line, 1,
                    "turret log " + turret.source() + " does not cover the observation's time t_s " + PointingFixed(t, 6) +
                        " (" + track::InterpStatusName(status) + ")");
  }
  o->az_log_rad = b->az_rad;
  o->el_log_rad = b->el_rad;
  o->sample_weight = turret.SampleWeight(t);
  const auto lo = turret.At(t - kRateStepS), hi = turret.At(t + kRateStepS);
  for (const auto& v : {lo, hi}) {
    if (v && (v->az_rad != b->az_rad || v->el_rad != b->el_rad)) o->log_moving = true;
  }
  if (!o->log_moving) return;  // a still reading: rate zero
  const double w = kTurretRateHalfWindowS;
  const auto wlo = turret.At(t - w), whi = turret.At(t + w);
  const double t_lo = wlo ? t - w : t, t_hi = whi ? t + w : t;
  const geo::AzEl a = wlo ? *wlo : *b, c = whi ? *whi : *b;
  if (t_hi > t_lo) {
    o->az_rate_rps = geo::WrapPi(c.az_rad - a.az_rad) / (t_hi - t_lo);
    o->el_rate_rps = (c.el_rad - a.el_rad) / (t_hi - t_lo);
  }
}

// Creep window (pointing_observations.h "Shared errors"): (1 + √2) bounds the creep after the last
// transition at constant deceleration; 2.5 leaves margin for the log's sampling of the transition times.
constexpr double kCreepFactor = 2.5;
constexpr double kMaxCreepSearchS = 10.0;  // transitions are looked for this far from a still stretch

bool SameReading(const std::optional<geo::AzEl>& a, const std::optional<geo::AzEl>& b) {
  return a && b && a->az_rad == b->az_rad && a->el_rad == b->el_rad;
}

// The end of a still stretch reading `r` at t0, searched in direction dir (−1: the approach before t0, +1: the
// departure after t0) on the log grid dt: `edge`, the stretch's last time still reading r (t0 when no
// transition is found), and `window`, the time the turret creeps inside its cell there: kCreepFactor × the
// time between the stretch's transition and the one before it, plus one log interval (0 when either
// transition is not found).
struct StretchEnd {
  double edge = 0.0, window = 0.0;
};
StretchEnd FindStretchEnd(const track::BoresightSource& turret, double t0, int dir, double dt) {
  const std::optional<geo::AzEl> r = turret.At(t0);
  StretchEnd end{t0, 0.0};
  double t = t0, t_edge = std::numeric_limits<double>::quiet_NaN();
  std::optional<geo::AzEl> cell;  // the reading just outside the stretch
  for (; std::abs(t - t0) <= kMaxCreepSearchS; t += dir * dt) {
    const std::optional<geo::AzEl> v = turret.At(t);
    if (!v) return end;
    if (!SameReading(v, r)) {
      t_edge = t;
      cell = v;
      break;
    }
    end.edge = t;
  }
  if (std::isnan(t_edge)) return end;
  for (t = t_edge + dir * dt; std::abs(t - t0) <= kMaxCreepSearchS; t += dir * dt) {
    const std::optional<geo::AzEl> v = turret.At(t);
    if (!v) break;
    if (!SameReading(v, cell)) {
      end.window = kCreepFactor * std::abs(t - t_edge) + dt;
      return end;
    }
  }
  return end;
}

// Splits off the image points of a still cluster taken while the turret may still be creeping in its cell.
void SplitCreep(const track::BoresightSource& turret, double dt, double sigma_q, PointingObservations* out) {
  if (!(dt > 0.0)) return;
  const std::size_t n_clusters = out->cluster_sigma_rad.size();
  std::vector<std::size_t> first(n_clusters, out->obs.size()), last(n_clusters, 0);
  for (std::size_t i = 0; i < out->obs.size(); ++i) {
    const auto c = static_cast<std::size_t>(out->obs[i].cluster);
    first[c] = std::min(first[c], i);
    last[c] = i;
  }
  for (std::size_t c = 0; c < n_clusters; ++c) {
    const PointingObservation& a = out->obs[first[c]];
    if (a.log_moving) continue;
    const double t_in = a.t_turret_s, t_out = out->obs[last[c]].t_turret_s;
    // stretch ends (to one log interval) and their creep windows, probed from the cluster's first and last
    // image point
    const StretchEnd in = FindStretchEnd(turret, t_in, -1, dt), out_end = FindStretchEnd(turret, t_out, +1, dt);
    const double w_in = in.window, w_out = out_end.window, start = in.edge, end = out_end.edge;
    if (w_in == 0.0 && w_out == 0.0) continue;
    for (std::size_t i = first[c]; i <= last[c]; ++i) {
      PointingObservation& o = out->obs[i];
      if (o.cluster != static_cast<int>(c)) continue;
      if (o.t_turret_s >= start + w_in && o.t_turret_s <= end - w_out) continue;
      --out->cluster_size[c];
      o.cluster = static_cast<int>(out->cluster_sigma_rad.size());
      out->cluster_sigma_rad.push_back(Eigen::Vector2d::Constant(sigma_q));
      out->cluster_size.push_back(1);
    }
  }
}

// σ of one axis's reading interpolated at weight w between two log samples during a slew:
// step/√12 · √((1 − w)² + w²) when the axis moves at least kSlowStepsPerSample steps per log interval
// (independent sample errors), step/√12 when slower.
double MovingReadingSigma(double sigma_q, double rate_rps, double w, double step_rad, double log_interval_s) {
  const bool fast = std::isfinite(log_interval_s) && std::isfinite(w) &&
                    std::abs(rate_rps) * log_interval_s >= kSlowStepsPerSample * step_rad;
  return fast ? sigma_q * std::sqrt((1 - w) * (1 - w) + w * w) : sigma_q;
}

// Groups consecutive observations with bit-identical logged angles: one dwell's encoder reading, or, during
// a slew, the one interpolated reading of a frame in which several targets are seen.
void AssignClusters(const track::BoresightSource& turret, double step_rad, PointingObservations* out) {
  const double log_interval_s = turret.mean_sample_interval_s();
  const double sigma_q = step_rad / std::sqrt(12.0);
  int current = -1;
  std::vector<char> still;
  for (std::size_t i = 0; i < out->obs.size(); ++i) {
    PointingObservation& o = out->obs[i];
    const bool same = i > 0 && o.az_log_rad == out->obs[i - 1].az_log_rad && o.el_log_rad == out->obs[i - 1].el_log_rad;
    if (!same) {
      current = static_cast<int>(out->cluster_sigma_rad.size());
      const bool moving = o.log_moving;
      still.push_back(!moving);
      const double w = o.sample_weight;
      out->cluster_sigma_rad.push_back(
          moving ? Eigen::Vector2d(MovingReadingSigma(sigma_q, o.az_rate_rps, w, step_rad, log_interval_s),
                                   MovingReadingSigma(sigma_q, o.el_rate_rps, w, step_rad, log_interval_s))
                 : Eigen::Vector2d::Constant(sigma_q));
      out->cluster_size.push_back(0);
    }
    o.cluster = current;
    ++out->cluster_size[static_cast<std::size_t>(current)];
  }
  SplitCreep(turret, log_interval_s, sigma_q, out);
  for (std::size_t c = 0; c < still.size(); ++c) {
    if (still[c] && out->cluster_size[c] > 1) ++out->dwells;
  }
}

}  // namespace

ImagePoints ReadImagePoints(const io::CsvTable& t) {
  const formats::ImagePoints file = formats::ReadImagePoints(t);
  ImagePoints out;
  out.source = file.source;
  std::int64_t row = 0;
  for (const formats::ImagePointFrame& f : file.frames) {
    for (const formats::ImagePoint& q : f.points) {
      const std::int64_t index = row++;
      if (!q.measured()) {  // no position to fit (image_points.h)
        ++out.unmeasured_rows;
        continue;
      }
      ImagePoint p;
      p.frame = f.frame.value_or(index);
      p.t_s = f.t_s;
      p.id = q.id;
      p.px = *q.px;
      p.sigma_px = q.sigma_px;
      p.line = q.line;
      p.id_column = static_cast<int>(q.col_id);
      out.rows.push_back(std::move(p));
    }
  }
  return out;
}

PointingObservations BuildObservations(const ImagePoints& pts, const TargetCatalogue& cat,
                                       const track::BoresightSource& turret, double encoder_step_rad,
                                       double default_sigma_px, double tau0_s) {
  const TargetIndex index(cat);
  PointingObservations out;
  out.tau0_s = tau0_s;
  std::map<int, int> target_slot;  // catalogue code → index into out.target_ids
  for (std::size_t r = 0; r < pts.rows.size(); ++r) {
    const ImagePoint& p = pts.rows[r];
    const auto it = index.by_id.find(p.id);
    if (it == index.by_id.end()) {
      throw DataError(pts.source, p.line, static_cast<std::size_t>(p.id_column),
                      "unknown target id '" + p.id + "' (not in the landmarks or stars)");
    }
    const int code = it->second;
    PointingObservation o;
    o.row = r;
    o.px = p.px;
    o.sigma_px = p.sigma_px.value_or(Eigen::Vector2d::Constant(default_sigma_px));
    o.is_star = code < 0;
    const double t = p.t_s + tau0_s;
    o.dir_enu = TargetDirection(cat, code, t);
    if (o.is_star) {
      o.dir_rate_enu = (TargetDirection(cat, code, t + kRateStepS) - TargetDirection(cat, code, t - kRateStepS)) /
                       (2 * kRateStepS);
      if (o.dir_enu.z() < 0.0) {
        throw DataError(pts.source, p.line, static_cast<std::size_t>(p.id_column),
                        "star '" + p.id + "' is below the horizon at t_s " + PointingFixed(p.t_s, 3) + " (elevation " +
                            PointingFixed(geo::RadToDeg(std::asin(o.dir_enu.z())), 3) + " deg; check --epoch-utc and --station)");
      }
    }
    o.t_turret_s = t;
    TurretAt(turret, pts, p, t, &o);
    auto [slot, inserted] = target_slot.emplace(code, static_cast<int>(out.target_ids.size()));
    if (inserted) {
      out.target_ids.push_back(p.id);
      double sigma = 0.0;
      if (code >= 0) {
        const target::Landmark& l = cat.landmarks[static_cast<std::size_t>(code)];
        sigma = l.sigma_m / l.p_enu.norm();
      }
      out.target_sigma_rad.push_back(sigma);
    }
    o.target = slot->second;
    out.obs.push_back(o);
  }
  AssignClusters(turret, encoder_step_rad, &out);
  return out;
}

}  // namespace rk::calibrate

#include "calibrate/pointing_observations.h"

#include <cmath>
#include <map>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::calibrate {
namespace {

constexpr double kRateStepS = 0.005;  // half-width of the central difference for turret and star rates
// Mean of (1−w)² + w² over w uniform in [0, 1]: the quantisation variance factor of a reading
// interpolated between two independent readings.
constexpr double kInterpolatedQuantFactor = 2.0 / 3.0;

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
void TurretAt(const locate::BoresightSource& turret, const ImagePoints& pts, const ImagePoint& p, double t,
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
  const auto lo = turret.At(t - kRateStepS), hi = turret.At(t + kRateStepS);
  const double t_lo = lo ? t - kRateStepS : t, t_hi = hi ? t + kRateStepS : t;
  const geo::AzEl a = lo ? *lo : *b, c = hi ? *hi : *b;
  if (t_hi > t_lo) {
    o->az_rate_rps = geo::WrapPi(c.az_rad - a.az_rad) / (t_hi - t_lo);
    o->el_rate_rps = (c.el_rad - a.el_rad) / (t_hi - t_lo);
  }
}

// Groups consecutive observations with bit-identical logged angles: one dwell's encoder reading, or, during
// a slew, the one interpolated reading of a frame in which several targets are seen.
void AssignClusters(double step_rad, PointingObservations* out) {
  const double sigma_q = step_rad / std::sqrt(12.0);
  int current = -1;
  std::vector<char> moving;
  for (std::size_t i = 0; i < out->obs.size(); ++i) {
    PointingObservation& o = out->obs[i];
    const bool same = i > 0 && o.az_log_rad == out->obs[i - 1].az_log_rad && o.el_log_rad == out->obs[i - 1].el_log_rad;
    if (!same) {
      current = static_cast<int>(out->cluster_sigma_rad.size());
      out->cluster_sigma_rad.push_back(Eigen::Vector2d::Constant(sigma_q));
      out->cluster_size.push_back(0);
      moving.push_back(o.az_rate_rps != 0.0 || o.el_rate_rps != 0.0);
    }
    o.cluster = current;
    ++out->cluster_size[static_cast<std::size_t>(current)];
  }
  for (std::size_t c = 0; c < out->cluster_size.size(); ++c) {
    if (moving[c]) {
      out->cluster_sigma_rad[c] *= std::sqrt(kInterpolatedQuantFactor);
    } else if (out->cluster_size[c] > 1) {
      ++out->dwells;
    }
  }
}

}  // namespace

ImagePoints ReadImagePoints(const io::CsvTable& t) {
  const int cf = t.Column("frame"), ct = t.RequireColumn("t_s"), cid = t.RequireColumn("id");
  const int cx = t.RequireColumn("x_px"), cy = t.RequireColumn("y_px");
  const int csx = t.Column("sigma_x_px"), csy = t.Column("sigma_y_px");
  t.RequireNonDecreasing(ct);
  ImagePoints out;
  out.source = t.name();
  for (std::size_t r = 0; r < t.rows(); ++r) {
    ImagePoint p;
    p.frame = cf >= 0 ? t.Int(r, cf) : static_cast<std::int64_t>(r);
    p.t_s = t.Double(r, ct);
    p.id = std::string(t.Cell(r, cid));
    if (p.id.empty()) throw t.CellError(r, cid, "empty target id");
    p.px = {t.Double(r, cx), t.Double(r, cy)};
    p.line = t.Line(r);
    p.id_column = static_cast<int>(t.CharColumn(r, cid));
    if (csx >= 0 && csy >= 0) {
      const auto sx = t.OptionalDouble(r, csx), sy = t.OptionalDouble(r, csy);
      if (sx && !(*sx > 0.0)) throw t.CellError(r, csx, "sigma_x_px must be > 0");
      if (sy && !(*sy > 0.0)) throw t.CellError(r, csy, "sigma_y_px must be > 0");
      if (sx && sy) p.sigma_px = Eigen::Vector2d(*sx, *sy);
    }
    out.rows.push_back(p);
  }
  return out;
}

PointingObservations BuildObservations(const ImagePoints& pts, const TargetCatalogue& cat,
                                       const locate::BoresightSource& turret, double encoder_step_rad,
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
  AssignClusters(encoder_step_rad, &out);
  return out;
}

}  // namespace rk::calibrate

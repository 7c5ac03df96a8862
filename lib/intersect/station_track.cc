// A station's located file aligned to any time; see station_track.h.
#include "intersect/station_track.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "intersect/intersect_common.h"
#include "geo/angles.h"
#include "track/interp.h"

namespace rk::intersect {
namespace {

// Rows k, k+1 of `t` around `ts` and the fraction f ∈ [0, 1]; false outside.
bool Bracket(const std::vector<double>& t, double ts, std::size_t* k, double* f) {
  if (t.empty() || ts < t.front() || ts > t.back()) return false;
  const auto it = std::upper_bound(t.begin(), t.end(), ts);
  std::size_t hi = static_cast<std::size_t>(it - t.begin());
  if (hi == t.size()) hi = t.size() - 1;
  if (hi == 0) hi = 1;
  if (t.size() == 1) {
    *k = 0, *f = 0.0;
    return true;
  }
  *k = hi - 1;
  *f = (ts - t[*k]) / (t[hi] - t[*k]);
  return true;
}

// σ of the linear interpolation of white noise with per-row σ s at fraction f.
double InterpSigma(const std::vector<double>& s, std::size_t k, double f) {
  if (k + 1 >= s.size()) return s[k];
  return std::sqrt((1.0 - f) * (1.0 - f) * s[k] * s[k] + f * f * s[k + 1] * s[k + 1]);
}

// Covariance of two such interpolated errors with per-row covariances c (rows independent of each other).
double InterpCovariance(const std::vector<double>& c, std::size_t k, double f) {
  if (k + 1 >= c.size()) return c[k];
  return (1.0 - f) * (1.0 - f) * c[k] + f * f * c[k + 1];
}

}  // namespace

struct StationTrack::Impl {
  std::optional<track::TimeSeriesInterpolator> az, el, range;
};

StationTrack::~StationTrack() = default;
StationTrack::StationTrack(StationTrack&&) noexcept = default;

StationTrack::StationTrack(const formats::LocatedFile& file, const TrackDefaults& defaults, double time_offset_s)
    : impl_(std::make_unique<Impl>()), source_(file.source) {
  has_range_ = file.has_range;
  has_sigma_ = file.has_sigma;
  std::vector<std::optional<double>> az, el, range;
  for (const formats::LocatedRecord& row : file.rows) {
    const double t = row.t_s + time_offset_s;
    row_t_.push_back(t);
    const bool status_measured = row.status == RowStatus::kOk || row.status == RowStatus::kReacquired;
    std::optional<double> a, e;
    if (row.measured()) a = row.az_rad, e = row.el_rad;
    const std::optional<double> r = has_range_ && status_measured ? row.range_m : std::nullopt;
    if (a) {
      const double ce = std::max(std::cos(*e), 1e-9);
      double saz = defaults.sigma_angle_rad / ce, sel = defaults.sigma_angle_rad;
      if (has_sigma_) {
        if (row.sigma_az_rad) saz = *row.sigma_az_rad;
        if (row.sigma_el_rad) sel = *row.sigma_el_rad;
      }
      // rk-locate's correlation of the azimuth and elevation errors (issue 28 item 6); 0 when absent.
      const double corr = row.corr_az_el.value_or(0.0);
      t_.push_back(t), sig_az_.push_back(saz), sig_el_.push_back(sel), cov_az_el_.push_back(corr * saz * sel);
      az_.push_back(*a);
      az_unwrapped_.push_back(az_unwrapped_.empty() ? *a
                                                    : az_unwrapped_.back() + geo::WrapPi(*a - az_unwrapped_.back()));
      el_.push_back(*e);
      row_range_.push_back(r ? *r : std::numeric_limits<double>::quiet_NaN());
      row_sig_r_.push_back(r ? row.sigma_range_m.value_or(defaults.sigma_range_m) : 0.0);
    }
    if (r) {
      tr_.push_back(t), sig_r_.push_back(row.sigma_range_m.value_or(defaults.sigma_range_m)), r_.push_back(*r);
    }
    az.push_back(a);
    el.push_back(e);
    range.push_back(r);
  }
  has_range_ = !tr_.empty();  // a range column that is always empty is no rangefinder
  std::vector<double> dt;
  for (std::size_t i = 1; i < row_t_.size(); ++i) dt.push_back(row_t_[i] - row_t_[i - 1]);
  frame_interval_s_ = dt.empty() ? 0.0 : internal::UpperMedianOrNaN(dt);
  track::InterpOptions io;
  io.method = track::InterpMethod::kLinear;
  io.max_gap_s = frame_interval_s_ > 0.0 ? defaults.max_gap_frames * frame_interval_s_ : 1.0;
  io.angle = true;
  impl_->az.emplace(row_t_, az, io);
  io.angle = false;
  impl_->el.emplace(row_t_, el, io);
  if (has_range_) impl_->range.emplace(row_t_, range, io);
}

bool StationTrack::At(double t_s, LineObservation* o) const {
  const track::InterpValue a = impl_->az->At(t_s);
  if (!a.ok()) return false;
  const track::InterpValue e = impl_->el->At(t_s);
  if (!e.ok()) return false;
  std::size_t k = 0;
  double f = 0.0;
  if (!Bracket(t_, t_s, &k, &f)) return false;
  o->az_rad = geo::WrapTwoPi(a.value);
  o->el_rad = e.value;
  o->sigma_az_rad = InterpSigma(sig_az_, k, f);
  o->sigma_el_rad = InterpSigma(sig_el_, k, f);
  double cov = InterpCovariance(cov_az_el_, k, f);
  if (time_sigma_s_ > 0.0 && k + 1 < t_.size()) {
    // The clock's uncertainty moves the line of sight along its own motion.
    const double dt = t_[k + 1] - t_[k];
    const double ra = (az_unwrapped_[k + 1] - az_unwrapped_[k]) / dt * time_sigma_s_;
    const double re = (el_[k + 1] - el_[k]) / dt * time_sigma_s_;
    o->sigma_az_rad = std::hypot(o->sigma_az_rad, ra);
    o->sigma_el_rad = std::hypot(o->sigma_el_rad, re);
    cov += ra * re;
  }
  o->corr_az_el = cov / (o->sigma_az_rad * o->sigma_el_rad);
  o->has_range = false;
  if (impl_->range) {
    const track::InterpValue r = impl_->range->At(t_s);
    if (r.ok() && Bracket(tr_, t_s, &k, &f)) {
      o->has_range = true;
      o->range_m = r.value;
      o->sigma_range_m = InterpSigma(sig_r_, k, f);
      if (time_sigma_s_ > 0.0 && k + 1 < tr_.size()) {
        o->sigma_range_m = std::hypot(o->sigma_range_m, (r_[k + 1] - r_[k]) / (tr_[k + 1] - tr_[k]) * time_sigma_s_);
      }
    }
  }
  return true;
}

LineObservation StationTrack::UsableRow(std::size_t k) const {
  LineObservation o;
  o.az_rad = geo::WrapTwoPi(az_[k]);
  o.el_rad = el_[k];
  o.sigma_az_rad = sig_az_[k];
  o.sigma_el_rad = sig_el_[k];
  o.corr_az_el = cov_az_el_[k] / (sig_az_[k] * sig_el_[k]);
  o.has_range = std::isfinite(row_range_[k]);
  if (o.has_range) {
    o.range_m = row_range_[k];
    o.sigma_range_m = row_sig_r_[k];
  }
  return o;
}

}  // namespace rk::intersect

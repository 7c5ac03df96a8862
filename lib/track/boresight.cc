// Turret boresight at frame times; see boresight.h.
#include "track/boresight.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::track {

BoresightSource BoresightSource::Fixed(double az_rad, double el_rad) {
  BoresightSource b;
  b.fixed_ = true;
  b.fixed_dir_.az_rad = geo::WrapTwoPi(az_rad);
  b.fixed_dir_.el_rad = el_rad;
  return b;
}

BoresightSource BoresightSource::FromLog(formats::TurretLog log, track::InterpMethod method, double max_gap_s) {
  if (!(max_gap_s > 0.0)) throw UsageError("--turret-max-gap must be > 0 s");
  BoresightSource b;
  b.fixed_ = false;
  b.source_ = log.source;
  track::InterpOptions o;
  o.method = method;
  o.max_gap_s = max_gap_s;
  // In place: azimuth unwrapped (so that merged repeated times average across north), repeated times merged
  // in both columns at once, then the columns handed to the interpolators, which share the times.
  track::UnwrapAnglesInPlace(&log.az_rad);
  b.duplicates_ = track::MergeDuplicateTimes(&log.t_s, {&log.az_rad, &log.el_rad});
  const auto times = std::make_shared<const std::vector<double>>(std::move(log.t_s));
  o.angle = true;
  b.az_.emplace(times, std::move(log.az_rad), o);
  o.angle = false;
  b.el_.emplace(times, std::move(log.el_rad), o);
  return b;
}

std::optional<geo::AzEl> BoresightSource::At(double t_s, track::InterpStatus* status) const {
  if (fixed_) {
    if (status) *status = track::InterpStatus::kOk;
    return fixed_dir_;
  }
  const track::InterpValue a = az_->At(t_s);
  const track::InterpValue e = el_->At(t_s);
  if (!a.ok() || !e.ok()) {
    if (status) *status = !a.ok() ? a.status : e.status;
    return std::nullopt;
  }
  if (status) *status = track::InterpStatus::kOk;
  geo::AzEl d;
  d.az_rad = geo::WrapTwoPi(a.value);
  d.el_rad = e.value;
  return d;
}

double BoresightSource::first_time() const { return fixed_ ? std::nan("") : az_->first_time(); }
double BoresightSource::last_time() const { return fixed_ ? std::nan("") : az_->last_time(); }
double BoresightSource::SampleWeight(double t_s) const {
  if (fixed_) return std::nan("");
  const auto b = az_->Bracket(t_s);
  if (!b || !(b->second > b->first)) return std::nan("");
  return std::clamp((t_s - b->first) / (b->second - b->first), 0.0, 1.0);
}

double BoresightSource::mean_sample_interval_s() const {
  if (fixed_ || az_->usable_samples() < 2) return std::nan("");
  return (az_->last_time() - az_->first_time()) / static_cast<double>(az_->usable_samples() - 1);
}

std::string BoresightSource::CoverageText() const {
  if (fixed_) return "is a fixed boresight";
  if (az_->usable_samples() == 0) return "has no usable sample";
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << "covers t_s " << az_->first_time() << " .. " << az_->last_time();
  return s.str();
}

void BoresightSource::ThrowNoFrameCovered(const std::string& kind, const std::string& frames_source, double t_first,
                                          double t_last, const std::string& gap_option) const {
  // Fixed-point seconds: in the default notation a log stamped in seconds since 1970 read "1.7643e+09 ..
  // 1.7643e+09" at both ends. When the log and the frames do not overlap at all, say by how much: the usual
  // cause is two clocks (a log in UTC seconds, frames in seconds since the trial epoch).
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << kind << " log " << CoverageText() << " but no frame time of "
    << frames_source << " (t_s " << t_first << " .. " << t_last << ") is covered within the " << gap_option
    << " limit";
  if (!fixed_ && az_->usable_samples() > 0) {
    if (az_->first_time() > t_last) {
      s << "; the log starts " << az_->first_time() - t_last << " s after the last frame";
    } else if (az_->last_time() < t_first) {
      s << "; the log ends " << t_first - az_->last_time() << " s before the first frame";
    }
    if (az_->first_time() > t_last || az_->last_time() < t_first) s << " (are both t_s on the trial's clock?)";
  }
  throw DataError(source_, 0, 0, s.str());
}

}  // namespace rk::track

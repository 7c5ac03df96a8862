// Beacon tracking with Singer prediction, gating, template validation and
// occlusion handling; the method is described in beacon_tracker.h (seed 001 §2.2).
#include "extract/beacon_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rk::extract {

const io::OptionTable<BeaconTrackOptions>& BeaconTrackOptions::Table() {
  using B = io::Bounds;
  using O = BeaconTrackOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Sub(&O::detect, DetectOptions::Table())
          .Real("--maneuver-time", &O::maneuver_time_s, "s", B::Positive().Finite(), "Singer maneuver time constant 1/a (s)")
          .Real("--accel-sigma", &O::accel_sigma_px_s2, "px/s^2", B::Positive().Finite(),
                "Singer RMS image acceleration (px/s^2)")
          .Real("--meas-sigma", &O::meas_sigma_px, "px", B::Positive(), "Centroid noise assumed by the filter (px)")
          .Real("--gate-sigma", &O::gate_sigma, "", B::Positive(), "Search window half size in predicted sigmas")
          .Real("--gate-chi2", &O::gate_chi2, "", B::Positive(),
                "Mahalanobis gate (2 dof): full-frame search while tracking; a re-acquisition beyond it restarts "
                "the filter")
          .Integer("--window-min", &O::min_window_px, "px", B::AtLeast(4), "Smallest search window half size (px)")
          .Integer("--window-max", &O::max_window_px, "px", B::AtLeast(4),
                   "Largest search window half size (px); beyond it the whole frame is searched")
          .Real("--ncc-track", &O::ncc_track, "", B::Closed(-1, 1), "NCC with the template needed while tracking")
          .Real("--ncc-reacquire", &O::ncc_reacquire, "", B::Closed(-1, 1), "NCC needed to re-acquire after a loss")
          .Real("--ncc-update", &O::ncc_template_update, "", B::Closed(-1, 1), "Template refreshed when NCC >= this")
          .Real("--size-ratio", &O::size_ratio, "", B::AtLeast(1), "Candidate/template size ratio allowed, [1/r, r]")
          .Real("--flux-ratio", &O::flux_ratio, "", B::AtLeast(1),
                "Re-acquisition: candidate/template flux ratio allowed, [1/r, r]")
          .Real("--long-loss", &O::long_loss_s, "s", B::AtLeast(0),
                "Losses this long (s): no window search, the filter restarts")
          .Real("--min-flux", &O::min_flux_dn, "dn", B::AtLeast(0), "Acquisition: minimum flux (DN*px), 0 = any")
          .Real("--fill-gaps", &O::fill_gaps_s, "s", B::AtLeast(0),
                "Fill the first S seconds of a gap with the prediction (status predicted); 0 = off")
          .Choice("--estimator", &O::per_lamp, {{true, "auto"}, {false, "cluster"}},
                  "Position: auto (per-lamp centroids with averaged flux shares when the lamps resolve, else the "
                  "cluster centroid) or cluster (always the cluster centroid)");
  return table;
}

bool BeaconTrackOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why) || !detect.Check(why)) return false;
  auto fail = [&](const char* w) {
    if (why) *why = w;
    return false;
  };
  if (!(init_vel_sigma_px_s > 0)) return fail("initial velocity sigma must be > 0 px/s");
  if (max_window_px < min_window_px) return fail("--window-max must be >= --window-min");
  return true;
}

namespace {
// After a (re)start the filter needs this many measurements to know the image
// velocity; until then a window without a match falls back to the full frame.
constexpr int kSettleUpdates = 2;

track::SingerAxisOptions Axis(const BeaconTrackOptions& o) {
  track::SingerAxisOptions a;
  a.maneuver_time_s = o.maneuver_time_s;
  a.accel_sigma = o.accel_sigma_px_s2;
  return a;
}
}  // namespace

BeaconTracker::BeaconTracker(const BeaconTrackOptions& opt)
    : opt_(opt), det_(opt.detect), kf_({Axis(opt), Axis(opt)}), lamps_(opt.detect) {
  cand_.reserve(static_cast<std::size_t>(opt.detect.max_candidates) + 4);
}

bool BeaconTracker::AcquireInitial(const cv::Mat& frame, SpotMeasurement* best) {
  det_.FindInFrame(frame, &cand_);
  ++summary_.full_frame_searches;
  bool found = false;
  for (const auto& c : cand_) {
    if (c.clipped || c.flux_dn < opt_.min_flux_dn) continue;
    if (!found || c.size_px > best->size_px) {
      *best = c;
      found = true;
    }
  }
  return found;
}

void BeaconTracker::Accept(const cv::Mat& frame, const SpotMeasurement& m, double ncc, bool restart,
                           BeaconFrameResult* r) {
  r->x_px = m.x_px;
  r->y_px = m.y_px;
  r->sigma_x_px = m.sigma_x_px;
  r->sigma_y_px = m.sigma_y_px;
  if (restart) lamps_.Reset();
  LampEstimate lamp;
  if (opt_.per_lamp && lamps_.Estimate(frame, m, &lamp)) {
    r->x_px = lamp.x_px;
    r->y_px = lamp.y_px;
    r->sigma_x_px = lamp.sigma_x_px;
    r->sigma_y_px = lamp.sigma_y_px;
    r->per_lamp = true;
    ++summary_.per_lamp;
  }
  const Eigen::Vector2d z(r->x_px, r->y_px);
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * (opt_.meas_sigma_px * opt_.meas_sigma_px);
  if (restart || !kf_.initialised()) {
    kf_.Initialise(z, R, opt_.init_vel_sigma_px_s, opt_.accel_sigma_px_s2);
    updates_since_restart_ = 0;
  } else {
    kf_.Update(z, R);
    ++updates_since_restart_;
  }
  if (restart || !template_.valid() || ncc >= opt_.ncc_template_update) det_.MakeTemplate(frame, m, &template_);
  mode_ = Mode::kTrack;
  r->has_xy = true;
  r->has_spot = true;
  r->peak_dn = m.peak_dn;
  r->area_px = m.area_px;
}

void BeaconTracker::Miss(bool invalid, BeaconFrameResult* r) {
  if (mode_ == Mode::kTrack) {
    mode_ = Mode::kLostShort;
    lost_since_s_ = r->t_s;
  }
  r->status = invalid ? BeaconStatus::kInvalid : BeaconStatus::kLost;
  if (!invalid && opt_.fill_gaps_s > 0 && kf_.initialised() && mode_ != Mode::kAcquire &&
      r->t_s - lost_since_s_ < opt_.fill_gaps_s) {
    const Eigen::Vector2d p = kf_.PredictedMeasurement();
    const Eigen::Matrix2d S = kf_.InnovationCovariance(Eigen::Matrix2d::Zero());
    r->status = BeaconStatus::kPredicted;
    r->has_xy = true;
    r->x_px = p(0);
    r->y_px = p(1);
    r->sigma_x_px = std::sqrt(std::max(0.0, S(0, 0)));
    r->sigma_y_px = std::sqrt(std::max(0.0, S(1, 1)));
  }
}

bool BeaconTracker::Matches(const cv::Mat& frame, const SpotMeasurement& c, bool reacquire, double* ncc) {
  *ncc = det_.Ncc(frame, c, template_);
  const double size = template_.size_px > 0 && c.size_px > 0 ? c.size_px / template_.size_px : 0.0;
  const bool size_ok = size >= 1.0 / opt_.size_ratio && size <= opt_.size_ratio;
  const double flux = template_.flux_dn > 0 && c.flux_dn > 0 ? c.flux_dn / template_.flux_dn : 0.0;
  const bool flux_ok = !reacquire || (flux >= 1.0 / opt_.flux_ratio && flux <= opt_.flux_ratio);
  return *ncc >= (reacquire ? opt_.ncc_reacquire : opt_.ncc_track) && size_ok && flux_ok && !c.clipped;
}

BeaconFrameResult BeaconTracker::Process(const cv::Mat& frame, std::int64_t frame_index, double t_s) {
  BeaconFrameResult r;
  r.frame = frame_index;
  r.t_s = t_s;
  ++summary_.frames;
  const double dt = have_time_ ? std::max(0.0, t_s - last_t_s_) : 0.0;
  last_t_s_ = t_s;
  have_time_ = true;

  if (mode_ == Mode::kAcquire) {
    SpotMeasurement m;
    if (AcquireInitial(frame, &m)) {
      ++summary_.acquisitions;
      Accept(frame, m, 1.0, true, &r);
      r.status = BeaconStatus::kOk;
      ++summary_.ok;
    } else {
      r.status = BeaconStatus::kLost;
      ++summary_.lost;
    }
    return r;
  }

  kf_.Predict(dt);
  if (mode_ == Mode::kLostShort && t_s - lost_since_s_ >= opt_.long_loss_s) mode_ = Mode::kLostLong;
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * (opt_.meas_sigma_px * opt_.meas_sigma_px);
  const Eigen::Vector2d pred = kf_.PredictedMeasurement();
  const Eigen::Matrix2d S = kf_.InnovationCovariance(R);
  const double gx = opt_.gate_sigma * std::sqrt(S(0, 0)), gy = opt_.gate_sigma * std::sqrt(S(1, 1));
  const bool tracking = mode_ == Mode::kTrack;
  const bool long_loss = mode_ == Mode::kLostLong;
  const bool settling = tracking && updates_since_restart_ < kSettleUpdates;
  const bool window_too_big = gx > opt_.max_window_px || gy > opt_.max_window_px || !std::isfinite(gx + gy) ||
                              !std::isfinite(pred(0) + pred(1));

  // Among candidates passing the identity checks (and the Mahalanobis gate when
  // `gated`), the smallest d² wins. Copied out: cand_ is refilled below.
  SpotMeasurement best;
  bool found = false, rejected = false;
  double best_d2 = std::numeric_limits<double>::infinity(), best_ncc = 0.0;
  auto pick = [&](bool gated, bool reacquire, bool report_rejects) {
    for (const auto& c : cand_) {
      if (c.area_px <= 0) continue;
      const double d2 = kf_.Mahalanobis2(Eigen::Vector2d(c.x_px, c.y_px), R);
      if (gated && d2 > opt_.gate_chi2) continue;  // outside the gate
      double ncc = 0.0;
      if (!Matches(frame, c, reacquire, &ncc)) {
        if (report_rejects) {  // report what was seen and rejected
          rejected = true;
          r.has_spot = true;
          r.peak_dn = c.peak_dn;
          r.area_px = c.area_px;
          r.has_ncc = true;
          r.ncc = ncc;
        }
        continue;
      }
      if (d2 < best_d2) {
        best = c;
        found = true;
        best_d2 = d2;
        best_ncc = ncc;
      }
    }
  };

  cand_.clear();
  bool full_frame = false;
  if (!long_loss && !window_too_big) {
    const int hw_x = std::clamp(static_cast<int>(std::ceil(gx)) + template_.half + opt_.detect.cluster_gap_px, opt_.min_window_px, opt_.max_window_px);
    const int hw_y = std::clamp(static_cast<int>(std::ceil(gy)) + template_.half + opt_.detect.cluster_gap_px, opt_.min_window_px, opt_.max_window_px);
    const int px = static_cast<int>(std::lround(pred(0))), py = static_cast<int>(std::lround(pred(1)));
    const PixelBox box{px - hw_x, py - hw_y, px + hw_x, py + hw_y};
    const NoiseStats noise = det_.BorderStats(frame, box);
    det_.FindInBox(frame, box, noise, &cand_);
    pick(false, !tracking, tracking);
  } else if (tracking) {
    det_.FindInFrame(frame, &cand_);
    ++summary_.full_frame_searches;
    full_frame = true;
    pick(true, false, tracking);
  }
  // Lost, or the velocity not known yet: the whole frame at once, identity
  // checked, ungated.
  if (!found && (!tracking || settling)) {
    if (!full_frame) {
      det_.FindInFrame(frame, &cand_);
      ++summary_.full_frame_searches;
    }
    pick(false, true, false);
  }

  if (found) {
    const bool restart = long_loss || (!tracking && best_d2 > opt_.gate_chi2);
    if (restart && !long_loss) ++summary_.restarts;
    Accept(frame, best, best_ncc, restart, &r);
    r.has_ncc = true;
    r.ncc = best_ncc;
    summary_.ncc_sum += best_ncc;
    ++summary_.ncc_count;
    if (tracking) {
      r.status = BeaconStatus::kOk;
      ++summary_.ok;
    } else {
      r.status = BeaconStatus::kReacquired;
      ++summary_.reacquired;
      if (long_loss) ++summary_.acquisitions;
    }
    return r;
  }
  Miss(tracking && rejected, &r);
  switch (r.status) {
    case BeaconStatus::kInvalid: ++summary_.invalid; break;
    case BeaconStatus::kPredicted: ++summary_.predicted; break;
    default: ++summary_.lost; break;
  }
  return r;
}

}  // namespace rk::extract

// Marker tracking with identities; method in features_tracker.h.
#include "extract/features_tracker.h"

#include <algorithm>
#include <cmath>

namespace rk::extract {

namespace {
constexpr double kMinMeasVarPx2 = 1e-6;  // a floor on a marker's measurement variance for the motion model
}  // namespace

const io::OptionTable<FeatureTrackOptions>& FeatureTrackOptions::Table() {
  using B = io::Bounds;
  using O = FeatureTrackOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Sub(&O::detect, MarkerDetectOptions::Table())
          .Real("--search-px", &O::search_px, "px", B::Positive(), "Search half-size around a predicted marker (px)")
          .Real("--gate", &O::gate_frac, "", B::LeftOpen(0, 0.5),
                "Constellation check: a marker farther than this fraction of the smallest marker separation from "
                "the fitted affine camera is rejected")
          .Integer("--min-track", &O::min_track, "", B::AtLeast(3),
                   "Fewer tracked markers than this start a new identification")
          .Sub(&O::identify, IdentifyOptions::Table());
  return table;
}

bool FeatureTrackOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why) || !detect.Check(why) || !identify.Check(why)) return false;
  auto fail = [&](const char* w) {
    *why = w;
    return false;
  };
  if (!(search_speed_factor >= 0)) return fail("search speed factor must be >= 0");
  if (!(gate_min_px > 0)) return fail("gate must be > 0 px");
  if (!(coast_s >= 0)) return fail("coast time must be >= 0 s");
  return true;
}

FeatureTracker::FeatureTracker(const target::FeatureModel& model, const FeatureTrackOptions& options)
    : model_(model),
      opt_(options),
      detector_(options.detect),
      affine_(model, options.identify.planar_ratio),
      tracks_(model.size()) {}

void FeatureTracker::Accept(std::size_t id, const MarkerMeasurement& m, double t_s, FeatureFrameResult* out) {
  FeaturePoint& p = out->points[id];
  p.has_xy = true;
  p.px = m.px;
  p.sigma_px = m.sigma_px;
  p.ncc = m.ncc;
  p.radius_px = m.radius_px;
  p.edge_px = m.edge_px;
  p.status = tracks_[id].ever && tracks_[id].lost ? RowStatus::kReacquired : RowStatus::kOk;
  (void)t_s;
}

bool FeatureTracker::FitConstellation(const FeatureFrameResult& r, Eigen::Matrix<double, 2, 4>* A,
                                      double* gate) const {
  std::vector<int> idx;
  std::vector<Eigen::Vector2d> px;
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    if (r.points[i].has_xy) {
      idx.push_back(static_cast<int>(i));
      px.push_back(r.points[i].px);
    }
  }
  // A check needs redundancy: one more point than the affine camera has columns.
  const std::size_t need = affine_.planar() ? 4 : 5;
  if (idx.size() < need || !affine_.Fit(idx, px, A)) return false;
  double min_sep = 1e300;
  for (std::size_t i = 0; i < model_.size(); ++i) {
    for (std::size_t j = i + 1; j < model_.size(); ++j) {
      min_sep = std::min(min_sep, (affine_.Predict(*A, i) - affine_.Predict(*A, j)).norm());
    }
  }
  *gate = std::max(opt_.gate_min_px, opt_.gate_frac * min_sep);
  return true;
}

void FeatureTracker::Acquire(double t_s, FeatureFrameResult* out) {
  out->acquisition = true;
  ++summary_.acquisitions;
  std::vector<MarkerMeasurement> det = detector_.DetectAll();
  std::vector<Eigen::Vector2d> px;
  for (const auto& d : det) px.push_back(d.px);
  const Identification id = Identify(px, model_, affine_, opt_.identify);
  if (!id.ok) {
    if (id.ambiguous) {
      out->ambiguous = true;
      ++summary_.ambiguous;
    }
    return;
  }
  ++summary_.acquisitions_ok;
  for (std::size_t i = 0; i < model_.size(); ++i) {
    const int j = id.detection_of_model[i];
    if (j >= 0) Accept(i, det[static_cast<std::size_t>(j)], t_s, out);
  }
  locked_ = true;
}

void FeatureTracker::TrackMarkers(double t_s, FeatureFrameResult* out) {
  const std::size_t n = model_.size();
  // 1. Predicted search for every marker with a recent position.
  for (std::size_t i = 0; i < n; ++i) {
    MarkerTrack& tr = tracks_[i];
    if (!tr.has_pos || t_s - tr.last_t > opt_.coast_s) continue;
    // The shared image motion model (track/image_motion.h); until two consecutive measurements give it a
    // velocity it predicts the last position.
    tr.motion.PredictTo(t_s);
    const Eigen::Vector2d pred = tr.fresh ? tr.pos : tr.motion.Predicted();
    const Eigen::Vector2d motion = pred - tr.pos;
    const double search = opt_.search_px + opt_.search_speed_factor * motion.norm();
    const MarkerMeasurement m = detector_.Measure(pred, search, tr.radius, tr.edge);
    if (m.ok) Accept(i, m, t_s, out);
  }
  // 2. Two ids on one blob: neither can be trusted.
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      FeaturePoint &a = out->points[i], &b = out->points[j];
      if (a.has_xy && b.has_xy && (a.px - b.px).norm() < std::max(2.0, 0.5 * std::max(a.radius_px, b.radius_px))) {
        a.has_xy = b.has_xy = false;
        a.status = b.status = RowStatus::kInvalid;
        summary_.rejected += 2;
      }
    }
  }
  // 3. Constellation check: reject the worst outlier while one exceeds the gate.
  Eigen::Matrix<double, 2, 4> A;
  double gate = 0;
  for (int pass = 0; pass < 3; ++pass) {
    if (!FitConstellation(*out, &A, &gate)) break;
    double worst = 0;
    std::size_t worst_i = n;
    for (std::size_t i = 0; i < n; ++i) {
      if (!out->points[i].has_xy) continue;
      const double d = (out->points[i].px - affine_.Predict(A, i)).norm();
      if (d > gate && d > worst) {
        worst = d;
        worst_i = i;
      }
    }
    if (worst_i == n) break;
    out->points[worst_i].has_xy = false;
    out->points[worst_i].status = RowStatus::kInvalid;
    ++summary_.rejected;
  }
  // 4. Markers not measured: search at the constellation's prediction.
  if (FitConstellation(*out, &A, &gate)) {
    for (std::size_t i = 0; i < n; ++i) {
      FeaturePoint& p = out->points[i];
      if (p.has_xy || p.status == RowStatus::kInvalid) continue;
      const Eigen::Vector2d pred = affine_.Predict(A, i);
      double radius = tracks_[i].radius, edge = tracks_[i].edge;
      if (!(radius > 0)) {  // never seen: borrow the size of the others
        double sum = 0;
        int cnt = 0;
        for (const auto& q : out->points) {
          if (q.has_xy) {
            sum += q.radius_px;
            ++cnt;
          }
        }
        radius = cnt ? sum / cnt : 0.5 * (opt_.detect.min_radius_px + opt_.detect.max_radius_px);
        edge = 1.0;
      }
      const MarkerMeasurement m = detector_.Measure(pred, 0.5 * gate, radius, edge);
      if (!m.ok || (m.px - pred).norm() > 0.5 * gate) continue;
      bool clash = false;
      for (std::size_t j = 0; j < n; ++j) {
        if (j != i && out->points[j].has_xy && (out->points[j].px - m.px).norm() < std::max(2.0, m.radius_px)) {
          clash = true;
        }
      }
      if (!clash) Accept(i, m, t_s, out);
    }
  }
  int measured = 0;
  for (const auto& p : out->points) measured += p.has_xy ? 1 : 0;
  if (measured < opt_.min_track) locked_ = false;
}

FeatureFrameResult FeatureTracker::Process(const cv::Mat& frame, std::int64_t index, double t_s) {
  FeatureFrameResult out;
  out.frame = index;
  out.t_s = t_s;
  out.points.assign(model_.size(), FeaturePoint{});
  detector_.SetFrame(frame);
  if (locked_) TrackMarkers(t_s, &out);
  if (!locked_) {
    // Identities lost (or never had): start again from the whole frame.
    out.points.assign(model_.size(), FeaturePoint{});
    Acquire(t_s, &out);
  }
  // Update the tracks and the counters.
  int measured = 0;
  for (std::size_t i = 0; i < model_.size(); ++i) {
    FeaturePoint& p = out.points[i];
    MarkerTrack& tr = tracks_[i];
    if (p.has_xy) {
      ++measured;
      const double var = std::max(p.sigma_px * p.sigma_px, kMinMeasVarPx2);
      const Eigen::Matrix2d R = var * Eigen::Matrix2d::Identity();
      if (tr.has_pos && !tr.lost && !tr.fresh && t_s > tr.last_t) {
        tr.motion.Update(p.px, R, t_s);
      } else {
        tr.motion.Start(p.px, R, t_s);
      }
      tr.fresh = false;
      tr.pos = p.px;
      tr.has_pos = true;
      tr.last_t = t_s;
      tr.radius = tr.radius > 0 ? 0.5 * (tr.radius + p.radius_px) : p.radius_px;
      tr.edge = tr.ever ? 0.5 * (tr.edge + p.edge_px) : p.edge_px;
      tr.ever = true;
      tr.lost = false;
      summary_.ncc_sum += p.ncc;
      ++summary_.measured;
    } else {
      tr.lost = true;
      if (p.status != RowStatus::kInvalid) p.status = RowStatus::kLost;
    }
    ++summary_.rows_by_status[static_cast<std::size_t>(p.status)];
  }
  if (!locked_) {
    for (auto& tr : tracks_) tr.fresh = true;  // identities found again: each motion starts afresh
  }
  if (measured >= 4) ++summary_.frames_with_4;
  ++summary_.frames;
  summary_.mean_ncc = summary_.measured ? summary_.ncc_sum / static_cast<double>(summary_.measured) : 0.0;
  return out;
}

}  // namespace rk::extract

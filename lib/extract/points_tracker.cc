// Seeded points tracking; the method is described in points_tracker.h.
#include "extract/points_tracker.h"

#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "io/error.h"
#include "numeric/robust_stats.h"

namespace rk::extract {

const io::OptionTable<PointsTrackOptions>& PointsTrackOptions::Table() {
  using B = io::Bounds;
  using O = PointsTrackOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--ncc-min", [](O& o) -> double& { return o.measure.ncc_min; }, "", B::Open(-1, 1),
                "Correlation with the template or the model needed to accept a measurement")
          .Real("--min-contrast", [](O& o) -> double& { return o.measure.min_contrast_sigmas; }, "",
                B::AtLeast(0), "Smallest marker contrast accepted, in noise sigmas of its window")
          .Real("--sigma-floor", [](O& o) -> double& { return o.measure.sigma_floor_px; }, "px", B::AtLeast(0),
                "Added in quadrature to every row's sigma (px)")
          .Real("--maneuver-time", [](O& o) -> double& { return o.motion.maneuver_time_s; }, "s", B::Positive().Finite(),
                "Singer maneuver time constant 1/a (s)")
          .Real("--accel-sigma", [](O& o) -> double& { return o.motion.accel_sigma_px_s2; }, "px/s^2", B::Positive().Finite(),
                "Singer RMS image acceleration (px/s^2)")
          .Real("--init-vel-sigma", [](O& o) -> double& { return o.motion.init_vel_sigma_px_s; }, "px/s", B::Positive().Finite(),
                "Image velocity uncertainty at a seed or a restart (px/s)")
          .Real("--gate-sigma", &O::gate_sigma, "", B::Positive(), "Search half-width in predicted sigmas")
          .Real("--gate-chi2", &O::gate_chi2, "", B::Positive(),
                "Mahalanobis gate (2 dof) for a match while tracking; a re-acquisition beyond it restarts the "
                "filter")
          .Real("--window-min", &O::window_min_px, "px", B::AtLeast(1), "Smallest search half-width (px)")
          .Real("--window-max", &O::window_max_px, "px", B::AtLeast(1), "Largest search half-width while tracking (px)")
          .Real("--reacquire-px", &O::reacquire_px, "px", B::AtLeast(0),
                "Re-acquisition searches at least this far about the prediction (px); 0 = the whole frame")
          .Real("--seed-search", &O::seed_search_px, "px", B::Positive(),
                "Search half-width at a seed without search_px (px)")
          .Real("--context-min", &O::context_min, "", B::Closed(-1, 1),
                "NCC of a match's surroundings with the point's at its last good frame needed to accept it (look-alikes)")
          .Real("--predict-max-sigma", &O::predict_max_sigma_px, "px", B::AtLeast(0),
                "A hidden point is predicted while the prediction's 1 sigma is below this (px), then lost")
          .Real("--predict-max-gap", &O::predict_max_gap_s, "s", B::AtLeast(0),
                "... and for at most this long (s)");
  return table;
}

bool PointsTrackOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (window_max_px < window_min_px) {
    *why = "--window-max must be >= --window-min";
    return false;
  }
  return true;
}

namespace {

constexpr double kMinMeasVar = 1e-6;  // px²: a floor on R so that S stays invertible
constexpr double kStructureSnr = 3.0;    // surroundings whose variance beyond the noise's is below 3 σ_n² are flat
constexpr int kNoiseRowStep = 4;
constexpr double kTypicalWeight = 0.1;        // of the latest row in the point's usual σ and score
constexpr double kReacquireSigmaRatio = 4.0;  // a candidate with σ beyond this × the usual is not the point
constexpr double kReacquireScoreRatio = 0.85; // nor one scoring below this × the usual
constexpr int kShotNoiseFrames = 10;     // frames tried for the recording's shot noise (ShotNoiseSlope)
constexpr double kCleanScoreRatio = 0.97;  // a clean measurement scores at least this × the point's usual
constexpr double kCleanSigmaRatio = 1.5;   // and its σ is at most this × the usual
constexpr int kGroupMin = 3;             // other points, there and here, for a group prediction
constexpr double kGroupMaxRmsPx = 1.0;   // they moved as one body: the similarity fits them to this RMS (px)
constexpr double kGroupTolPx = 1.0;      // a candidate within this (+ kGroupTolSigmas × that RMS) of the
constexpr double kGroupTolSigmas = 4.0;  //   group's prediction is the point
constexpr double kGroupSearchMarginPx = 4.0;  // searched about the group's prediction beyond its tolerance
constexpr double kGroupScore = 2.0;      // ranks a candidate at the group's prediction above any ring NCC (≤ 1)
constexpr double kClaimedPx = 3.0;       // a candidate this close to another point's measurement is that point

// NCC of the ring of a and b (same-size square patches) outside the centre square of half size r_in, divided
// by the NCC that pixel noise alone leaves between two views of the same surroundings (σ_n from each
// patch's neighbour differences), so that the threshold does not depend on the noise. Surroundings without
// structure above the noise (a clear or saturated sky) tell nothing: 1 (no verdict).
// Pixel noise of a patch from the horizontal neighbour differences of every kNoiseRowStep-th row (MAD / √2;
// the context check runs every frame, and a quarter of the rows estimates the noise well enough).
double PatchNoise(const cv::Mat& m) {
  std::vector<double> d;
  d.reserve(static_cast<std::size_t>(m.rows / kNoiseRowStep + 1) * static_cast<std::size_t>(m.cols));
  for (int y = 0; y < m.rows; y += kNoiseRowStep) {
    const float* r = m.ptr<float>(y);
    for (int x = 0; x + 1 < m.cols; ++x) d.push_back(static_cast<double>(r[x + 1]) - r[x]);
  }
  if (d.size() < 8) return 1.0;
  return std::max(1.4826 * numeric::UpperMedianAndMadInPlace(d).mad / std::sqrt(2.0), 0.3);
}

// a_noise: PatchNoise(a), computed when a was stored.
double RingNcc(const cv::Mat& a, double a_noise, const cv::Mat& b, int r_in) {
  const int R = a.cols / 2;
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x) {
      if (std::max(std::abs(x - R), std::abs(y - R)) <= r_in) continue;
      const double u = a.at<float>(y, x), v = b.at<float>(y, x);
      sa += u;
      sb += v;
      saa += u * u;
      sbb += v * v;
      sab += u * v;
      n += 1;
    }
  const double va = (saa - sa * sa / n) / n, vb = (sbb - sb * sb / n) / n;
  const double na = a_noise, nb = PatchNoise(b);
  const double signal_a = va - na * na, signal_b = vb - nb * nb;
  if (!(signal_a > kStructureSnr * na * na && signal_b > kStructureSnr * nb * nb)) return 1.0;
  const double ncc = (sab / n - sa * sb / (n * n)) / std::sqrt(va * vb);
  const double expected = std::sqrt(signal_a / va * signal_b / vb);
  return std::min(1.0, ncc / expected);
}

}  // namespace

struct PointsTracker::Point {
  std::size_t index = 0;
  std::string id;
  formats::PointMethod method{};
  std::unique_ptr<PointMeasurer> measurer;
  track::ImagePointMotion motion;
  bool started = false;
  bool tracking = false;        // the last frame was accepted
  double last_t = 0.0, miss_since = 0.0;
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
  cv::Mat context;              // surroundings at the last good frame (CV_32F, (2 r + 1)²)
  int context_inner = 0;
  double context_noise = 1.0;   // its pixel noise (PatchNoise)
  double typical_sigma = 0.0, typical_score = 0.0;  // of its accepted measurements (exponential mean)
  Eigen::Vector2d clean_z{0, 0};  // the last clean measurement (AcceptRow) ...
  std::vector<Claim> anchors;     // ... and the other points' clean ones in that frame (GroupPrediction)
  explicit Point(const PointsTrackOptions& o) : motion(o.motion) {}
};

PointsTracker::~PointsTracker() = default;

PointsTracker::PointsTracker(const formats::Seeds& seeds, const PointsTrackOptions& options) : opt_(options) {
  std::string why;
  if (!opt_.Check(&why)) throw UsageError(why);
  for (std::size_t i = 0; i < seeds.ids.size(); ++i) {
    auto p = std::make_unique<Point>(opt_);
    p->index = i;
    p->id = seeds.ids[i];
    PointSummary s;
    s.id = p->id;
    for (const formats::SeedRow& r : seeds.rows) {
      if (r.id == p->id) {
        p->method = r.method;
        p->measurer = MakePointMeasurer(r.method, r.size_px, opt_.measure);
        break;
      }
    }
    s.method = p->method;
    points_.push_back(std::move(p));
    summary_.push_back(s);
  }
  pending_ = seeds.rows;
  std::stable_sort(pending_.begin(), pending_.end(),
                   [](const formats::SeedRow& a, const formats::SeedRow& b) { return a.frame < b.frame; });
}

PointsFrameResult PointsTracker::Process(const cv::Mat& frame, std::int64_t frame_index, double t_s) {
  PointsFrameResult out;
  out.frame = frame_index;
  out.t_s = t_s;
  while (next_seed_ < pending_.size() && pending_[next_seed_].frame < frame_index) ++next_seed_;  // frames not processed
  std::vector<const formats::SeedRow*> here(points_.size(), nullptr);
  while (next_seed_ < pending_.size() && pending_[next_seed_].frame == frame_index) {
    const formats::SeedRow* r = &pending_[next_seed_++];
    for (const auto& p : points_) {
      if (p->id == r->id) here[p->index] = r;
    }
  }
  // The recording's shot noise, for the methods that propagate pixel noise: from the first frames until one
  // has enough levels to tell (a dark first frame says nothing).
  if (shot_tries_ < kShotNoiseFrames && shot_slope_ < 0) {
    ++shot_tries_;
    shot_slope_ = ShotNoiseSlope(frame);
    for (const auto& p : points_) p->measurer->SetShotNoise(std::max(0.0, shot_slope_));
  }
  // Points still tracking (and seeds) first, then the hidden ones: a re-acquisition knows where every other
  // point is in this frame (the group's prediction, and candidates that are another point).
  out.points.assign(points_.size(), PointRow{});
  claimed_.clear();
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& p : points_) {
      const bool hidden = p->started && !p->tracking && !here[p->index];
      if (hidden != (pass == 1)) continue;
      PointSummary& sum = summary_[p->index];
      PointRow row = Step(*p, frame, t_s, here[p->index], sum);
      ++sum.rows_by_status[static_cast<int>(row.status)];
      if (row.has_score) {
        sum.score_sum += row.score;
        ++sum.scored;
      }
      out.points[p->index] = row;
    }
  }
  // Each accepted point remembers where the others were in this frame (GroupPrediction).
  for (const Claim& mine : claimed_) {
    if (!mine.clean) continue;
    std::vector<Claim>& anchors = points_[mine.index]->anchors;
    anchors.clear();
    for (const Claim& c : claimed_) {
      if (c.index != mine.index && c.clean) anchors.push_back(c);
    }
  }
  return out;
}

PointRow PointsTracker::Step(Point& p, const cv::Mat& frame, double t_s, const formats::SeedRow* seed,
                             PointSummary& sum) {
  if (seed) {
    p.last_t = t_s;
    PointRow r = Reseed(p, frame, *seed, sum);
    if (!p.tracking) p.miss_since = t_s;
    return r;
  }
  if (!p.started) return PointRow{};  // before its first seed: lost, no position
  p.last_t = t_s;
  return Track(p, frame, sum);
}

PointRow PointsTracker::Reseed(Point& p, const cv::Mat& frame, const formats::SeedRow& seed, PointSummary& sum) {
  ++sum.seeds;
  const Eigen::Vector2d at(seed.x_px, seed.y_px);
  const PointMeasurement m = p.measurer->Seed(frame, at, seed.search_px.value_or(opt_.seed_search_px));
  p.started = true;
  if (!m.ok) {
    ++sum.seed_failures;
    seed_failures_.push_back({seed.line, p.id, m.why});
    // The user's position starts the motion (1 px²); the method's first measurement gives the velocity.
    p.motion.Start(at, Eigen::Matrix2d::Identity(), p.last_t);
    p.R = Eigen::Matrix2d::Identity();
    p.tracking = false;
    p.context.release();
    PointRow r;
    r.status = RowStatus::kInvalid;
    return r;
  }
  p.R = m.cov;
  p.R.diagonal().array() += kMinMeasVar;
  p.tracking = false;
  return AcceptRow(p, frame, m, false, true);
}

PointRow PointsTracker::Track(Point& p, const cv::Mat& frame, PointSummary& sum) {
  p.motion.PredictTo(p.last_t);
  const Eigen::Vector2d pred = p.motion.Predicted();
  const Eigen::Matrix2d S = p.motion.InnovationCovariance(p.R);
  const double spread = opt_.gate_sigma * std::sqrt(std::max(S(0, 0), S(1, 1)));
  // Until the filter has two measurements its velocity is a guess: the largest window, no χ² gate.
  const bool settling = !p.motion.settled();
  const double window = settling ? opt_.window_max_px : std::clamp(spread, opt_.window_min_px, opt_.window_max_px);
  if (p.tracking) {
    const PointMeasurement m = p.measurer->Measure(frame, pred, window);
    if (m.ok) {
      Eigen::Matrix2d R = m.cov;
      R.diagonal().array() += kMinMeasVar;
      // Its surroundings too: a marker that vanished and an identical one in its place are not one point.
      if (ContextScore(p, frame, m.px) >= opt_.context_min) {
        if (!settling && p.motion.Mahalanobis2(m.px, R) > opt_.gate_chi2) {
          // The same marker where the model did not expect it (a manoeuvre beyond --accel-sigma): the
          // motion restarts from its last two measurements.
          ++sum.restarts;
          p.motion.RestartFromLast();
        }
        return AcceptRow(p, frame, m, false, false);
      }
      ++sum.lookalikes_refused;  // the point itself is not seen: predicted, then lost
    }
    p.tracking = false;
    p.miss_since = p.last_t;
    return MissRow(p, false);
  }
  bool invalid = false;
  PointMeasurement m;
  // The whole frame (--reacquire-px 0), or at least that far about the prediction.
  const double reach = opt_.reacquire_px > 0 ? std::max(spread, opt_.reacquire_px) : std::max(frame.cols, frame.rows);
  if (Reacquire(p, frame, reach, &m, sum, &invalid)) {
    Eigen::Matrix2d R = m.cov;
    R.diagonal().array() += kMinMeasVar;
    const bool restart = p.motion.Mahalanobis2(m.px, R) > opt_.gate_chi2;
    if (restart) ++sum.restarts;
    return AcceptRow(p, frame, m, true, restart);
  }
  return MissRow(p, invalid);
}

bool PointsTracker::Reacquire(Point& p, const cv::Mat& frame, double search, PointMeasurement* out,
                              PointSummary& sum, bool* invalid) {
  const bool has_context = !p.context.empty();
  // Where the other points say it is: a candidate there is the point, whatever its surroundings look like
  // (a cloud still over part of them); elsewhere its surroundings must match. With that place known, only
  // about it is searched (a point that is not there is still hidden, and the search is small).
  Eigen::Vector2d group_px;
  double group_tol = 0.0;
  Eigen::Matrix2d group_change;
  const bool grouped = GroupPrediction(p, &group_px, &group_tol, &group_change);
  if (grouped) p.measurer->PredictChange(group_change);
  const std::vector<PointCandidate> cands =
      grouped ? p.measurer->Candidates(frame, group_px, std::min(search, group_tol + kGroupSearchMarginPx), 8)
              : p.measurer->Candidates(frame, p.motion.Predicted(), search, 8);
  double best = -2, second = -2;
  for (const PointCandidate& c : cands) {
    const PointMeasurement m = p.measurer->Measure(frame, c.px, 2.0);
    if (!m.ok) continue;
    // A candidate measured much worse than the point usually is (clutter the method half fits) is not it.
    if (p.typical_sigma > 0 && (std::sqrt(0.5 * m.cov.trace()) > kReacquireSigmaRatio * p.typical_sigma ||
                                m.score < kReacquireScoreRatio * p.typical_score)) {
      continue;
    }
    // Another point measured here this frame (an identical marker elsewhere on the target): not this one.
    bool taken = false;
    for (const Claim& q : claimed_) taken = taken || (q.px - m.px).norm() < kClaimedPx;
    if (taken) continue;
    const bool at_group = grouped && (m.px - group_px).norm() <= group_tol;
    const double ctx = at_group ? kGroupScore : ContextScore(p, frame, m.px);
    if (ctx < opt_.context_min) {
      ++sum.lookalikes_refused;
      continue;
    }
    if ((m.px - out->px).norm() < 1.0 && best > -2) continue;  // the same marker found twice
    if (ctx > best) {
      second = best;
      best = ctx;
      *out = m;
    } else if (ctx > second) {
      second = ctx;
    }
  }
  if (best <= -2) return false;
  if (second > best - 0.05 && has_context) {
    ++sum.ambiguous;
    *invalid = true;
    return false;
  }
  // Measured again: the measurer keeps what it learns (angles, radius, warp) from its last measurement, which
  // must be the chosen candidate's, not the last one looked at.
  const PointMeasurement again = p.measurer->Measure(frame, out->px, 1.0);
  if (!again.ok) return false;
  *out = again;
  return true;
}

bool PointsTracker::GroupPrediction(const Point& p, Eigen::Vector2d* px, double* tolerance_px,
                                    Eigen::Matrix2d* change) const {
  Eigen::Matrix2Xd then(2, p.anchors.size()), now(2, p.anchors.size());
  Eigen::Index n = 0;
  for (const Claim& a : p.anchors) {
    for (const Claim& c : claimed_) {
      if (c.index != a.index || !c.clean) continue;
      then.col(n) = a.px;
      now.col(n) = c.px;
      ++n;
    }
  }
  if (n < kGroupMin) return false;
  then.conservativeResize(2, n);
  now.conservativeResize(2, n);
  // The least-squares similarity (Umeyama 1991; in 2-D a complex factor, closed form). Eigen::umeyama does
  // the same, but GCC 12 warns (-Wstringop-overread, a false positive) inside it.
  const Eigen::Vector2d mt = then.rowwise().mean(), mn = now.rowwise().mean();
  double sxx = 0, c = 0, d = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d u = then.col(i) - mt, v = now.col(i) - mn;
    sxx += u.squaredNorm();
    c += u.dot(v);
    d += u.x() * v.y() - u.y() * v.x();
  }
  if (!(sxx > 0)) return false;
  Eigen::Matrix2d A;
  A << c / sxx, -d / sxx, d / sxx, c / sxx;
  const Eigen::Vector2d b = mn - A * mt;
  const double rms = std::sqrt(((A * then).colwise() + b - now).squaredNorm() / static_cast<double>(n));
  if (!(rms <= kGroupMaxRmsPx)) return false;
  *px = A * p.clean_z + b;
  *change = A;
  *tolerance_px = kGroupTolPx + kGroupTolSigmas * rms;
  return true;
}

double PointsTracker::ContextScore(Point& p, const cv::Mat& frame, const Eigen::Vector2d& px) {
  if (p.context.empty()) return 1.0;
  const int R = p.context.cols / 2;
  const int ix = static_cast<int>(std::lround(px.x())), iy = static_cast<int>(std::lround(px.y()));
  if (!CopyFloatRoi(frame, cv::Rect(ix - R, iy - R, 2 * R + 1, 2 * R + 1), &patch_)) return 1.0;  // at the border
  return RingNcc(p.context, p.context_noise, patch_, p.context_inner);
}

PointRow PointsTracker::AcceptRow(Point& p, const cv::Mat& frame, const PointMeasurement& m, bool reacquired,
                                  bool restart) {
  Eigen::Matrix2d R = m.cov;
  R.diagonal().array() += kMinMeasVar;
  if (restart) {
    p.motion.Start(m.px, R, p.last_t);
  } else {
    p.motion.Update(m.px, R, p.last_t);
  }
  p.R = R;
  p.tracking = true;
  // A measurement as good as the point's usual (not one half under a cloud's edge, whose position drifts)
  // is what the method learns the appearance from and what the group's prediction starts from.
  const double sig = std::sqrt(0.5 * m.cov.trace());
  const bool clean = !(p.typical_sigma > 0) || (m.score >= kCleanScoreRatio * p.typical_score &&
                                                sig <= kCleanSigmaRatio * p.typical_sigma);
  // The point's usual measurement quality (exponential mean over its accepted rows).
  const double w = p.typical_sigma > 0 ? kTypicalWeight : 1.0;
  p.typical_sigma = (1 - w) * p.typical_sigma + w * sig;
  p.typical_score = (1 - w) * p.typical_score + w * m.score;
  claimed_.push_back({p.index, m.px, clean});
  if (clean) {
    p.measurer->Accept(m);
    p.clean_z = m.px;
  }
  // The surroundings, for telling this point from a look-alike after it was hidden.
  const int inner = p.measurer->SupportHalfPx();
  const int outer = std::clamp(2 * inner, inner + 6, inner + 40);
  const int ix = static_cast<int>(std::lround(m.px.x())), iy = static_cast<int>(std::lround(m.px.y()));
  cv::Mat ctx;
  if (CopyFloatRoi(frame, cv::Rect(ix - outer, iy - outer, 2 * outer + 1, 2 * outer + 1), &ctx)) {
    p.context = ctx;
    p.context_noise = PatchNoise(ctx);
    p.context_inner = inner;
  }
  PointRow r;
  r.status = reacquired ? RowStatus::kReacquired : RowStatus::kOk;
  r.has_xy = true;
  r.px = m.px;
  r.sigma_px = m.cov.diagonal().cwiseSqrt();
  r.score = m.score;
  r.has_score = true;
  return r;
}

PointRow PointsTracker::MissRow(Point& p, bool invalid) {
  PointRow r;
  const Eigen::Matrix2d S = p.motion.InnovationCovariance(Eigen::Matrix2d::Zero());
  const double sigma = std::sqrt(std::max(S(0, 0), S(1, 1)));
  if (invalid) {
    r.status = RowStatus::kInvalid;
  } else if (sigma <= opt_.predict_max_sigma_px && p.last_t - p.miss_since <= opt_.predict_max_gap_s) {
    r.status = RowStatus::kPredicted;
    r.has_xy = true;
    r.px = p.motion.Predicted();
    r.sigma_px = S.diagonal().cwiseSqrt();
  } else {
    r.status = RowStatus::kLost;
  }
  return r;
}

}  // namespace rk::extract

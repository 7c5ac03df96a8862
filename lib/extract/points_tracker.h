// rk-extract points: any number of user-seeded points tracked through a recording, each with its own method
// (point_measure.h) and motion model.
//
// Per point, per frame:
//   1. A seeds-file row at this frame (re)starts the point: its measurer learns the appearance there and
//      measures it within ±search_px (seeds `search_px`, else --seed-search); the row is `ok` (or `invalid`
//      with the user's position kept as the filter's start, when the method finds nothing there).
//   2. Otherwise the image motion model (track/image_motion.h: a Singer filter per axis, shared with
//      rk-extract features) predicts
//      the point; the search half-width is gate_sigma · √S (S the innovation covariance with the last
//      measurement's own covariance), within [--window-min, --window-max] px.
//   3. While tracking, the nearest good match in the window is accepted (`ok`) and updates the filter with
//      its own 2×2 covariance; one whose Mahalanobis d² exceeds gate_chi2 (a manoeuvre the model did not
//      expect) restarts the motion from the point's last two measurements. The filter's velocity comes from
//      the first two measurements after a seed (a high-speed camera's image velocity is beyond any prior).
//   4. After a frame without one (hidden by a cloud, by the target's own wing, out of the frame, blurred)
//      the point is `predicted` (the filter's position and σ = √diag S with R = 0) while that σ is below
//      --predict-max-sigma and the gap shorter than --predict-max-gap, then `lost` (no position).
//      Every accepted match, also while tracking, must have surroundings like the point's (below): an
//      identical marker that appears where the hidden one was predicted is not taken for it.
//      Re-acquisition looks at every candidate of the method in the whole frame (or ±--reacquire-px of the
//      prediction), not only the nearest, so a point that moved anywhere while hidden (a reversal) is found
//      the frame it returns; a candidate another point measured in this frame is that point, not this one.
//      Hidden points are looked for after the others, so each knows where the rest of the target is: when
//      at least 3 other points were measured both in the point's last good frame and in this one and one
//      similarity (shift, rotation, scale) carries them from there to here within 1 px RMS (they move as one
//      body), that similarity applied to the point's last position is where the target carried it, and its
//      rotation and scale are given to the method (a correlation template turned and grown while hidden); a
//      candidate within 1 px + 4 × that RMS of it is the point, and only ±(that + 4 px) about it is searched.
//      The place is carried from the point's last clean measurement (score and σ as good as its usual: not one
//      degrading under a cloud's edge), which alone teaches the method the appearance. Any other candidate is taken only if its
//      surroundings (the ring between the method's support and twice it, where a look-alike marker differs
//      from the real one) correlate with those stored at the point's last good frame (NCC ≥
//      --context-min), the best such; two nearly equal (within 0.05) are ambiguous and give `invalid`; a
//      candidate whose surroundings do not match (a look-alike) is refused and counted, and the point stays
//      predicted or lost. (The surroundings alone fail while a cloud still covers part of them: the group
//      re-acquires such a marker the frame it comes out.)
//      The first accepted row after a miss is `reacquired`; one outside the gate restarts the filter.
// σ per row: the method's own (point_measure.h), written as sigma_x_px, sigma_y_px; score the method's.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "extract/point_measure.h"
#include "formats/seeds.h"
#include "io/json_util.h"
#include "io/options.h"
#include "io/row_status.h"
#include "track/image_motion.h"

namespace rk::extract {

struct PointsTrackOptions {
  PointMeasureOptions measure;
  track::ImageMotionOptions motion;     // --maneuver-time, --accel-sigma, --init-vel-sigma
  double gate_sigma = 4.0;              // search half-width in innovation sigmas
  double gate_chi2 = 18.4;              // Mahalanobis gate d² (2 dof, 99.99 %)
  double window_min_px = 3.0;           // search half-width bounds while tracking (px)
  double window_max_px = 40.0;
  double reacquire_px = 0.0;            // re-acquisition searches ±this about the prediction at least (px);
                                        // 0: the whole frame
  double seed_search_px = 3.0;          // search at a seed without search_px (px)
  double context_min = 0.5;             // NCC of the surroundings needed to re-acquire
  double predict_max_sigma_px = 5.0;    // `predicted` while the prediction's 1σ is below this (px) ...
  double predict_max_gap_s = 0.5;       // ... and the gap shorter than this (s); then `lost`

  static const io::OptionTable<PointsTrackOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
};

struct PointRow {
  RowStatus status = RowStatus::kLost;
  bool has_xy = false;
  Eigen::Vector2d px{0, 0};
  Eigen::Vector2d sigma_px{0, 0};
  double score = 0.0;
  bool has_score = false;
};

struct PointsFrameResult {
  std::int64_t frame = 0;
  double t_s = 0.0;
  std::vector<PointRow> points;  // one per id, in the seeds file's order of first appearance
};

struct PointSummary {
  std::string id;
  formats::PointMethod method = formats::PointMethod::kCorrelation;
  std::int64_t rows_by_status[5] = {0, 0, 0, 0, 0};  // RowStatus order
  std::int64_t seeds = 0, seed_failures = 0, restarts = 0, lookalikes_refused = 0, ambiguous = 0;
  double score_sum = 0.0;
  std::int64_t scored = 0;
};

class PointsTracker {
 public:
  PointsTracker(const formats::Seeds& seeds, const PointsTrackOptions& options);
  ~PointsTracker();
  PointsTracker(const PointsTracker&) = delete;
  PointsTracker& operator=(const PointsTracker&) = delete;
  PointsFrameResult Process(const cv::Mat& frame, std::int64_t frame_index, double t_s);
  const std::vector<PointSummary>& summary() const { return summary_; }
  // Seed rows whose method found nothing at the seed (line, id, why), for warnings.
  struct SeedFailure {
    std::size_t line = 0;
    std::string id, why;
  };
  const std::vector<SeedFailure>& seed_failures() const { return seed_failures_; }

 private:
  struct Point;
  PointRow Step(Point& p, const cv::Mat& frame, double t_s, const formats::SeedRow* seed, PointSummary& sum);
  PointRow Reseed(Point& p, const cv::Mat& frame, const formats::SeedRow& seed, PointSummary& sum);
  PointRow Track(Point& p, const cv::Mat& frame, PointSummary& sum);
  bool Reacquire(Point& p, const cv::Mat& frame, double search, PointMeasurement* m, PointSummary& sum, bool* invalid);
  PointRow AcceptRow(Point& p, const cv::Mat& frame, const PointMeasurement& m, bool reacquired, bool restart);
  PointRow MissRow(Point& p, bool invalid);
  // NCC of the ring around px (between the method's support and twice it) with the point's at its last good
  // frame; 1 when there is nothing to compare.
  double ContextScore(Point& p, const cv::Mat& frame, const Eigen::Vector2d& px);

  PointsTrackOptions opt_;
  std::vector<std::unique_ptr<Point>> points_;
  std::vector<formats::SeedRow> pending_;  // the seed rows (a copy) in frame order
  std::size_t next_seed_ = 0;
  std::vector<PointSummary> summary_;
  std::vector<SeedFailure> seed_failures_;
  struct Claim {
    std::size_t index = 0;
    Eigen::Vector2d px{0, 0};
    bool clean = true;  // as good as the point's usual measurement (AcceptRow)
  };
  // Where the point's group puts it now: the similarity (shift, rotation, scale) that carries the other points
  // from the point's last good frame to this one, applied to its last position; false without at least
  // kGroupMin of them there and here, or when they did not move as one body. *change: the similarity's
  // linear part (rotation and scale since then).
  bool GroupPrediction(const Point& p, Eigen::Vector2d* px, double* tolerance_px, Eigen::Matrix2d* change) const;
  std::vector<Claim> claimed_;  // the points measured so far in this frame
  double shot_slope_ = -1.0;              // the recording's shot noise (DN² per DN), −1 until known
  int shot_tries_ = 0;
  cv::Mat patch_;
};

}  // namespace rk::extract

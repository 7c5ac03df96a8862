// Frame-to-frame tracking of the target's markers with identities consistent with the target
// model (rk-extract features).
//
// Acquisition (no identities yet, or identities lost): every marker candidate of the frame is
// detected and measured (features_detect.h) and identified against the model
// (features_identify.h). Refused identifications (ambiguous, too few markers) leave the frame
// without points; the next frame tries again.
// Tracking: each identified marker is predicted by the image motion model rk-extract points uses
// (track/image_motion.h: a Singer filter per axis whose velocity starts from two consecutive
// measurements; before that, the last position), searched by correlation within search_px + search_speed_factor · |predicted
// motion| of the prediction, and measured by least-squares correlation. Then the constellation
// is checked: an affine camera is fitted to the measured markers (≥ 5, or ≥ 4 for a planar
// model) and a marker farther than gate_frac × (the smallest separation of the predicted
// markers) from its fitted position is rejected for this frame (status invalid, values empty):
// a marker that jumped onto a neighbour, a glint, or a swap never passes silently. Markers not
// measured (hidden, lost) are searched again at their position predicted by the fitted affine
// camera, and accepted (status reacquired) only within half the gate of that prediction. When
// fewer than min_track markers are measured, the identities are dropped and the next frame
// acquires again.
// Per frame and per model id one point, status (SPEC.md §2): ok, reacquired (measured after
// frames without), invalid (measured but rejected by the constellation check), lost.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "extract/features_detect.h"
#include "extract/features_identify.h"
#include "io/row_status.h"
#include "target/feature_model.h"
#include "track/image_motion.h"

namespace rk::extract {

struct FeatureTrackOptions {
  MarkerDetectOptions detect;
  IdentifyOptions identify;
  double search_px = 12.0;            // search half-size around a prediction (px), > 0
  double search_speed_factor = 0.5;   // + this × predicted image motion since the last frame, ≥ 0
  double gate_frac = 0.25;            // constellation gate / smallest predicted separation, (0, 0.5]
  double gate_min_px = 3.0;           // smallest gate (px), > 0
  int min_track = 4;                  // fewer measured markers → re-acquire, ≥ 3
  double coast_s = 0.5;               // a marker unseen for longer is predicted from the constellation only (s)

  // The command-line options of rk-extract features: detect's, the tracker's, identify's (io/options.h).
  static const io::OptionTable<FeatureTrackOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
};

struct FeaturePoint {
  RowStatus status = RowStatus::kLost;
  bool has_xy = false;
  Eigen::Vector2d px{0, 0};
  double sigma_px = 0.0;
  double ncc = 0.0;
  double radius_px = 0.0;
  double edge_px = 0.0;   // fitted edge blur s (not written)
};

struct FeatureFrameResult {
  std::int64_t frame = 0;
  double t_s = 0.0;
  std::vector<FeaturePoint> points;   // per model id (target::FeatureModel order)
  bool acquisition = false;           // full-frame identification ran in this frame
  bool ambiguous = false;             // ... and was refused as ambiguous
};

struct FeatureTrackSummary {
  std::int64_t frames = 0;
  std::array<std::int64_t, 5> rows_by_status{};  // indexed by RowStatus
  std::int64_t acquisitions = 0;                 // full-frame identifications tried
  std::int64_t acquisitions_ok = 0;
  std::int64_t ambiguous = 0;                    // refused as ambiguous
  std::int64_t rejected = 0;                     // points rejected by the constellation check
  std::int64_t frames_with_4 = 0;                // frames with ≥ 4 measured points (a pose is possible)
  double mean_ncc = 0.0;                         // over measured points
  double ncc_sum = 0.0;
  std::int64_t measured = 0;
};

class FeatureTracker {
 public:
  FeatureTracker(const target::FeatureModel& model, const FeatureTrackOptions& options);
  FeatureFrameResult Process(const cv::Mat& frame, std::int64_t index, double t_s);
  const FeatureTrackSummary& summary() const { return summary_; }

 private:
  struct MarkerTrack {
    bool has_pos = false;
    Eigen::Vector2d pos{0, 0};             // the last measurement (px)
    track::ImagePointMotion motion;        // its image motion (velocity from two consecutive measurements)
    bool fresh = true;                     // the next measurement starts the motion again
    double last_t = 0.0;
    double radius = 0.0, edge = 1.0;
    bool ever = false;                     // measured at least once
    bool lost = true;                      // not measured in the last frame
  };
  void Acquire(double t_s, FeatureFrameResult* out);
  void TrackMarkers(double t_s, FeatureFrameResult* out);
  void Accept(std::size_t id, const MarkerMeasurement& m, double t_s, FeatureFrameResult* out);
  bool FitConstellation(const FeatureFrameResult& r, Eigen::Matrix<double, 2, 4>* A, double* gate) const;

  const target::FeatureModel& model_;
  FeatureTrackOptions opt_;
  MarkerDetector detector_;
  AffineCameraModel affine_;
  std::vector<MarkerTrack> tracks_;
  bool locked_ = false;
  FeatureTrackSummary summary_;
};

}  // namespace rk::extract

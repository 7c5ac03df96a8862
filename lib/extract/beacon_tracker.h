// Beacon tracking over a frame sequence, seed 001 §2.2 (Guan et al. 2014):
// a Singer-model Kalman filter (track/singer.h) per image axis predicts the
// beacon position so that only a gated window around the prediction is
// searched; the template (NCC) validates identity; occlusions are handled as in
// the paper, except that a lost beacon is searched for in the whole frame at
// once (full-frame acquisition costs ≈ 1 ms per 5-Mpixel frame,
// docs/benchmarks.md), because the image motion may turn while the beacon is
// hidden (a turret catching up) and carry any prediction the wrong way.
//
// Per frame (time t_k):
//   no track yet  → full-frame acquisition (beacon_detect.h, grey projection);
//                   without a template the candidate with the largest
//                   signal-weighted size (a lamp cluster is wider than a single
//                   glint) among those with flux ≥ min_flux is taken.
//   tracking      → predict to t_k; search window = prediction ± (gate_sigma·√S_ii
//                   + template half size), clamped to [min_window, max_window];
//                   accept the candidate with the smallest Mahalanobis distance
//                   d² ≤ gate_chi2 whose NCC with the template ≥ ncc_track and whose
//                   size ratio to the template is within size_ratio → status ok;
//                   candidates that fail the checks → invalid; none → lost.
//                   When the window would exceed max_window: full-frame search
//                   gated by d² ≤ gate_chi2.
//   lost (any length) → re-acquisition: the window grown with the prediction
//                   covariance (while it fits max_window and the loss is shorter
//                   than long_loss_s), and, when it holds no match, the whole
//                   frame in the same frame. A candidate must pass the identity
//                   checks of the template saved before the loss: NCC ≥
//                   ncc_reacquire, size ratio within size_ratio, flux ratio within
//                   flux_ratio (a glint of the right shape is far fainter or
//                   brighter than the cluster); no Mahalanobis gate, so a wrong
//                   prediction cannot keep the beacon out. Among the matches the
//                   one with the smallest d² wins. The filter restarts at the
//                   measurement after a long loss or when d² > gate_chi2 (the
//                   motion did not follow the model), else it is updated.
//   just restarted → for the next kSettleUpdates measurements the velocity is not
//                   known yet: a window without a match falls back to the same
//                   identity-checked full-frame search (status ok).
//   The first accepted frame after a loss has status `reacquired`.
// Position of an accepted cluster: the per-lamp estimator (beacon_lamps.h) when
// its lamps resolve (sparse cluster), else the cluster centroid; the per-lamp
// share averages restart with the filter.
// While tracking nothing outside the gate is accepted, so a distractor outside
// the window can never capture the track; while lost only a candidate that
// matches the template in shape, size and flux can. Frames without an accepted
// measurement get `lost` (or `predicted`, with the prediction, when
// fill_gaps_s > 0 and the gap is shorter than that).
// No heap allocation per frame in tracking mode once buffers are warm.
#pragma once

#include "io/row_status.h"

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "extract/beacon_detect.h"
#include "extract/beacon_lamps.h"
#include "track/singer.h"

namespace rk::extract {

using BeaconStatus = RowStatus;  // SPEC.md §2 statuses (io/row_status.h)
inline const char* BeaconStatusName(BeaconStatus s) { return RowStatusName(s); }

struct BeaconTrackOptions {
  DetectOptions detect;
  double maneuver_time_s = 1.0;     // Singer τ_m (s)
  double accel_sigma_px_s2 = 100.0; // Singer σ_m, RMS image acceleration (px/s²)
  double meas_sigma_px = 0.1;       // centroid measurement noise in the filter (px)
  double init_vel_sigma_px_s = 50.0;// velocity uncertainty at (re)acquisition (px/s)
  double gate_sigma = 5.0;          // window half size in innovation sigmas
  double gate_chi2 = 25.0;          // Mahalanobis gate d² (2 dof)
  int min_window_px = 12;           // window half size bounds (px)
  int max_window_px = 96;
  double ncc_track = 0.6;           // NCC needed while tracking
  double ncc_reacquire = 0.75;      // NCC needed to re-acquire after a loss
  double ncc_template_update = 0.8; // template replaced by the current patch when NCC ≥ this
  double size_ratio = 1.8;          // candidate size / template size within [1/r, r]
  double flux_ratio = 2.0;          // re-acquisition: candidate flux / template flux within [1/r, r]
  double long_loss_s = 1.0;         // losses at least this long → full-frame re-detection
  double min_flux_dn = 0.0;         // acquisition: minimum flux (DN·px); 0 = any
  double fill_gaps_s = 0.0;         // > 0: frames of gaps shorter than this get `predicted`
  bool per_lamp = true;             // position from the per-lamp estimator (beacon_lamps.h) when the
                                    // lamps resolve; false: always the cluster centroid
  // The command-line options of rk-extract beacon, detect's first (io/options.h).
  static const io::OptionTable<BeaconTrackOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
};

struct BeaconFrameResult {
  std::int64_t frame = 0;
  double t_s = 0.0;
  BeaconStatus status = BeaconStatus::kLost;
  bool has_xy = false;      // x/y written (ok, reacquired, predicted)
  double x_px = 0.0, y_px = 0.0;
  double sigma_x_px = 0.0, sigma_y_px = 0.0;
  bool has_spot = false;    // peak/area/ncc available (a measurement was made)
  double peak_dn = 0.0;
  int area_px = 0;
  double ncc = 0.0;         // NaN-free: valid only when has_ncc
  bool has_ncc = false;
  bool per_lamp = false;    // x/y from the per-lamp estimator (else the cluster centroid)
};

struct BeaconTrackSummary {
  std::int64_t frames = 0;
  std::int64_t ok = 0, reacquired = 0, lost = 0, predicted = 0, invalid = 0;
  std::int64_t acquisitions = 0;       // full-frame acquisitions that succeeded
  std::int64_t full_frame_searches = 0;
  std::int64_t per_lamp = 0;           // measured frames whose position came from the per-lamp estimator
  std::int64_t restarts = 0;           // re-acquisitions that restarted the filter (far from the prediction)
  double ncc_sum = 0.0;
  std::int64_t ncc_count = 0;
  double mean_ncc() const { return ncc_count ? ncc_sum / static_cast<double>(ncc_count) : 0.0; }
};

class BeaconTracker {
 public:
  explicit BeaconTracker(const BeaconTrackOptions& opt);
  // Processes one frame (CV_8UC1 or CV_16UC1) taken at t_s (non-decreasing).
  BeaconFrameResult Process(const cv::Mat& frame, std::int64_t frame_index, double t_s);
  const BeaconTrackSummary& summary() const { return summary_; }
  const SpotTemplate& current_template() const { return template_; }

 private:
  enum class Mode { kAcquire, kTrack, kLostShort, kLostLong };
  bool AcquireInitial(const cv::Mat& frame, SpotMeasurement* best);
  // Identity checks of a candidate against the template (NCC, size, and when
  // re-acquiring flux); *ncc receives the NCC.
  bool Matches(const cv::Mat& frame, const SpotMeasurement& c, bool reacquire, double* ncc);
  void Accept(const cv::Mat& frame, const SpotMeasurement& m, double ncc, bool restart, BeaconFrameResult* r);
  void Miss(bool invalid, BeaconFrameResult* r);

  BeaconTrackOptions opt_;
  SpotDetector det_;
  track::SingerFilter<2> kf_;
  SpotTemplate template_;
  LampEstimator lamps_;
  Mode mode_ = Mode::kAcquire;
  double last_t_s_ = 0.0;
  bool have_time_ = false;
  double lost_since_s_ = 0.0;
  int updates_since_restart_ = 0;  // measurements accepted since the filter (re)started
  bool have_prediction_ = false;
  std::vector<SpotMeasurement> cand_;
  BeaconTrackSummary summary_;
};

}  // namespace rk::extract

// Identification of detected markers with the ids of the target model, without a camera
// model (rk-extract features knows only the video and the target): hypothesise-and-verify with
// an affine camera.
//
// Model: a target small against its range is imaged by an affine camera
//   x_i ≈ A · (q_i, 1),   q_i = Eᵀ (p_i − p̄)  (model points in their principal axes),
// A a 2×4 matrix (8 dof); for a planar or near-planar model (λ3/λ1 < planar_ratio) the
// out-of-plane coordinate is dropped and A is 2×3 (6 dof). The perspective error of this model
// is about f · |x| · |z| / R² (target half-size x, depth z, range R): a few pixels for seed 001's
// geometry, far below the marker separation.
// Hypotheses: a basis of k model points (k = 4, or 3 planar; the bases with the largest
// volume / area, and for each basis point one basis without it, so that one hidden marker does
// not stop identification) and every ordered k-tuple of distinct detections give an exact A.
// Non-planar hypotheses must look like a weak-perspective camera (rows of the 2×3 part of equal
// length within max_aspect and nearly orthogonal, |cos| < max_skew_cos), which rejects most
// wrong ones. A hypothesis predicts every model point; a detection within tol of a prediction
// is an inlier (nearest first, each detection used once), tol = max(tol_min_px, tol_frac ×
// the smallest distance between two predicted points). The best hypothesis (most inliers, then
// smallest residual) is refined by least squares on its inliers and re-matched.
// Never a silent swap: if another assignment with as many inliers fits nearly as well (refined
// RMS within ambiguity_ratio) the identification is refused as ambiguous (e.g. a mirror-
// symmetric marker layout seen from its plane of symmetry). At least min_identified markers
// must be identified (≥ 5 non-planar, ≥ 4 planar: the minimal basis alone cannot be verified).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "io/options.h"
#include "target/feature_model.h"

namespace rk::extract {

struct IdentifyOptions {
  int min_identified = 5;          // ≥ 4; a planar model needs 4, a non-planar one 5 (raised to)
  double tol_frac = 0.25;          // inlier tolerance / smallest predicted separation, (0, 0.5]
  double tol_min_px = 3.0;         // smallest inlier tolerance (px), > 0
  double max_aspect = 1.6;         // weak-perspective check: row-length ratio, > 1
  double max_skew_cos = 0.4;       // weak-perspective check: |cos| between the rows, (0, 1]
  double ambiguity_ratio = 2.0;    // refused if a rival's RMS < ratio × best RMS + 0.5 px, ≥ 1
  double planar_ratio = 0.05;      // λ3/λ1 below which the model is treated as planar
  int max_bases = 6;               // bases tried, ≥ 1
  int max_detections = 16;         // strongest detections considered, ≥ 4

  // The command-line options of rk-extract features' identification (io/options.h).
  static const io::OptionTable<IdentifyOptions>& Table();
  bool Check(std::string* why) const;
};

// Affine camera: image = A · (q, 1) with q in the model's principal axes (planar: last
// coordinate ignored). Built for one model.
class AffineCameraModel {
 public:
  explicit AffineCameraModel(const target::FeatureModel& model, double planar_ratio = 0.05);
  bool planar() const { return planar_; }
  std::size_t size() const { return q_.size(); }
  const Eigen::Vector3d& q(std::size_t i) const { return q_[i]; }
  // Least-squares A from matched (model index, pixel) pairs; false if too few / degenerate.
  bool Fit(const std::vector<int>& model_index, const std::vector<Eigen::Vector2d>& px,
           Eigen::Matrix<double, 2, 4>* A) const;
  Eigen::Vector2d Predict(const Eigen::Matrix<double, 2, 4>& A, std::size_t i) const;

 private:
  bool planar_ = false;
  std::vector<Eigen::Vector3d> q_;
};

struct Identification {
  bool ok = false;
  std::string why;                       // when not ok
  std::vector<int> detection_of_model;   // per model point: index into the detections, or −1
  int identified = 0;
  double rms_px = 0.0;                   // residual of the refined affine fit
  double tol_px = 0.0;                   // inlier tolerance used
  bool ambiguous = false;
  Eigen::Matrix<double, 2, 4> A = Eigen::Matrix<double, 2, 4>::Zero();
  long hypotheses = 0;                   // tried (for reports)
};

Identification Identify(const std::vector<Eigen::Vector2d>& detections, const target::FeatureModel& model,
                        const AffineCameraModel& affine, const IdentifyOptions& options);

}  // namespace rk::extract

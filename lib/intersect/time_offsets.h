// rk-intersect --estimate-time-offsets (SPEC.md §7, docs/rk-intersect.md "Clock offsets"): each station's clock
// offset against the reference station's, estimated jointly with the trajectory, with its 1σ.
//
// Model. The target's path in the origin ENU frame is a uniform cubic B-spline in time per target (knots every
// h s; p(τ) = Σ_{m=0..3} B_m(u) c_{i+m} with τ = t0 + (i + u) h), and station s's clock reads t_s = τ − δ_s:
// every usable row of every station (its own time t, azimuth, elevation, range where it has one, their σ and
// az–el correlation) is one observation of p(t + δ_s) through the station's line-of-sight model
// (solver.h Predict, whitened by NormalisedResiduals). Each row enters once, at its own time: no
// interpolation between a station's frames and no re-intersection at output times, so the normal matrix
// counts every frame once and the offsets' covariance is the real one.
// Unknowns: the control points of every target and δ_s of every station but the reference
// (formats::StationsFile::TimeReference, whose δ is 0 by definition). The stations' starting offsets (their
// time_offset_s) are applied first; δ is the correction to them.
// Priors (pseudo-observations, in the normal matrix and in the σ): the path's acceleration, the second
// difference of the control points over h², is 0 ± accel_sigma (a weak smoothness prior that holds the
// path where one station alone sees it and between frames; 100 m/s² by default, beyond any aircraft
// manoeuvre's error over one knot), and each correction is 0 ± 1 s (no effect unless the geometry gives no
// information at all, where it keeps the system solvable and the σ honestly of the order of a second).
// Solution: Ceres Levenberg–Marquardt (sparse normal Cholesky), first with the offsets held at their starting
// values (the residuals "as given", which the report compares), then with them free. A row whose time moves
// to another knot span while δ changes is re-assigned and the problem solved again.
// Covariance: of the corrections, from the whole normal matrix (JᵀJ, Eigen's sparse LDLT, columns of the
// offsets solved), scaled by χ²/dof when above 1 (what the spline and the σ columns do not describe is then
// in the σ, not hidden). Poorly determined: an offset whose σ exceeds poor_inflation × the σ it would have
// if the path were known (a time shift and a path shift look alike: stations on a line and a straight pass
// along it) gets a warning in words; so does one whose σ exceeds half its station's frame interval.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "formats/stations.h"
#include "intersect/station_track.h"
#include "io/json_util.h"

namespace rk::intersect {

struct TimeOffsetOptions {
  double knot_interval_s = 0.0;   // h; 0: 4 × the slowest station's median frame interval, within [0.1, 1] s
  double accel_sigma_mps2 = 100.0;  // the smoothness prior
  double correction_sigma_s = 1.0;  // the corrections' prior
  double poor_inflation = 5.0;    // warn when σ exceeds this × the σ with the path known
  int max_iterations = 100;
};

// One target (the beacon, or one point id): the tracks that saw it, each with its station's index.
struct OffsetTarget {
  std::vector<int> station;
  std::vector<const StationTrack*> track;  // built with the stations' starting offsets applied
};

struct TimeOffsetFit {
  std::vector<std::string> names;
  std::size_t reference = 0;
  std::vector<double> start_s;       // per station: the starting offset (time_offset_s)
  std::vector<double> offset_s;      // the estimate: start + correction (the reference's is its start)
  std::vector<double> sigma_s;       // 1σ (0 for the reference)
  std::vector<double> sigma_known_s; // the σ it would have if the path were known (information of its own rows)
  std::vector<std::size_t> rows;     // observations per station
  Eigen::MatrixXd correlation;       // stations × stations (the reference's row and column 0, diagonal 1)
  std::vector<std::string> warnings; // poorly determined offsets, in words
  double rms_arcsec_as_given = 0.0;  // angle residual RMS (az·cos el and el) with the starting offsets
  double rms_arcsec_estimated = 0.0; // and with the estimated ones
  double chi2_per_dof = 0.0;
  double sigma_scale = 1.0;          // √max(1, χ²/dof) applied to the σ
  double knot_interval_s = 0.0;
  std::size_t observations = 0, parameters = 0;
  int iterations = 0;

  // The report's "time_offsets": per station {offset_s, sigma_s, reference, start_s, rows, sigma_if_path_known_s};
  // and "time_offset_fit": correlation (by station), residual RMS as given and estimated, χ²/dof, knots, warnings.
  io::Json OffsetsJson() const;
  io::Json FitJson() const;
};

// Estimates the offsets of every station against stations.TimeReference(). Throws DataError (naming
// stations.json) when no target has two stations' rows at overlapping times, ProcessingError when the
// solver fails.
TimeOffsetFit EstimateTimeOffsets(const formats::StationsFile& stations, const std::vector<OffsetTarget>& targets,
                                  const TimeOffsetOptions& options);

namespace internal {
// Tests: the worst difference between one row's analytic Jacobian (residuals z(az, el, range) with respect to its
// four control points and its station's correction) and central differences, over the largest entry of that
// residual's row. `c`: the four control points, `delta` the correction, the row's knot span starting at t0.
double RowJacobianMismatch(const StationFrame& frame, const LineObservation& o, double t_s,
                           const Eigen::Vector3d c[4], double delta, double t0, double h);
}  // namespace internal

}  // namespace rk::intersect

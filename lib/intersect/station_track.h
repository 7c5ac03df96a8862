// One station's located-target file (SPEC.md §2.1, formats/located.h) aligned to any time: the
// station's azimuth and elevation (and range) interpolated linearly to t (lib/track's
// TimeSeriesInterpolator; azimuth on its unwrapped sequence, so a pass through north is continuous), only
// where two of its own usable rows bracket t no further apart than max_gap_frames × its median frame
// interval (no extrapolation; a gap, a lost row or an empty value between them: no contribution).
// Usable row: az_deg and el_deg present and status ok or reacquired (or no status column).
// 1σ: sigma_az_deg / sigma_el_deg / sigma_range_m where the file has them (per row), else the defaults.
// Linear interpolation of white noise at fraction f between rows k and k+1 has variance
// (1−f)² σ_k² + f² σ_{k+1}² (≤ σ²): that is the σ given to the solver, so the covariance stays honest.
// corr_az_el (rk-locate's correlation of a row's azimuth and elevation errors; 0 when absent): the
// interpolated covariance (1−f)² ρ_k σaz_k σel_k + f² ρ_{k+1} σaz_{k+1} σel_{k+1} over the interpolated σ.
// Clock (SPEC.md §7): every time of the file plus the station's time_offset_s is the common clock; an offset
// known only to σ_t (estimated, time_offsets.h) adds the line of sight's rate × σ_t to each angle's error (and
// the range rate × σ_t to a range's): az and el move together along the track, so their covariance gains
// ȧ·ė·σ_t² too.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "formats/located.h"
#include "intersect/solver.h"

namespace rk::intersect {

struct TrackDefaults {
  double sigma_angle_rad = 0.0;  // cross-line σ for both angles when the file has no σ columns
  double sigma_range_m = 0.0;
  double max_gap_frames = 1.5;
};

class StationTrack {
 public:
  // The file as formats::ReadLocated read (and checked) it.
  StationTrack(const formats::LocatedFile& file, const TrackDefaults& defaults, double time_offset_s = 0.0);
  ~StationTrack();
  StationTrack(StationTrack&&) noexcept;

  // Fills o (angles, σ, range) at t; false when the station does not contribute at t.
  bool At(double t_s, LineObservation* o) const;
  // The clock offset's 1σ (s), 0 by default (a known offset).
  void SetTimeSigma(double sigma_s) { time_sigma_s_ = sigma_s; }
  // Usable row k (0 ≤ k < usable_rows()) as measured, at its own time (common clock), without interpolation:
  // the observation (and its range where that row has one).
  double usable_time(std::size_t k) const { return t_[k]; }
  LineObservation UsableRow(std::size_t k) const;

  const std::vector<double>& row_times() const { return row_t_; }  // every row of the file
  std::size_t usable_rows() const { return t_.size(); }
  bool has_range() const { return has_range_; }
  bool has_sigma() const { return has_sigma_; }
  double frame_interval_s() const { return frame_interval_s_; }
  const std::string& source() const { return source_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string source_;
  std::vector<double> row_t_;
  std::vector<double> t_, sig_az_, sig_el_;     // usable angle rows
  std::vector<double> az_, az_unwrapped_, el_;  // their angles (rad)
  std::vector<double> row_range_, row_sig_r_;   // the range of the same row, NaN without
  std::vector<double> cov_az_el_;               // their az–el error covariance (rad², corr_az_el · σ_az · σ_el)
  std::vector<double> tr_, sig_r_, r_;          // usable range rows
  bool has_range_ = false, has_sigma_ = false;
  double frame_interval_s_ = 0.0;
  double time_sigma_s_ = 0.0;
};

}  // namespace rk::intersect

// Turret or theodolite boresight (A, E) at a frame time, for the camera that rides on it (seed 001:
// "the camera's extrinsics are updated each frame from the turret angles"): used by rk-locate,
// rk-attitude oi and rk-attitude cylinder alike.
//
// From a turret log (SPEC.md §2.1 `t_s,az_deg,el_deg`, read by formats::ReadTurretLog): samples
// with repeated time stamps are merged (track::MergeDuplicateTimes), azimuth is interpolated on
// its unwrapped sequence and wrapped back to [0, 2π) (a pass through north is continuous),
// elevation directly, by track::TimeSeriesInterpolator (linear or 4-point cubic). No
// extrapolation; no interpolation across a log interval longer than max_gap_s or across an
// empty sample: such times have no boresight (the caller marks the frame invalid).
// Or a fixed boresight (a camera that does not move during the recording).
#pragma once

#include <optional>
#include <string>

#include "geo/line_of_sight.h"
#include "formats/turret_log.h"
#include "track/interp.h"

namespace rk::track {

class BoresightSource {
 public:
  static BoresightSource Fixed(double az_rad, double el_rad);
  // Takes the log's columns over (pass an rvalue for a long log: no copy; the times are shared by both
  // axes when neither has an empty sample). Throws UsageError if max_gap_s is not > 0.
  static BoresightSource FromLog(formats::TurretLog log, track::InterpMethod method, double max_gap_s);

  // Boresight at t, or nullopt (with the reason in *status when given).
  std::optional<geo::AzEl> At(double t_s, track::InterpStatus* status = nullptr) const;

  bool fixed() const { return fixed_; }
  const std::string& source() const { return source_; }  // the log's name ("" when fixed)
  std::size_t duplicate_times() const { return duplicates_; }
  // Time span of the usable samples (NaN for a fixed boresight or an empty log).
  double first_time() const;
  double last_time() const;
  // Mean interval between usable samples (s): (last − first) / (samples − 1); NaN for a fixed boresight or
  // a log with fewer than two usable samples.
  double mean_sample_interval_s() const;
  // Where t_s lies between the two azimuth samples it is interpolated from: (t − t_k) / (t_k+1 − t_k) in
  // [0, 1]; NaN for a fixed boresight or outside the samples.
  double SampleWeight(double t_s) const;
  // The error for a run none of whose frame times (t_first .. t_last, from `frames_source`) the log
  // covers: DataError naming the log, e.g. "turret log covers t_s A .. B but no frame time of F (t_s C ..
  // D) is covered within the --turret-max-gap limit". `kind` = "turret" / "theodolite".
  [[noreturn]] void ThrowNoFrameCovered(const std::string& kind, const std::string& frames_source, double t_first,
                                        double t_last, const std::string& gap_option) const;

 private:
  // "covers t_s A .. B" or "has no usable sample".
  std::string CoverageText() const;

  bool fixed_ = true;
  std::string source_;
  geo::AzEl fixed_dir_;
  std::optional<track::TimeSeriesInterpolator> az_, el_;
  std::size_t duplicates_ = 0;
};

}  // namespace rk::track

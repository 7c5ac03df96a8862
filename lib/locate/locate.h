// Beacon track + turret log + camera model (+ range log) → azimuth, elevation,
// range and station ENU position of the target, per video frame.
//
// Method (seed 001, Guan et al. 2014, with SPEC.md §3's exact geometry in
// place of the paper's small-angle eq. 12):
//   1. Boresight A(t), E(t) at the frame time t: the turret log interpolated
//      (track::TimeSeriesInterpolator; azimuth on its unwrapped sequence so a
//      pass through north is continuous). No extrapolation: a frame outside
//      the log, or inside a turret gap > turret_max_gap_s, gets no angles.
//   2. Line of sight: pixel → undistorted normalised ray m_cam (Newton-inverted
//      OpenCV distortion) → ray_enu = R_enu_turret(A, E) · R_turret_cam · m_cam
//      (camera::CameraModel::RayEnu), az = atan2(e, n) mod 2π,
//      el = atan2(u, hypot(e, n)). Exact at any elevation (no small angles).
//   3. Range r(t): the 5 Hz rangefinder log interpolated to the frame time
//      (method selectable); empty across gaps > range_max_gap_s and across
//      device-error rows; no extrapolation.
//   4. Position p_enu = r · ray_enu (unit ray). Assumption: the rangefinder
//      measures from the turret rotation centre along the line of sight to the
//      beacon (no lever arm, beam and camera ray coincide at the target), and
//      the camera centre is at the rotation centre (docs/conventions.md).
// Rows are never dropped: every track row gives one output row.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "camera/camera_model.h"
#include "io/options.h"
#include "locate/inputs.h"
#include "track/interp.h"

namespace rk::locate {

struct LocateOptions {
  track::InterpMethod turret_method = track::InterpMethod::kCubic;
  double turret_max_gap_s = 0.1;  // longest turret-log interval interpolated across (s), > 0
  // Default by measurement (bench/range_interp_accuracy.cc, docs/rk-locate.md):
  // local cubic fit over 3 samples per side, 0.23 mm RMS at 0.35 mm noise.
  track::InterpMethod range_method = track::InterpMethod::kLocalCubic;
  double range_max_gap_s = 0.5;  // longest range-log interval interpolated across (s), > 0
  int range_window = 3;          // local-quadratic / local-cubic: range samples per side, [2, 50]

  // Flags, units, valid ranges and help of every member above (io/options.h): rk-locate's options,
  // Check() and the report's "options" block all come from it.
  static const io::OptionTable<LocateOptions>& Table();
  bool Check(std::string* why) const { return Table().Check(*this, why); }
  io::Json ToJson() const { return Table().ToJson(*this); }
};

// Why a row with a line of sight has, or has not, a range.
enum class RangeStatus { kOk, kGap, kDeviceError, kOutside, kNoLog, kNotApplicable };
std::string RangeStatusName(RangeStatus status);  // ok gap device_error outside none ""

// Output row status (SPEC.md §2): the track's for measured rows (ok,
// reacquired, predicted), lost without a measurement, invalid where the
// track said so or the turret log does not cover the frame time.
struct LocatedRow {
  std::optional<std::int64_t> frame;
  double t_s = 0.0;
  TrackStatus status = TrackStatus::kLost;
  std::optional<double> az_rad, el_rad;                      // line of sight
  std::optional<double> boresight_az_rad, boresight_el_rad;  // interpolated turret
  std::optional<double> range_m;
  std::optional<Eigen::Vector3d> p_enu_m;
  RangeStatus range_status = RangeStatus::kNotApplicable;
};

struct LocateResult {
  std::vector<LocatedRow> rows;
  bool has_frame = false;
  // Counters (reports, warnings).
  std::array<std::size_t, 5> rows_by_status{};        // indexed by TrackStatus
  std::array<std::size_t, 6> rows_by_range_status{};  // indexed by RangeStatus
  std::size_t rows_with_los = 0;                      // az/el computed
  std::size_t rows_with_range = 0;                    // range and ENU computed
  std::size_t rows_turret_not_covered = 0;            // any row whose time the turret log does not cover
  std::size_t measured_rows_turret_not_covered = 0;   // of those, rows with a pixel (→ invalid)
  std::size_t turret_duplicate_times = 0;             // turret samples merged (repeated time stamps)
  std::size_t range_duplicate_times = 0;
  std::size_t range_device_errors = 0;
  // Fraction of rows with a line of sight that also got a range (NaN if none).
  double RangeCoverage() const;
  // The report's "summary" (docs/rk-locate.md "Report"): the headline figures rk-run copies.
  io::Json SummaryJson() const;
};

// Throws rk::Error: DataError naming the turret log if it covers no frame
// time at all; UsageError if options fail Check().
LocateResult Locate(const Track& track, const camera::CameraModel& camera, const TurretLog& turret,
                    const RangeLog* range, const LocateOptions& options);

// Located-target CSV (SPEC.md §2.1) with extra columns:
//   frame (if the track had it),t_s,az_deg,el_deg,range_m,e_m,n_m,u_m,status,
//   range_status,boresight_az_deg,boresight_el_deg
io::CsvWriter LocatedCsv(const LocateResult& result);

}  // namespace rk::locate

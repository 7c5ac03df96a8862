// Beacon track + turret log + camera model (+ range log) → azimuth, elevation,
// range and station ENU position of the target, per video frame.
//
// Method (seed 001, Guan et al. 2014, with SPEC.md §3's exact geometry in
// place of the paper's small-angle eq. 12):
//   0. Time: the frame's mid-exposure time t = t_s + camera.time_offset_s (SPEC.md §3: the turret and range
//      logs' times are true). The turret and range logs are interpolated at t, and the output row's t_s
//      is t (the time the angles and range refer to); with a zero offset it is the track's t_s.
//   1. Boresight A(t), E(t) at the frame time t: the turret log interpolated
//      (track::TimeSeriesInterpolator; azimuth on its unwrapped sequence so a
//      pass through north is continuous). No extrapolation: a frame outside
//      the log, or inside a turret gap > turret_max_gap_s, gets no angles.
//   2. Line of sight: pixel → undistorted normalised ray m_cam (Newton-inverted
//      OpenCV distortion) → ray_enu = R_enu_turret(A, E) · R_turret_cam · m_cam
//      (camera::CameraModel::RayEnu), az = atan2(e, n) mod 2π,
//      el = atan2(u, hypot(e, n)). Exact at any elevation (no small angles). With a pointing model
//      (--pointing, SPEC.md §3.1) R_enu_turret has its four terms (CameraModel::RayEnu with the terms).
//   3. Range r(t): the 5 Hz rangefinder log interpolated to the frame time
//      (method selectable); empty across gaps > range_max_gap_s and across
//      device-error rows; no extrapolation.
//   4. Position p_enu = r · ray_enu (unit ray). Assumption: the rangefinder
//      measures from the turret rotation centre along the line of sight to the
//      beacon (no lever arm, beam and camera ray coincide at the target), and
//      the camera centre is at the rotation centre (docs/conventions.md).
//   5. 1σ of az, el, range, e, n, u (locate_sigma.h): first-order propagation of the pixel, turret,
//      pointing-model, camera-calibration, time-offset and range σ by automatic differentiation.
//   6. WGS-84 lat/lon/h of p_enu when the station's position is given (geo::LocalEnu, GeographicLib).
// Rows are never dropped: every track row gives one output row.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "geo/wgs84.h"
#include "io/options.h"
#include "formats/beacon_track.h"
#include "formats/range_log.h"
#include "formats/turret_log.h"
#include "io/run_summary.h"
#include "locate/locate_sigma.h"
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
  // 1σ inputs (locate_sigma.h). Pixel σ for tracks without sigma_x_px/sigma_y_px: rk-extract beacon's
  // measured centroid accuracy (docs/rk-extract.md: max std 0.027 px, max |bias| 0.013 px).
  double sigma_px = 0.03;
  double encoder_step_deg = 0.003;  // turret encoder step (the FLIR PTU of seed 001); σ = step/√12
  double turret_sigma_deg = 0.0;    // further turret angle noise per axis (servo jitter, interpolation)
  double range_sigma_mm = 0.35;     // range σ at a frame (DLS-B15 static std of seed 001)

  // Not options of the table (files and a position, set by the app):
  std::optional<camera::PointingModel> pointing;  // --pointing: SPEC.md §3.1 terms and their σ
  std::optional<geo::Geodetic> station;           // --station: WGS-84 position of the ENU origin
  std::string camera_source = "camera";           // the camera file's name, for errors in its calibration

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
  std::string id;  // the point's id when located from a points track (MergeById)
  RowStatus status = RowStatus::kLost;
  std::optional<double> az_rad, el_rad;                      // line of sight
  std::optional<double> boresight_az_rad, boresight_el_rad;  // interpolated turret
  std::optional<double> range_m;
  std::optional<Eigen::Vector3d> p_enu_m;
  RangeStatus range_status = RangeStatus::kNotApplicable;
  // Covariance of (az, el, range, e, n, u) (rad, m) with the line of sight; the range rows and columns only
  // mean something when range_m is set.
  std::optional<LocatedCovariance> cov;
  std::optional<geo::Geodetic> geodetic;  // WGS-84 of p_enu_m (with --station)
};

struct LocateResult {
  std::vector<LocatedRow> rows;
  bool has_frame = false;
  bool has_station = false;  // lat_deg, lon_deg, h_m columns
  bool has_id = false;       // an id column: one series per point of a points track (MergeById)
  double time_offset_s = 0.0;  // the camera's, added to every row's t_s
  // Counters (reports, warnings).
  std::array<std::size_t, 5> rows_by_status{};        // indexed by RowStatus
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

// Where a run's inputs came from, for its summary's warnings and report.
struct LocateSources {
  std::string turret;                  // the turret log's path
  std::string range;                   // the range log's path ("" = none)
  std::size_t turret_empty_samples = 0;  // turret rows without angles (TurretLog::empty_samples, before Locate)
};

// The run's summary (io/run_summary.h): rows by status, the warnings rk-locate prints (turret log not
// covering frame times, no range at all), range coverage as headline figure, and the report keys of
// docs/rk-locate.md "Report" (options, station, time_offset_s, counts, range_coverage, summary).
io::RunSummary LocateSummary(const LocateResult& result, const LocateOptions& options, const LocateSources& sources);

// Throws rk::Error: DataError naming the turret log if it covers no frame
// time at all, or the camera for a malformed calibration.sigma; UsageError if options fail Check().
// The turret log's columns are taken over (std::move a long log: track::BoresightSource::FromLog).
LocateResult Locate(const formats::Track& track, const camera::CameraModel& camera, formats::TurretLog turret,
                    const formats::RangeLog* range, const LocateOptions& options);

// The results of each id of a points track (Locate per id) as one: rows in time order, the ids of one time in
// the order given, each row with its id; counters summed.
LocateResult MergeById(std::vector<std::pair<std::string, LocateResult>> by_id);

// Located-target CSV (SPEC.md §2.1) with extra columns:
//   frame (if the track had it),t_s,[id (from a points track),]az_deg,el_deg,range_m,e_m,n_m,u_m,status,
//   range_status,boresight_az_deg,boresight_el_deg,
//   sigma_az_deg,sigma_el_deg,sigma_range_m,sigma_e_m,sigma_n_m,sigma_u_m,corr_az_el[,lat_deg,lon_deg,h_m]
// (lat/lon/h with a station position). boresight_* are the logged (interpolated) turret angles.
io::CsvWriter LocatedCsv(const LocateResult& result);

}  // namespace rk::locate

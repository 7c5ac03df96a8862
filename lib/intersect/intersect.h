// rk-intersect (SPEC.md §7): two or more stations' located-target files → one trajectory with its
// covariance in the origin's ENU frame and in WGS-84 (docs/rk-intersect.md).
//
// Per output time t: every station whose rows bracket t (station_track.h) gives a line of sight (± range)
// → SolveRow (solver.h: Gauss–Newton weighted least squares, covariance (JᵀWJ)⁻¹, outlier rejection,
// geometry figures). Output times: the union of the stations' row times, `--at` times, or a `--rate` grid.
// A row with fewer than two lines of sight (and not one line with a range) keeps its row: status `lost`;
// one whose solution fails (singular geometry, no convergence, behind a station): status `invalid`.
// --smooth: velocity and acceleration by the Singer RTS smoother of lib/filter (singer_series.h) run on
// e, n, u of the rows whose 3-D σ is within smooth_gate × the median (the per-row covariance gates it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "filter/singer_series.h"
#include "intersect/solver.h"
#include "intersect/station_track.h"
#include "intersect/time_offsets.h"
#include "formats/stations.h"
#include "io/csv.h"
#include "io/options.h"
#include "io/row_status.h"
#include "io/run_summary.h"

namespace rk::intersect {

inline constexpr double kDefaultSigmaAngleArcsec = 5.0;  // a tracking camera's line-of-sight noise
inline constexpr double kDefaultSigmaRangeM = 1.0;       // a laser rangefinder beyond a few km
inline constexpr double kDefaultRejectSigma = 5.0;       // false rejection ~ 6e-7 per residual (Gaussian)
inline constexpr double kDefaultMaxGapFrames = 1.5;      // frame-time jitter yes, a dropped frame no
inline constexpr double kDefaultSmoothGate = 3.0;        // × the median 3-D σ

struct IntersectOptions {
  double sigma_angle_arcsec = kDefaultSigmaAngleArcsec;  // 1σ of both angles across the line (no σ columns)
  double sigma_range_m = kDefaultSigmaRangeM;            // 1σ of a range (no sigma_range_m column)
  double reject_sigma = kDefaultRejectSigma;             // k; +inf never rejects
  double max_gap_frames = kDefaultMaxGapFrames;          // × a station's median frame interval
  double rate_hz = 0.0;                                  // > 0: output times k / rate_hz
  bool smooth = false;
  bool estimate_time_offsets = false;  // SPEC §7 --estimate-time-offsets (time_offsets.h)
  double smooth_gate = kDefaultSmoothGate;
  filter::SingerSeriesOptions singer;  // --maneuver-time

  static const io::OptionTable<IntersectOptions>& Table();
  bool Check(std::string* why) const;
  io::Json ToJson() const { return Table().ToJson(*this); }
  TrackDefaults Defaults() const;
  SolverOptions Solver() const { return SolverOptions{reject_sigma}; }
};

struct TrajectoryRow {
  double t_s = 0.0;
  RowStatus status = RowStatus::kLost;
  int n_lines = 0;  // lines of sight available; used = popcount(result.used)
  RowResult result;
  geo::Geodetic wgs84;
  bool has_kinematics = false;
  Eigen::Vector3d v = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero();  // m/s, m/s² (ENU)
  Eigen::Vector3d sigma_v = Eigen::Vector3d::Zero(), sigma_a = Eigen::Vector3d::Zero();
};

// Per station and row: what it did (none, used, rejected) and its residuals at the final solution.
enum class LineUse : std::uint8_t { kNone, kUsed, kRejected };

struct StationCounts {
  std::size_t rows_contributed = 0, rows_used = 0, rows_rejected = 0;
  double sum2_az = 0.0, sum2_el = 0.0, sum2_range = 0.0;  // used residuals: arcsec², arcsec², m²
  std::size_t n_range = 0;
};

struct IntersectResult {
  std::string id;                  // the point's id (IntersectById); "" for the one trajectory of a beacon
  std::vector<std::string> names;  // stations
  std::vector<bool> has_range;     // station file has a range column
  std::vector<Eigen::Vector3d> station_enu;  // each station's position in the output's ENU frame (m)
  std::vector<TrajectoryRow> rows;
  std::vector<LineUse> use;              // rows × stations
  std::vector<Eigen::Vector3d> residual;  // rows × stations: az·cos el (arcsec), el (arcsec), range (m)
  std::vector<StationCounts> stations;
  std::size_t rows_ok = 0, rows_lost = 0, rows_invalid = 0, rows_with_rejection = 0;
  filter::SingerSeriesResult singer;  // --smooth
  bool smoothed = false;

  LineUse Use(std::size_t row, std::size_t s) const { return use[row * names.size() + s]; }
  // The report's "summary" (rk-run copies it): rows_ok, rows_lost, rows_invalid, rows_with_rejection,
  // median sigma_3d_m, gdop, intersection_angle_deg, rms_residual_arcsec.
  io::Json SummaryJson() const;
  // Report body: counts, per-station figures, median correlations, summary.
  io::Json ToJson() const;
  // The run's summary (io/run_summary.h): rows by status, the warning for rows with fewer than two lines of
  // sight, the median 3-D 1σ as headline, ToJson as details.
  io::RunSummary Summary() const;
};

// Output times: `at` when not empty, else the rate grid over the stations' span, else the union of rows.
std::vector<double> OutputTimes(const std::vector<StationTrack>& tracks, const IntersectOptions& options,
                                const std::vector<double>& at);

// The whole run. Throws DataError (exit 3, naming stations.json) when no time has two stations' lines of
// sight (their times never overlap).
IntersectResult Intersect(const formats::StationsFile& stations, const std::vector<StationTrack>& tracks,
                          const std::vector<double>& times, const IntersectOptions& options);

// Reads `--at` times (column t_s, strictly increasing).
std::vector<double> ReadTimes(const io::CsvTable& table);

// Trajectory CSV (SPEC.md §2.1 trajectory columns + docs/rk-intersect.md "Columns").
io::CsvWriter TrajectoryCsv(const IntersectResult& result);

// Located files with ids (rk-locate of points tracks): one trajectory per id, from the stations whose files
// have rows of it (an id at fewer than two stations, or whose stations' times never overlap, gets none and a
// warning in *warnings). Each id's rows enter only its own intersection. Throws DataError (naming
// stations.json) when no id has a trajectory.
// Every station's times are put on the common clock by its time_offset_s; sigma_s (per station, optional):
// the offsets' 1σ (StationTrack::SetTimeSigma).
std::vector<IntersectResult> IntersectById(const formats::StationsFile& stations,
                                           const std::vector<formats::LocatedFile>& files,
                                           const IntersectOptions& options, const std::vector<double>& at,
                                           std::vector<std::string>* warnings,
                                           const std::vector<double>* sigma_s = nullptr);
// --estimate-time-offsets with ids: every id is a target of its own path, the offsets shared.
TimeOffsetFit EstimateTimeOffsetsById(const formats::StationsFile& stations,
                                      const std::vector<formats::LocatedFile>& files,
                                      const IntersectOptions& options, const TimeOffsetOptions& offsets);
// The trajectories of IntersectById as one CSV: an id column after t_s, rows in time order (ids of one time
// in the located files' order).
io::CsvWriter TrajectoryCsv(const std::vector<IntersectResult>& by_id);
// Their run summary: rows of every id by status, the median 3-D 1σ over all, the warnings; details: the first
// id's report body (its "summary") and "by_id" with each id's.
io::RunSummary SummaryById(const std::vector<IntersectResult>& by_id, const std::vector<std::string>& warnings);

}  // namespace rk::intersect

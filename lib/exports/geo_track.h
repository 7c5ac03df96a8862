// What rk-export writes, whatever file it came from: one path per id of a trajectory (SPEC.md §7, rk-intersect)
// or of a located target with its WGS-84 columns (SPEC.md §2.1, rk-locate --station), each a time-ordered list of
// the rows that have a position, split into runs where rows without one lie between.
//
// A row is placed when its status has values (ok, reacquired, predicted: RowStatusHasValues) and it has
// lat_deg, lon_deg, h_m; lost and invalid rows, and a located row without a range (no position), are not, and
// end the run they follow (a drawn line never bridges them). The positions are the file's WGS-84 numbers as they
// are (heights ellipsoidal), longitudes brought to [-180, 180).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "formats/located.h"
#include "formats/trajectory.h"
#include "geo/wgs84.h"
#include "io/csv.h"
#include "io/row_status.h"
#include "io/run_summary.h"

namespace rk::exports {

struct PathSample {
  double t_s = 0.0;
  geo::Geodetic wgs84;  // degrees, longitude in [-180, 180); h_m above the WGS-84 ellipsoid
  std::optional<Eigen::Vector3d> sigma_enu_m;  // 1σ east, north, up (m), where the file gives it
  RowStatus status = RowStatus::kOk;
  std::optional<int> n_stations;  // a trajectory's
  std::size_t line = 0;           // the row's line in the input file
};

struct GeoPath {
  std::string id;  // "" without an id column
  std::vector<PathSample> samples;
  std::vector<std::pair<std::size_t, std::size_t>> runs;  // [begin, end) into samples, in time order
  std::size_t rows = 0;                                    // the file's rows of this id, placed or not
};

enum class InputKind { kTrajectory, kLocated };
const char* InputKindName(InputKind kind);   // "trajectory", "located" (the report's input role)
const char* InputKindWords(InputKind kind);  // "trajectory", "located target" (for people)

struct GeoTrack {
  std::string source;  // the input file
  InputKind kind = InputKind::kTrajectory;
  bool has_id = false;
  std::vector<GeoPath> paths;  // ids in order of first appearance; a path may have no sample
  std::array<std::size_t, 5> rows_by_status{};  // every row, by RowStatus
  std::size_t rows = 0, placed = 0;

  std::size_t Runs() const;
  // Rows by status, the placed fraction as headline, a warning per id with nothing placed.
  io::RunSummary Summary() const;
};

GeoTrack FromTrajectory(const formats::TrajectoryFile& file);
GeoTrack FromLocated(const formats::LocatedFile& file);

// Reads `path` ("-" = stdin) as a trajectory (formats::ReadTrajectory) or a located target with its positions
// (formats::ReadLocated, LocatedRead::kPositions) under --bad-rows `bad_rows`, and converts it. A file with no
// placed row is a ProcessingError (exit 1) that says why ("FILE: no row has a position: 12 rows, 12 lost").
GeoTrack ReadGeoTrack(const std::string& path, InputKind kind, io::BadRows bad_rows);

// Longitude in [-180, 180) (degrees).
double WrapLongitudeDeg(double lon_deg);

}  // namespace rk::exports

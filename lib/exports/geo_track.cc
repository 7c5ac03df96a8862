// The placed paths of a trajectory or located target; model in geo_track.h.
#include "exports/geo_track.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "io/error.h"

namespace rk::exports {
namespace {

// The index of id `id` in track->paths, appending a new path at its first appearance.
GeoPath& PathOf(GeoTrack* track, const std::string& id) {
  const auto it = std::find_if(track->paths.begin(), track->paths.end(), [&](const GeoPath& p) { return p.id == id; });
  if (it != track->paths.end()) return *it;
  track->paths.push_back(GeoPath{id, {}, {}, 0});
  return track->paths.back();
}

// One row of the file: counted, and placed (appended to its path's current run, or starting one) when it has a
// position; a row without one closes its path's run.
void AddRow(GeoTrack* track, const std::string& id, RowStatus status, const std::optional<geo::Geodetic>& g,
            PathSample sample) {
  GeoPath& path = PathOf(track, id);
  ++path.rows;
  ++track->rows;
  ++track->rows_by_status[static_cast<std::size_t>(status)];
  const bool placed = RowStatusHasValues(status) && g.has_value();
  if (!placed) {
    if (!path.runs.empty() && path.runs.back().second == 0) path.runs.back().second = path.samples.size();
    return;
  }
  sample.wgs84 = *g;
  sample.wgs84.lon_deg = WrapLongitudeDeg(g->lon_deg);
  sample.status = status;
  if (path.runs.empty() || path.runs.back().second != 0) path.runs.emplace_back(path.samples.size(), 0);
  path.samples.push_back(sample);
  ++track->placed;
}

// Closes every path's open run (end 0 marks one while reading).
void CloseRuns(GeoTrack* track) {
  for (GeoPath& p : track->paths) {
    if (!p.runs.empty() && p.runs.back().second == 0) p.runs.back().second = p.samples.size();
  }
}

}  // namespace

const char* InputKindName(InputKind kind) { return kind == InputKind::kTrajectory ? "trajectory" : "located"; }
const char* InputKindWords(InputKind kind) { return kind == InputKind::kTrajectory ? "trajectory" : "located target"; }

double WrapLongitudeDeg(double lon_deg) {
  if (lon_deg >= -180.0 && lon_deg < 180.0) return lon_deg;  // the file's number, untouched
  return lon_deg - 360.0 * std::floor((lon_deg + 180.0) / 360.0);
}

std::size_t GeoTrack::Runs() const {
  std::size_t n = 0;
  for (const GeoPath& p : paths) n += p.runs.size();
  return n;
}

io::RunSummary GeoTrack::Summary() const {
  io::RunSummary s;
  for (std::size_t k = 0; k < rows_by_status.size(); ++k) s.CountRows(static_cast<RowStatus>(k), rows_by_status[k]);
  s.AddFigure("rows placed", rows > 0 ? static_cast<double>(placed) / static_cast<double>(rows) : NAN, "fraction",
              std::to_string(placed) + " of " + std::to_string(rows) + " rows; " + std::to_string(paths.size()) +
                  (paths.size() == 1 ? " path, " : " paths, ") + std::to_string(Runs()) + (Runs() == 1 ? " run" : " runs"));
  for (const GeoPath& p : paths) {
    if (p.samples.empty()) {
      s.Warn("path_not_placed", "id '" + p.id + "' has no row with a position (" + std::to_string(p.rows) +
                                    " rows): it is not exported");
    }
  }
  s.details["export"] = {{"input_kind", InputKindName(kind)}, {"rows", rows}, {"rows_placed", placed},
                         {"paths", paths.size()}, {"runs", Runs()}};
  return s;
}

namespace {

// The rows of a trajectory or a located target (their records share the fields a path needs).
template <class File>
GeoTrack FromRecords(const File& file, InputKind kind) {
  GeoTrack t;
  t.source = file.source;
  t.kind = kind;
  t.has_id = file.has_id;
  for (const auto& r : file.rows) {
    PathSample s;
    s.t_s = r.t_s;
    s.sigma_enu_m = r.sigma_enu_m;
    if constexpr (std::is_same_v<File, formats::TrajectoryFile>) s.n_stations = r.n_stations;
    s.line = r.line;
    AddRow(&t, r.id, r.status, r.geodetic, s);
  }
  CloseRuns(&t);
  return t;
}

}  // namespace

GeoTrack FromTrajectory(const formats::TrajectoryFile& file) { return FromRecords(file, InputKind::kTrajectory); }

GeoTrack FromLocated(const formats::LocatedFile& file) { return FromRecords(file, InputKind::kLocated); }

GeoTrack ReadGeoTrack(const std::string& path, InputKind kind, io::BadRows bad_rows) {
  GeoTrack t;
  if (kind == InputKind::kTrajectory) {
    t = FromTrajectory(formats::ReadTrajectory(io::CsvTable::Read(path, {bad_rows, formats::TrajectoryRowRule()})));
  } else {
    const formats::LocatedRead what = formats::LocatedRead::kPositions;
    t = FromLocated(formats::ReadLocated(io::CsvTable::Read(path, {bad_rows, formats::LocatedRowRule(what)}), what));
  }
  if (t.placed == 0) {
    std::string counts;
    for (std::size_t k = 0; k < t.rows_by_status.size(); ++k) {
      if (t.rows_by_status[k] == 0) continue;
      counts += ", " + std::to_string(t.rows_by_status[k]) + " " + RowStatusName(static_cast<RowStatus>(k));
    }
    throw ProcessingError(t.source + ": no row has a position to export (" + std::to_string(t.rows) + " rows" + counts +
                          (kind == InputKind::kLocated ? "; a located row has one only with a range" : "") + ")");
  }
  return t;
}

}  // namespace rk::exports

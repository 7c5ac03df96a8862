// One trajectory per point id (located files from points tracks); see intersect.h.
#include <algorithm>
#include <cmath>

#include "intersect/intersect.h"
#include "intersect/intersect_common.h"
#include "intersect/station_track.h"
#include "io/error.h"

namespace rk::intersect {

namespace {

std::vector<std::string> AllIds(const std::vector<formats::LocatedFile>& files) {
  std::vector<std::string> ids;
  for (const formats::LocatedFile& f : files) {
    for (const std::string& id : f.Ids()) {
      if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
    }
  }
  return ids;
}

// The stations that saw `id`, each with its rows only, on the common clock (time_offset_s; its 1σ from
// sigma_s when given).
void IdTracks(const formats::StationsFile& stations, const std::vector<formats::LocatedFile>& files,
              const IntersectOptions& options, const std::string& id, const std::vector<double>* sigma_s,
              formats::StationsFile* sub, std::vector<int>* index, std::vector<StationTrack>* tracks) {
  *sub = stations;
  sub->stations.clear();
  for (std::size_t s = 0; s < files.size(); ++s) {
    formats::LocatedFile f = files[s];
    f.rows.erase(std::remove_if(f.rows.begin(), f.rows.end(),
                                [&](const formats::LocatedRecord& r) { return r.id != id; }),
                 f.rows.end());
    if (f.rows.empty()) continue;
    sub->stations.push_back(stations.stations[s]);
    index->push_back(static_cast<int>(s));
    tracks->emplace_back(f, options.Defaults(), stations.stations[s].time_offset_s);
    if (sigma_s) tracks->back().SetTimeSigma((*sigma_s)[s]);
  }
}

}  // namespace

TimeOffsetFit EstimateTimeOffsetsById(const formats::StationsFile& stations,
                                      const std::vector<formats::LocatedFile>& files,
                                      const IntersectOptions& options, const TimeOffsetOptions& offsets) {
  const std::vector<std::string> ids = AllIds(files);
  std::vector<std::vector<StationTrack>> keep(ids.size());
  std::vector<OffsetTarget> targets(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    formats::StationsFile sub;
    IdTracks(stations, files, options, ids[i], nullptr, &sub, &targets[i].station, &keep[i]);
    for (const StationTrack& t : keep[i]) targets[i].track.push_back(&t);
  }
  return EstimateTimeOffsets(stations, targets, offsets);
}

std::vector<IntersectResult> IntersectById(const formats::StationsFile& stations,
                                           const std::vector<formats::LocatedFile>& files,
                                           const IntersectOptions& options, const std::vector<double>& at,
                                           std::vector<std::string>* warnings, const std::vector<double>* sigma_s) {
  std::vector<IntersectResult> out;
  for (const std::string& id : AllIds(files)) {
    formats::StationsFile sub;
    std::vector<int> index;
    std::vector<StationTrack> tracks;
    IdTracks(stations, files, options, id, sigma_s, &sub, &index, &tracks);
    if (tracks.size() < 2) {
      warnings->push_back("point '" + id + "' is seen by " + std::to_string(tracks.size()) +
                          " station(s): no trajectory (two are needed)");
      continue;
    }
    try {
      const std::vector<double> times = OutputTimes(tracks, options, at);
      IntersectResult r = Intersect(sub, tracks, times, options);
      r.id = id;
      out.push_back(std::move(r));
    } catch (const Error& e) {
      if (e.code() != ExitCode::kInvalidData) throw;
      warnings->push_back("point '" + id + "': no trajectory: " + e.what());
    }
  }
  if (out.empty()) {
    throw DataError(stations.path, 0, 0, "no point id is seen by two stations at overlapping times");
  }
  return out;
}

io::RunSummary SummaryById(const std::vector<IntersectResult>& by_id, const std::vector<std::string>& warnings) {
  io::RunSummary out;
  std::vector<double> sigma;
  std::size_t rows = 0, ok = 0;
  io::Json per = io::Json::object();
  for (const IntersectResult& r : by_id) {
    for (const TrajectoryRow& tr : r.rows) {
      out.CountRows(tr.status);
      ++rows;
      if (tr.status != RowStatus::kOk) continue;
      ++ok;
      sigma.push_back(std::sqrt(tr.result.solution.P.trace()));
    }
    per[r.id] = r.ToJson();
  }
  for (const std::string& w : warnings) out.Warn("point_without_trajectory", w);
  if (!sigma.empty()) {
    out.AddFigure("median 3-D 1σ", internal::UpperMedianOrNaN(sigma), "m",
                  std::to_string(ok) + " of " + std::to_string(rows) + " rows of " + std::to_string(by_id.size()) +
                      " points");
  }
  out.details = by_id.front().ToJson();
  out.details["by_id"] = per;
  return out;
}

}  // namespace rk::intersect

// stations.json of rk-intersect (SPEC.md §7; written by rk-run's plan and rk-sim multistation, read by rk-intersect): the origin of the output ENU frame and, per station, its
// WGS-84 position and located-target file. Every error names stations.json with the line and column of the
// offending value (or of the object that lacks it): exit 3; an unreadable file: exit 4.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "geo/wgs84.h"
#include "io/json_util.h"

namespace rk::formats {

// Most stations one file may hold (rk-intersect's solver marks the stations of a row in a 64-bit mask).
inline constexpr std::size_t kMaxStations = 64;

// A station's or radar's name: [A-Za-z0-9_.-]+ (it names file columns: R_range_m, residual columns).
bool GoodName(const std::string& name);

struct StationSpec {
  std::string name;     // unique, [A-Za-z0-9_.-]+ (it names the station's residual columns)
  geo::Geodetic position;
  std::string located;  // path of its located.csv, resolved against the folder of stations.json
  std::size_t line = 0, column = 0;  // of the station's object in stations.json, for messages
  // SPEC.md §7: the station's t_s + time_offset_s is the common clock (default 0); with
  // --estimate-time-offsets the starting value. time_reference: the station whose clock the others are
  // estimated against (at most one; default the first).
  double time_offset_s = 0.0;
  bool time_offset_given = false;
  bool time_reference = false;
};

struct StationsFile {
  std::string path;
  geo::Geodetic origin;           // "origin", default the first station
  bool origin_given = false;
  std::vector<StationSpec> stations;  // at least 2
  // The station marked "time_reference": true, else the first.
  std::size_t TimeReference() const;
};

StationsFile LoadStations(const std::string& path);
// The same from text already read (`path` names it and anchors relative paths).
StationsFile ParseStations(const std::string& text, const std::string& path);
// The JSON of a stations file: "origin" when origin_given, each station's name, position and `located` as
// given (a writer puts the path relative to the file's folder). Keys in nlohmann's order (sorted).
io::Json StationsJson(const StationsFile& f);

}  // namespace rk::formats

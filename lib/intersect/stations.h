// stations.json of rk-intersect (SPEC.md §7): the origin of the output ENU frame and, per station, its
// WGS-84 position and located-target file. Every error names stations.json with the line and column of the
// offending value (or of the object that lacks it): exit 3; an unreadable file: exit 4.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "intersect/station_frames.h"

namespace rk::intersect {

struct StationSpec {
  std::string name;     // unique, [A-Za-z0-9_.-]+ (it names the station's residual columns)
  geo::Geodetic position;
  std::string located;  // path of its located.csv, resolved against the folder of stations.json
  std::size_t line = 0, column = 0;  // of the station's object in stations.json, for messages
};

struct StationsFile {
  std::string path;
  geo::Geodetic origin;           // "origin", default the first station
  bool origin_given = false;
  std::vector<StationSpec> stations;  // at least 2
};

StationsFile LoadStations(const std::string& path);
// The same from text already read (`path` names it and anchors relative paths).
StationsFile ParseStations(const std::string& text, const std::string& path);

}  // namespace rk::intersect

// A radar feed (ASTERIX CAT048/CAT001 target reports, CAT034 service messages, from captures or raw streams) into
// radar plots (SPEC.md §2.1, formats/radar_plots.h): rk-import asterix.
//
// Time. A target report carries its time of day (I048/140, UTC) — or, in CAT001, only its time of day modulo
// 512 s (I001/141). The date comes from the capture: each record's time is the instant with that time of day
// nearest to its packet's capture time (so a record stamped 23:59:59 and captured 00:00:01 belongs to the day
// before: the midnight rollover), and a truncated CAT001 time is unwrapped the same way with its 512-s period. A
// raw `.ast` stream has no capture times: the previous record's time takes their place, starting from
// --epoch-utc. t_s counts from --epoch-utc; rows are written in time order (feeds interleave radars and
// sectors). The median capture-minus-record latency is in the report, with a warning when the capture clock
// and the radar's differ by more than a minute (the date would be wrong if they differed by 12 h).
//
// Duplicates. A record whose octets equal another's seen within 5 to 10 s of its own time (a redundant feed sends
// every datagram on two multicast groups) is written once, whether the copies come in one capture or in several
// inputs read one after the other (records further apart in time are never copies: each carries its time of
// day); the report counts duplicates per source (sender → group).
//
// Elevation. For a radar whose position radars.json gives, el_deg is the geometric elevation of the straight
// line from the radar to the target at its slant range and height on the WGS-84 ellipsoid
// (geo::ElevationToHeight): the height of a 3-D radar (I048/110, `el_source` 3d), else the validated Mode C
// flight level as a height (FL × 100 ft; a pressure altitude taken as the ellipsoidal height: `mode_c`); empty
// for a plot with neither (a 2-D plot) or a height that range cannot reach.
#pragma once

#include <string>
#include <vector>

#include "formats/radar_plots.h"
#include "io/run_summary.h"

namespace rk::asterix {

struct FeedOptions {
  double epoch_unix_s = 0.0;                 // t_s = 0
  std::vector<formats::RadarSite> radars;    // radars.json (may be empty)
  bool bad_records_error = false;            // --bad-records error: the first bad record throws (exit 3)
};

struct FeedResult {
  std::vector<std::string> radar_names;        // AsterixPlotRow::radar indexes these
  std::vector<formats::AsterixPlotRow> rows;   // in time order
  io::RunSummary summary;                      // warnings; details: inputs, sources, radars, categories
};

// Reads every input in turn (capture.h). ByteOffsetError for a bad record under bad_records_error, IoError for an
// unreadable input.
FeedResult ImportFeed(const std::vector<std::string>& inputs, const FeedOptions& options);

}  // namespace rk::asterix

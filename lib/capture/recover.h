// rk-capture recover DIR: checks a trial directory written by rk-capture (after a crash, a kill -9,
// a power cut, or as a routine check) and repairs what a crash can leave behind:
//   - a torn last line of a CSV log or of events.log (no line end, or NUL bytes from a power cut)
//     is cut off;
//   - a torn last frame of a y4m segment is cut off; a half-written PGM (hidden .tmp file) removed;
//     a segment without frames removed;
//   - frames and frames.csv rows are matched segment by segment: at the end of the recording, rows
//     naming frames that are not on disk are removed, and frames without a row (no time) removed,
//     so that frames.csv never names a frame that cannot be read and every frame has its time;
//   - the manifest's video lists are rebuilt from what is on disk, "capture.state" becomes
//     "recovered" (a clean recording keeps "complete"), and "capture.recover" records every repair.
// Anything else that is wrong (a corrupt row inside a log, a frame marker missing inside a
// segment, times going backwards, a missing file) is not touched and is reported as unreadable.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/json_util.h"

namespace rk::capture {

struct RecoverOptions {
  bool check_only = false;  // report what would be repaired, change nothing
};

struct RecoverSummary {
  std::string dir;
  std::string state_before, state_after;
  std::vector<std::string> repairs;   // what was (or, with check_only, would be) repaired
  std::vector<std::string> problems;  // unreadable data, left as found (each names the file)
  std::map<std::string, std::int64_t> frames;  // per camera, readable frames with times
  std::map<std::string, std::int64_t> rows;    // per log file, data rows
  bool readable() const { return problems.empty(); }
  io::Json ToJson() const;
};

// Throws IoError if DIR or its trial.json cannot be read, DataError if trial.json is not a manifest.
RecoverSummary RecoverTrial(const std::string& dir, const RecoverOptions& options);

}  // namespace rk::capture

// What rk-run reads back from its last good run (out/report.json) and from the shared --tool-cache
// file, and the shape checks that decide whether those records are trusted (docs/rk-run.md, "Skipping").
// These files are rk-run's own output, but a hand edit, another program or another version can leave
// anything in them: a record that is not of the expected shape is not trusted (its steps run again)
// instead of ending the run in a JSON type error.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>

#include "io/json_util.h"

namespace rk::run {

// The JSON of `path`, or null when it is not a regular file or cannot be parsed.
io::Json LoadJsonOrNull(const std::string& path);

// {path?, bytes?, mtime_ns?, ...} as file digests, tool identities and step outputs are written.
bool IsFileRecord(const io::Json& j);
// One entry of a report's "steps" whose every field rk-run reads has the expected type.
bool IsStepRecord(const io::Json& s);
// A report of rk-run whose every part rk-run reads has the expected type.
bool IsUsableReport(const io::Json& r);

// The step records of a report by id (the last record of an id wins); empty for a non-report.
// The pointers point into `report`.
std::map<std::string, const io::Json*> PreviousSteps(const io::Json& report);

// The state of a file under out/ that the previous report names (a product, a step's report or log).
struct OutFileState {
  bool stat_ok = false;  // StatFile succeeded
  std::uintmax_t bytes = 0;
  std::int64_t mtime_ns = 0;
  bool regular = false;  // a regular file
};

// The state of every file under `out_dir` named by the step records of `report` ("outputs"[].path,
// "report", "log"), by the path as the report writes it.
std::map<std::string, OutFileState> ProbeOutFiles(const std::string& out_dir, const io::Json& report);

// Every path under out/ (relative, normalised) that the step records of `report` name as made by rk-run:
// products, step reports and logs, and the files rk-run generated for a step (stations.json). Empty for a
// non-report. Anything else in out/ is the user's (KeepUserEntries).
std::set<std::string> PathsMadeByRun(const io::Json& report);

}  // namespace rk::run

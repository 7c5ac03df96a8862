// The CLI edge shared by every rk-<verb>: common options, parse-error handling,
// and the mapping of rk::Error to SPEC.md §4 exit codes with one-line messages
// "rk-<tool>: error: ...".
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "io/error.h"
#include "io/json_util.h"

namespace rk::cli {

struct CommonOptions {
  std::string report_path;  // --report FILE.json
  bool quiet = false;       // --quiet: no progress, no warnings
};

// Sets --version, --report, --quiet (accepted before or after a subcommand).
void AddCommonOptions(CLI::App& app, const std::string& tool, CommonOptions* common);

// Parses argv and runs `body`. Returns the process exit code: 0 for --help and
// --version, 2 for usage errors, the code of any rk::Error, 1 for other failures.
int Run(CLI::App& app, const std::string& tool, int argc, char** argv, const std::function<int()>& body);

// Report skeleton {"tool", "version", "command_line", "inputs": {}} (SPEC.md §2).
io::Json MakeReport(const std::string& tool, int argc, char** argv);
// Records an input file: path and size in bytes.
void AddReportInput(io::Json* report, const std::string& role, const std::string& path);

// True when stderr is a terminal (progress display) and not quiet.
bool ShowProgress(const CommonOptions& common);
// Prints "rk-<tool>: warning: ..." unless quiet.
void Warn(const std::string& tool, const CommonOptions& common, const std::string& what);

}  // namespace rk::cli

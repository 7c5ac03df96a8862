// The CLI edge shared by every rk-<verb>: common options, parse-error handling,
// and the mapping of rk::Error to SPEC.md §4 exit codes with one-line messages
// "rk-<tool>: error: ...".
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "io/csv.h"
#include "io/error.h"
#include "io/json_util.h"
#include "io/options.h"
#include "io/progress.h"
#include "io/run_summary.h"

namespace rk::cli {

struct CommonOptions {
  std::string report_path;  // --report FILE.json
  bool quiet = false;       // --quiet: no progress, no warnings
};

// Sets --version, --report, --quiet (accepted before or after a subcommand), and sends library
// warnings (io::EmitWarning) to Warn(tool, *common, ...). `common` must outlive the run.
void AddCommonOptions(CLI::App& app, const std::string& tool, CommonOptions* common);

// Adds --bad-rows error|skip (what to do with a CSV data row the tool cannot use, io::BadRows) to
// `app` (a tool or a subcommand). Every tool that reads CSV calls this, and passes *bad_rows on to
// io::CsvTable::Read with the rule of the file it reads.
void AddBadRowsOption(CLI::App* app, io::BadRows* bad_rows);

// One option of a table, as AddOptions registers it. A number's shown default is captured from the member
// (capture_default_str), never set with default_val: CLI11 runs the callback of a variable's option for a
// default value, so default_val would write the 6-digit text back into the member (0.0087 rad given as
// 0.4984732... deg would become 0.498473).
template <class O>
void AddOption(CLI::App* app, O* options, const io::OptionSpec<O>& s) {
  using Kind = typename io::OptionSpec<O>::Kind;
  switch (s.kind) {
    case Kind::kReal: {
      double& v = s.real(*options);
      app->add_option(s.names(), v, s.help)->capture_default_str();
      break;
    }
    case Kind::kInteger: {
      int& v = s.integer(*options);
      app->add_option(s.names(), v, s.help)->capture_default_str();
      break;
    }
    case Kind::kCount: {
      std::uint64_t& v = s.count(*options);
      app->add_option(s.names(), v, s.help)->capture_default_str();
      break;
    }
    case Kind::kFlag:
      app->add_flag(s.names(), s.flag_value(*options), s.help);
      break;
    case Kind::kChoice: {
      auto set = s.set_choice;
      const std::string flag = s.flag;
      app->add_option_function<std::string>(
             s.names(),
             [options, set, flag](const std::string& v) {
               if (!set(options, v)) throw CLI::ValidationError(flag, "unknown value '" + v + "'");
             },
             s.help)
          ->check(CLI::IsMember(s.choices))
          ->default_str(s.get_choice(*options));
      break;
    }
  }
}

// Registers every option of `table` on `app` (a tool or a subcommand), bound to the members of
// *options, in the table's order: numbers with their current value as the shown default, choices
// checked against their names (TEXT:{a,b}=current). Bounds are checked after parsing, by the
// Options' Check() (io::OptionTable::Check), so that the library and the CLI share one message.
template <class O>
void AddOptions(CLI::App* app, O* options, const io::OptionTable<O>& table) {
  for (const auto& s : table.specs()) AddOption(app, options, s);
}

// The same, with options registered by hand (paths, lists, optional values) in between, in --help
// order: before.at(flag)() runs just before the table's option `flag` is registered.
template <class O>
void AddOptions(CLI::App* app, O* options, const io::OptionTable<O>& table,
                const std::map<std::string, std::function<void()>>& before) {
  for (const auto& s : table.specs()) {
    const auto it = before.find(s.flag);
    if (it != before.end()) it->second();
    AddOption(app, options, s);
  }
}

// Parses argv and runs `body`. Returns the process exit code: 0 for --help and
// --version, 2 for usage errors, the code of any rk::Error, 1 for other failures.
// When the run fails (parse errors included) and --report FILE was given, FILE is still
// written (atomically): the last report the tool wrote with WriteReport, else the MakeReport
// skeleton, with the inputs read so far (io::InputsRead) and "status": "failed",
// "exit_code", "error" (the one-line message). It is never written over an input or over
// another path on the command line, and failing to write it does not change the exit code.
int Run(CLI::App& app, const std::string& tool, int argc, char** argv, const std::function<int()>& body);

// Report skeleton {"tool", "version", "command_line", "inputs": {}} (SPEC.md §2).
io::Json MakeReport(const std::string& tool, int argc, char** argv);
// Records an input file: path, size in bytes and, for a CSV read, "rows_skipped" (rows dropped
// under --bad-rows skip).
void AddReportInput(io::Json* report, const std::string& role, const std::string& path);
// Writes a run report atomically ("-" = stdout) after adding "status" ("ok" when "exit_code"
// is absent or 0, else "failed") and "exit_code" (0 when absent). Run keeps a copy: if the run
// fails afterwards, the report is rewritten with the failure.
void WriteReport(const std::string& path, io::Json report);
// The same with the run's summary (io/run_summary.h), the one place a summary becomes report keys: its
// details merged as they are, then "rows_by_status" ({ok, reacquired, predicted, lost, invalid}, or null for a
// tool whose product has no row status), "warnings" ([{"code", "message"}]: the summary's, then one
// "rows_skipped" per input with bad rows skipped), "termination" and "headline" ({name: {"value", "unit"[,
// "note"]}}).
void WriteReport(const std::string& path, io::Json report, const io::RunSummary& summary);
// Prints the summary's warnings meant for stderr (Warn, in order) unless quiet.
void WarnAll(const std::string& tool, const CommonOptions& common, const io::RunSummary& summary);

// A path on the command line and the flag that named it ("-o", "--errors", "--at").
struct NamedPath {
  std::string flag;
  std::string path;  // "" = not given
  // An output that is the report itself (rk-analyze's -o JSON): --report may name the same file or stream.
  bool may_be_report = false;
};
// The one check of a tool's files before anything is read (SPEC.md §2): at most one input is stdin ('-'); no
// output (the given `outputs`, and --report) is an input; no two outputs name the same file; no two are stdout.
// Throws UsageError: "only one input can be read from stdin ('-')", "A and B name the same file PATH",
// "A and B cannot both be stdout" (A, B the flags, --report first).
void CheckStreams(const CommonOptions& common, const std::vector<NamedPath>& inputs,
                  const std::vector<NamedPath>& outputs);

// True when stderr is a terminal (progress display) and not quiet.
bool ShowProgress(const CommonOptions& common);
// The progress display (io/progress.h), under the names the apps use.
using io::FormatProgress;
using io::ProgressMeter;

// Prints "rk-<tool>: warning: ..." unless quiet.
void Warn(const std::string& tool, const CommonOptions& common, const std::string& what);

}  // namespace rk::cli

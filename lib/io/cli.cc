#include "io/cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>

#include "io/error.h"
#include "io/file_util.h"
#include "io/row_status.h"
#include "io/run_record.h"
#include "io/version.h"

namespace rk::cli {
namespace {

// The report the tool last wrote with WriteReport (Run rewrites it if the run then fails).
std::optional<io::Json>& LastReport() {
  static std::optional<io::Json> report;
  return report;
}

// The value of --report in argv (its index in *at), or "" if absent. Read from argv rather than
// from the parsed options so that it is found after a parse error too.
std::string ReportPathInArgv(int argc, char** argv, int* at) {
  static const char kOpt[] = "--report";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--") == 0) break;
    if (std::strcmp(argv[i], kOpt) == 0 && i + 1 < argc) {
      *at = i + 1;
      return argv[i + 1];
    }
    if (std::strncmp(argv[i], kOpt, sizeof kOpt - 1) == 0 && argv[i][sizeof kOpt - 1] == '=') {
      *at = i;
      return argv[i] + sizeof kOpt;
    }
  }
  return "";
}

// The name under which a path given to `app` (or its subcommands) is reported: the option's long
// name without dashes ("turret"), else its short name or positional name; "" if no option has it.
std::string RoleOf(const CLI::App& app, const std::string& path) {
  for (const CLI::Option* opt : app.get_options()) {
    for (const std::string& r : opt->results()) {
      if (r != path) continue;
      if (!opt->get_lnames().empty()) return opt->get_lnames().front();
      if (!opt->get_snames().empty()) return opt->get_snames().front();
      return opt->get_name();
    }
  }
  for (const CLI::App* sub : app.get_subcommands()) {
    const std::string role = RoleOf(*sub, path);
    if (!role.empty()) return role;
  }
  return "";
}

// Writes the report of a failed run; never throws (a failure to write it is a warning).
void WriteFailureReport(const CLI::App& app, const std::string& tool, int argc, char** argv, int exit_code,
                        const std::string& error, const std::string& kind) {
  int at = -1;
  const std::string path = ReportPathInArgv(argc, argv, &at);
  if (path.empty()) return;
  try {
    // Never over an input, nor over any other path on the command line (an output, say).
    std::vector<std::string> others;
    for (int i = 1; i < argc; ++i) {
      if (i == at) continue;
      const char* eq = std::strchr(argv[i], '=');
      others.push_back(argv[i][0] == '-' && eq ? std::string(eq + 1) : std::string(argv[i]));
    }
    const std::vector<io::InputRead> read = io::InputsRead();
    for (const auto& in : read) others.push_back(in.path);
    io::CheckOutputNotInput(path, others);

    io::Json rep = LastReport() ? *LastReport() : MakeReport(tool, argc, argv);
    if (!rep.contains("inputs") || !rep["inputs"].is_object()) rep["inputs"] = io::Json::object();
    io::Json& inputs = rep["inputs"];
    for (const auto& in : read) {
      bool listed = false;
      for (const auto& [k, v] : inputs.items()) {
        if ((v.is_object() && v.value("path", std::string()) == in.path) || (v.is_string() && v == in.path)) {
          listed = true;
        }
      }
      if (listed) continue;
      std::string base = RoleOf(app, in.path);
      if (base.empty()) base = in.path;
      std::string role = base;
      for (int n = 2; inputs.contains(role); ++n) role = base + "_" + std::to_string(n);
      AddReportInput(&rep, role, in.path);
    }
    rep["status"] = "failed";
    rep["exit_code"] = exit_code;
    rep["error"] = error;
    if (!kind.empty()) rep["error_kind"] = kind;
    io::WriteJson(path, rep);
  } catch (const std::exception& e) {
    std::cerr << tool << ": warning: the report " << path << " was not written: " << e.what() << "\n";
  }
}

}  // namespace

void AddCommonOptions(CLI::App& app, const std::string& tool, CommonOptions* common) {
  app.set_version_flag("--version", VersionLine(tool));
  app.add_option("--report", common->report_path,
                 "Write a JSON run report (inputs, options, statistics; status, exit code and error of a "
                 "failed run too)");
  app.add_flag("--quiet,-q", common->quiet, "No progress display and no warnings on stderr");
  app.fallthrough();
  io::SetWarningSink([tool, common](const std::string& what) { Warn(tool, *common, what); });
}

void AddBadRowsOption(CLI::App* app, io::BadRows* bad_rows) {
  app->add_option_function<std::string>(
         "--bad-rows",
         [bad_rows](const std::string& v) {
           if (!io::ParseBadRows(v, bad_rows)) throw CLI::ValidationError("--bad-rows", "must be error or skip");
         },
         "CSV rows the tool cannot use (wrong field count, a bad or missing number, time going backwards): "
         "error = stop with exit code 3 (default); skip = drop each with a warning, count them in the report")
      ->type_name("error|skip");
}

int Run(CLI::App& app, const std::string& tool, int argc, char** argv, const std::function<int()>& body) {
  LastReport().reset();
  const auto fail = [&](int code, const std::string& message, const std::string& kind = "") {
    std::cerr << tool << ": error: " << message << "\n";
    WriteFailureReport(app, tool, argc, argv, code, message, kind);
    return code;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(static_cast<int>(ExitCode::kUsage), std::string(e.what()) + " (see " + tool + " --help)");
  }
  try {
    return body();
  } catch (const Error& e) {
    return fail(static_cast<int>(e.code()), e.what(), e.kind());
  } catch (const std::bad_alloc&) {
    return fail(static_cast<int>(ExitCode::kProcessing), "out of memory");
  } catch (const std::exception& e) {
    return fail(static_cast<int>(ExitCode::kProcessing), std::string("internal: ") + e.what());
  }
}

io::Json MakeReport(const std::string& tool, int argc, char** argv) {
  io::Json r;
  r["tool"] = tool;
  r["version"] = kVersion;
  r["git_commit"] = kGitCommit;
  std::vector<std::string> args(argv, argv + argc);
  r["command_line"] = args;
  r["inputs"] = io::Json::object();
  return r;
}

void AddReportInput(io::Json* report, const std::string& role, const std::string& path) {
  io::Json in;
  in["path"] = path;
  std::error_code ec;
  const std::optional<io::InputRead> read = io::FindInputRead(path);
  if (path != "-" && std::filesystem::is_regular_file(path, ec)) {
    in["bytes"] = std::filesystem::file_size(path, ec);
  } else if (read && read->bytes) {
    in["bytes"] = *read->bytes;
  }
  if (read && read->csv) in["rows_skipped"] = read->rows_skipped;
  (*report)["inputs"][role] = in;
}

void WriteReport(const std::string& path, io::Json report) {
  if (!report.contains("exit_code")) report["exit_code"] = 0;
  const bool ok = report["exit_code"].is_number_integer() && report["exit_code"].get<int>() == 0;
  report["status"] = ok ? "ok" : "failed";
  LastReport() = report;
  io::WriteJson(path, report);
}

namespace {

// Every input of the report with bad rows skipped (--bad-rows skip), as a typed warning.
void AddSkippedRowWarnings(const io::Json& report, io::Json* warnings) {
  if (!report.contains("inputs") || !report["inputs"].is_object()) return;
  for (const auto& [role, in] : report["inputs"].items()) {
    if (!in.is_object() || !in.contains("rows_skipped") || !in["rows_skipped"].is_number_unsigned()) continue;
    const auto n = in["rows_skipped"].get<std::uint64_t>();
    if (n == 0) continue;
    warnings->push_back({{"code", "rows_skipped"},
                         {"message", std::to_string(n) + " bad row(s) of " + in.value("path", role) +
                                         " skipped (--bad-rows skip)"}});
  }
}

io::Json FigureValue(double v) { return std::isfinite(v) ? io::Json(v) : io::Json(nullptr); }

}  // namespace

void WriteReport(const std::string& path, io::Json report, const io::RunSummary& summary) {
  report.update(summary.details);
  if (summary.rows_by_status) {
    io::Json rows = io::Json::object();
    for (std::size_t s = 0; s < summary.rows_by_status->size(); ++s)
      rows[RowStatusName(static_cast<RowStatus>(s))] = (*summary.rows_by_status)[s];
    report["rows_by_status"] = rows;
  } else {
    report["rows_by_status"] = nullptr;
  }
  io::Json warnings = io::Json::array();
  for (const io::Warning& w : summary.warnings) warnings.push_back({{"code", w.code}, {"message", w.message}});
  AddSkippedRowWarnings(report, &warnings);
  report["warnings"] = warnings;
  report["termination"] = summary.termination;
  io::Json headline = io::Json::object();
  for (const io::Figure& f : summary.headline) {
    io::Json fig = {{"value", FigureValue(f.value)}, {"unit", f.unit}};
    if (!f.note.empty()) fig["note"] = f.note;
    headline[f.name] = fig;
  }
  report["headline"] = headline;
  WriteReport(path, std::move(report));
}

void WarnAll(const std::string& tool, const CommonOptions& common, const io::RunSummary& summary) {
  for (const io::Warning& w : summary.warnings)
    if (w.on_stderr) Warn(tool, common, w.message);
}

void CheckStreams(const CommonOptions& common, const std::vector<NamedPath>& inputs,
                  const std::vector<NamedPath>& outputs) {
  std::vector<std::string> in_paths;
  int n_stdin = 0;
  for (const NamedPath& in : inputs) {
    if (in.path.empty()) continue;
    in_paths.push_back(in.path);
    n_stdin += io::IsStdStream(in.path) ? 1 : 0;
  }
  if (n_stdin > 1) throw UsageError("only one input can be read from stdin ('-')");
  std::vector<NamedPath> outs;
  if (!common.report_path.empty()) outs.push_back({"--report", common.report_path});
  for (const NamedPath& o : outputs)
    if (!o.path.empty()) outs.push_back(o);
  for (const NamedPath& o : outs) io::CheckOutputNotInput(o.path, in_paths);
  for (std::size_t i = 0; i < outs.size(); ++i) {
    for (std::size_t j = i + 1; j < outs.size(); ++j) {
      if (i == 0 && !common.report_path.empty() && outs[j].may_be_report && outs[j].path == outs[i].path) continue;
      const bool same_stream = io::IsStdStream(outs[i].path) && io::IsStdStream(outs[j].path);
      if (same_stream) throw UsageError(outs[i].flag + " and " + outs[j].flag + " cannot both be stdout");
      if (outs[i].path == outs[j].path) {
        throw UsageError(outs[i].flag + " and " + outs[j].flag + " name the same file " + outs[i].path);
      }
    }
  }
}

bool ShowProgress(const CommonOptions& common) { return !common.quiet && ::isatty(STDERR_FILENO); }


void Warn(const std::string& tool, const CommonOptions& common, const std::string& what) {
  if (!common.quiet) std::cerr << tool << ": warning: " << what << "\n";
}

}  // namespace rk::cli

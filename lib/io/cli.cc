#include "io/cli.h"

#include <unistd.h>

#include <filesystem>
#include <iostream>

#include "io/error.h"
#include "io/version.h"

namespace rk::cli {

void AddCommonOptions(CLI::App& app, const std::string& tool, CommonOptions* common) {
  app.set_version_flag("--version", tool + " (rangekit) " + kVersion);
  app.add_option("--report", common->report_path, "Write a JSON run report (inputs, options, statistics)");
  app.add_flag("--quiet,-q", common->quiet, "No progress display and no warnings on stderr");
  app.fallthrough();
}

int Run(CLI::App& app, const std::string& tool, int argc, char** argv, const std::function<int()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << tool << ": error: " << e.what() << " (see " << tool << " --help)\n";
    return static_cast<int>(ExitCode::kUsage);
  }
  try {
    return body();
  } catch (const Error& e) {
    std::cerr << tool << ": error: " << e.what() << "\n";
    return static_cast<int>(e.code());
  } catch (const std::bad_alloc&) {
    std::cerr << tool << ": error: out of memory\n";
    return static_cast<int>(ExitCode::kProcessing);
  } catch (const std::exception& e) {
    std::cerr << tool << ": error: internal: " << e.what() << "\n";
    return static_cast<int>(ExitCode::kProcessing);
  }
}

io::Json MakeReport(const std::string& tool, int argc, char** argv) {
  io::Json r;
  r["tool"] = tool;
  r["version"] = kVersion;
  std::vector<std::string> args(argv, argv + argc);
  r["command_line"] = args;
  r["inputs"] = io::Json::object();
  return r;
}

void AddReportInput(io::Json* report, const std::string& role, const std::string& path) {
  io::Json in;
  in["path"] = path;
  std::error_code ec;
  if (path != "-" && std::filesystem::is_regular_file(path, ec)) {
    in["bytes"] = std::filesystem::file_size(path, ec);
  }
  (*report)["inputs"][role] = in;
}

bool ShowProgress(const CommonOptions& common) { return !common.quiet && ::isatty(STDERR_FILENO); }

void Warn(const std::string& tool, const CommonOptions& common, const std::string& what) {
  if (!common.quiet) std::cerr << tool << ": warning: " << what << "\n";
}

}  // namespace rk::cli

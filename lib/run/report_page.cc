#include "run/report_page.h"

#include <signal.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>

#include "io/error.h"
#include "run/process.h"
#include "run/trial_dir.h"

namespace rk::run {
namespace fs = std::filesystem;

namespace {

// The last non-empty line of the page's log: rk-report's one-line error.
std::string LastLine(const std::string& path) {
  std::ifstream f(path);
  std::string line, last;
  while (std::getline(f, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

}  // namespace

std::string MakeReportPage(const std::string& trial_dir, const std::string& out_path,
                           const std::vector<std::string>& tool_dirs, bool rebuilt, bool no_figures) {
  const fs::path out(out_path);
  const fs::path page = out / kReportPageFile;
  std::error_code ec, ec2;
  const auto page_time = fs::last_write_time(page, ec);
  const auto report_time = fs::last_write_time(out / kReportFile, ec2);
  if (ec2) return "";  // no out/ to show
  if (!rebuilt && !ec && page_time >= report_time) return "";
  const std::string tool = FindExecutable(kReportPageTool, tool_dirs);
  if (tool.empty()) return std::string(kReportPageTool) + " not found next to rk-run or on PATH";
  fs::create_directories(out / "steps", ec);
  const std::string log = (out / "steps" / "report-page.log").string();
  fs::remove(log, ec);
  ChildSpec spec{{tool, out.string(), "--quiet"}, trial_dir, log, {}};
  if (no_figures) spec.argv.push_back("--no-figures");
  pid_t pid = -1;
  try {
    pid = StartChild(spec);
  } catch (const Error& e) {
    return e.what();
  }
  ChildResult r;
  if (!WaitAnyChild(&r)) {  // a stop signal: the page is not worth waiting for
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return "interrupted";
  }
  if (r.exit_code == 0) return "";
  const std::string why = LastLine(log);
  return r.Describe() + (why.empty() ? "" : ": " + why) + " (out/steps/report-page.log)";
}

}  // namespace rk::run

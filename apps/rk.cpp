// rk: one command for the whole suite (git / colmap style).
//   rk help              every rk-<tool> with one line each
//   rk help TOOL         TOOL's --help
//   rk TOOL ARGS...      runs rk-TOOL ARGS... (exit code, stdin, stdout and stderr are the tool's own)
//   rk --version         the suite's version and the git commit it was built from
// Tools are found next to rk first (a build folder, an install prefix's bin/), then on PATH; the list
// in `rk help` is whatever rk-* executables are there, so a new tool needs no change here. Its line is
// the first sentence of the tool's own --help description (one owner: the tool).
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/version.h"

namespace {

constexpr const char* kName = "rk";
constexpr std::size_t kLineWidth = 76;  // one line per tool in `rk help`

std::string SelfDir() {
  std::vector<char> buf(4096);
  const ssize_t n = ::readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  if (n <= 0) return "";
  std::string p(buf.data(), static_cast<std::size_t>(n));
  const auto slash = p.rfind('/');
  return slash == std::string::npos ? "" : p.substr(0, slash);
}

bool IsExecutableFile(const std::string& path) {
  struct stat st{};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// Folders searched for rk-<tool>, in order: rk's own, then PATH's.
std::vector<std::string> SearchDirs() {
  std::vector<std::string> dirs;
  const std::string self = SelfDir();
  if (!self.empty()) dirs.push_back(self);
  if (const char* path = std::getenv("PATH")) {
    std::stringstream ss(path);
    std::string d;
    while (std::getline(ss, d, ':')) {
      if (!d.empty() && std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(d);
    }
  }
  return dirs;
}

std::string FindTool(const std::string& tool) {
  for (const std::string& d : SearchDirs()) {
    const std::string p = d + "/rk-" + tool;
    if (IsExecutableFile(p)) return p;
  }
  return "";
}

// tool name (without "rk-") → path, first found wins.
std::vector<std::pair<std::string, std::string>> ListTools() {
  std::set<std::string> seen;
  std::vector<std::pair<std::string, std::string>> tools;
  for (const std::string& d : SearchDirs()) {
    DIR* dir = ::opendir(d.c_str());
    if (!dir) continue;
    std::vector<std::string> names;
    while (const dirent* e = ::readdir(dir)) {
      const std::string n = e->d_name;
      if (n.rfind("rk-", 0) == 0 && n.size() > 3 && n.find('.') == std::string::npos) names.push_back(n);
    }
    ::closedir(dir);
    std::sort(names.begin(), names.end());
    for (const std::string& n : names) {
      const std::string p = d + "/" + n;
      if (IsExecutableFile(p) && seen.insert(n).second) tools.emplace_back(n.substr(3), p);
    }
  }
  std::sort(tools.begin(), tools.end());
  return tools;
}

// First sentence of the tool's --help description, on one line.
std::string OneLine(const std::string& path) {
  const std::string cmd = "'" + path + "' --help 2>/dev/null";
  FILE* f = ::popen(cmd.c_str(), "r");
  if (!f) return "";
  std::string text;
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
  ::pclose(f);
  std::string desc;
  if (text.rfind("usage:", 0) == 0) {
    // argparse (the Python tools): "usage: ..." lines, a blank line, then the description.
    const auto blank = text.find("\n\n");
    if (blank != std::string::npos) desc = text.substr(blank + 2, text.find("\n\n", blank + 2) - (blank + 2));
  } else {
    // CLI11: the description, then "Usage:".
    const auto usage = text.find("Usage:");
    desc = text.substr(0, usage == std::string::npos ? text.size() : usage);
  }
  // "rk-sim: synthesize ..." → "synthesize ...": the name is in the first column already.
  const std::string prefix = path.substr(path.rfind('/') + 1) + ": ";
  if (desc.rfind(prefix, 0) == 0) desc = desc.substr(prefix.size());
  std::replace(desc.begin(), desc.end(), '\n', ' ');
  const auto dot = desc.find(". ");
  if (dot != std::string::npos) desc = desc.substr(0, dot);
  while (!desc.empty() && (desc.back() == ' ' || desc.back() == '.')) desc.pop_back();
  while (!desc.empty() && desc.front() == ' ') desc.erase(desc.begin());
  if (desc.size() > kLineWidth) desc = desc.substr(0, kLineWidth - 3) + "...";
  return desc;
}

int Help() {
  std::cout << "usage: rk <tool> [options...]    (= rk-<tool> [options...])\n"
               "       rk help [<tool>]\n       rk --version\n\ntools:\n";
  const auto tools = ListTools();
  std::size_t width = 0;
  for (const auto& t : tools) width = std::max(width, t.first.size());
  for (const auto& [name, path] : tools) {
    std::cout << "  " << name << std::string(width + 2 - name.size(), ' ') << OneLine(path) << "\n";
  }
  std::cout << "\n'rk help <tool>' or 'rk <tool> --help' shows a tool's options; 'man rk-<tool>' its manual.\n";
  return 0;
}

int Exec(const std::string& tool, int argc, char** argv, int first) {
  const std::string path = FindTool(tool);
  if (path.empty()) {
    std::cerr << kName << ": error: unknown tool '" << tool << "' (rk help lists them)\n";
    return 2;
  }
  std::vector<std::string> args = {"rk-" + tool};
  for (int i = first; i < argc; ++i) args.emplace_back(argv[i]);
  std::vector<char*> cargs;
  for (auto& a : args) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  ::execv(path.c_str(), cargs.data());
  std::cerr << kName << ": error: cannot run " << path << "\n";
  return 4;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    Help();
    return 2;
  }
  const std::string a = argv[1];
  if (a == "--version") {
    std::cout << rk::VersionLine(kName) << "\n";
    return 0;
  }
  if (a == "help" || a == "--help" || a == "-h") {
    if (argc >= 3) {
      char help[] = "--help";
      char* args[] = {argv[0], argv[2], help};
      return Exec(argv[2], 3, args, 2);
    }
    return Help();
  }
  if (!a.empty() && a[0] == '-') {
    std::cerr << kName << ": error: unknown option " << a << " (rk help)\n";
    return 2;
  }
  return Exec(a, argc, argv, 2);
}

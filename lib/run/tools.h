// Finding and identifying the tools rk-run starts (docs/rk-run.md, "Skipping"): the executable's path,
// its --version line and its identity (GNU build ID, or SHA-256 for scripts), with the same size+mtime
// shortcut as the inputs and an optional --tool-cache file shared between trials.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <optional>
#include <string>
#include <vector>

#include "io/json_util.h"

namespace rk::run {

struct ToolIdentity {
  std::string name, path, version;
  std::string id;  // "build-id:<hex>" (ELF GNU build ID) or "sha256:<hex>" (scripts)
  std::uintmax_t bytes = 0;
  std::int64_t mtime_ns = 0;
  io::Json ToJson() const {
    return {{"path", path}, {"version", version}, {"id", id}, {"bytes", bytes}, {"mtime_ns", mtime_ns}};
  }
};

// The long option names in a --help text, CLI11's ("  -o,--output TEXT  ...") or argparse's
// ("  -o OUT, --output OUT  ..."): on each line that starts (after blanks) with '-', the names before
// the first run of two blanks.
std::set<std::string> HelpOptionNames(const std::string& help_text);

class Tools {
 public:
  // `dirs`: folders searched before PATH. `previous`: the "tools" of the last good report; `shared`:
  // the --tool-cache file's content (the same records, shared by every trial of a nightly run so that
  // each tool is asked once). `trust_stat`: use the size+mtime shortcut (false = --rehash).
  Tools(std::vector<std::string> dirs, const io::Json& previous, const io::Json& shared, bool trust_stat);
  bool shared_changed() const { return shared_changed_; }
  const io::Json& shared() const { return shared_; }

  // Null when the tool cannot be found; IoError when it exists but will not tell its version.
  const ToolIdentity* Get(const std::string& name);
  // The long options (without "--") that `tool [subcommand] --help` lists: the tool's real option table,
  // against which a manifest's step options are checked (exact names only, no abbreviation). Empty when
  // the tool gives no readable --help. Asked once per tool and subcommand.
  const std::set<std::string>& OptionNames(const ToolIdentity& tool, const std::string& subcommand);
  // {name: identity} of every tool found so far.
  io::Json ToJson() const;

 private:
  std::vector<std::string> dirs_;
  io::Json previous_, shared_;
  bool trust_;
  bool shared_changed_ = false;
  std::map<std::string, std::optional<ToolIdentity>> cache_;
  std::map<std::string, std::set<std::string>> options_;  // "path subcommand" → OptionNames
};

}  // namespace rk::run

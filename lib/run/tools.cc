#include "run/tools.h"

#include <utility>

#include "io/error.h"
#include "run/digest.h"
#include "run/elf_build_id.h"
#include "run/previous_report.h"
#include "run/process.h"
#include "run/sha256.h"

namespace rk::run {
using io::Json;

Tools::Tools(std::vector<std::string> dirs, const Json& previous, const Json& shared, bool trust_stat)
    : dirs_(std::move(dirs)), previous_(previous.is_object() ? previous : Json::object()),
      shared_(shared.is_object() ? shared : Json::object()), trust_(trust_stat) {}

const ToolIdentity* Tools::Get(const std::string& name) {
  auto it = cache_.find(name);
  if (it != cache_.end()) return it->second ? &*it->second : nullptr;
  const std::string path = FindExecutable(name, dirs_);
  if (path.empty()) {
    cache_[name] = std::nullopt;
    return nullptr;
  }
  ToolIdentity id;
  id.name = name;
  id.path = path;
  if (!StatFile(path, &id.bytes, &id.mtime_ns)) throw IoError(path, "cannot read the executable");
  const auto matches = [&](const Json* prev) {
    return prev && IsFileRecord(*prev) && prev->value("path", "") == path &&
           prev->value("bytes", std::uintmax_t{0}) == id.bytes &&
           prev->value("mtime_ns", std::int64_t{0}) == id.mtime_ns && prev->contains("id") &&
           prev->contains("version");
  };
  const Json* prev = previous_.contains(name) ? &previous_.at(name) : nullptr;
  if (!matches(prev)) prev = shared_.contains(path) ? &shared_.at(path) : nullptr;
  if (trust_ && matches(prev)) {
    id.id = prev->at("id").get<std::string>();
    id.version = prev->at("version").get<std::string>();
  } else {
    const std::string build_id = ElfBuildId(path);
    id.id = build_id.empty() ? "sha256:" + Sha256File(path) : "build-id:" + build_id;
    std::string out;
    const int rc = RunAndCapture({path, "--version"}, &out);
    const auto nl = out.find('\n');
    id.version = out.substr(0, nl);
    if (rc != 0 || id.version.empty()) {
      throw IoError(path, "does not answer --version (exit code " + std::to_string(rc) + "): not a rangekit tool?");
    }
    shared_[path] = id.ToJson();
    shared_changed_ = true;
  }
  cache_[name] = id;
  return &*cache_[name];
}

Json Tools::ToJson() const {
  Json j = Json::object();
  for (const auto& [name, id] : cache_) {
    if (id) j[name] = id->ToJson();
  }
  return j;
}

std::set<std::string> HelpOptionNames(const std::string& help_text) {
  std::set<std::string> names;
  std::size_t pos = 0;
  while (pos < help_text.size()) {
    std::size_t end = help_text.find('\n', pos);
    if (end == std::string::npos) end = help_text.size();
    std::string line = help_text.substr(pos, end - pos);
    pos = end + 1;
    const std::size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] != '-') continue;
    line = line.substr(first, line.find("  ", first) == std::string::npos ? std::string::npos
                                                                          : line.find("  ", first) - first);
    std::size_t p = 0;
    while (p < line.size()) {
      std::size_t q = line.find(',', p);
      if (q == std::string::npos) q = line.size();
      std::string item = line.substr(p, q - p);
      p = q + 1;
      item.erase(0, item.find_first_not_of(' '));
      item = item.substr(0, item.find_first_of(" =["));
      if (item.size() > 2 && item.compare(0, 2, "--") == 0) names.insert(item.substr(2));
    }
  }
  return names;
}

const std::set<std::string>& Tools::OptionNames(const ToolIdentity& tool, const std::string& subcommand) {
  const std::string key = tool.path + " " + subcommand;
  auto it = options_.find(key);
  if (it != options_.end()) return it->second;
  std::vector<std::string> argv = {tool.path};
  if (!subcommand.empty()) argv.push_back(subcommand);
  argv.push_back("--help");
  std::string text;
  std::set<std::string> names;
  if (RunAndCapture(argv, &text) == 0) names = HelpOptionNames(text);
  return options_.emplace(key, std::move(names)).first->second;
}

}  // namespace rk::run

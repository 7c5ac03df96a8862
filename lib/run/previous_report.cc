#include "run/previous_report.h"

#include <filesystem>
#include <functional>
#include <set>
#include <initializer_list>

#include "run/digest.h"

namespace rk::run {
namespace fs = std::filesystem;
using io::Json;

Json LoadJsonOrNull(const std::string& path) {
  try {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return Json(nullptr);
    return io::LoadJson(path);
  } catch (const std::exception&) {
    return Json(nullptr);
  }
}

namespace {

bool OptionalOf(const Json& j, const char* key, bool (Json::*is)() const noexcept) {
  return !j.contains(key) || (j.at(key).*is)();
}

bool StringsOnly(const Json& j, std::initializer_list<const char*> keys) {
  for (const char* k : keys) {
    if (!OptionalOf(j, k, &Json::is_string)) return false;
  }
  return true;
}

}  // namespace

bool IsFileRecord(const Json& j) {
  return j.is_object() && OptionalOf(j, "bytes", &Json::is_number_unsigned) &&
         OptionalOf(j, "mtime_ns", &Json::is_number_integer) && OptionalOf(j, "files", &Json::is_number_unsigned) &&
         StringsOnly(j, {"path", "sha256", "id", "version"});
}

bool IsStepRecord(const Json& s) {
  if (!s.is_object() || !StringsOnly(s, {"id", "status", "reason", "key", "report", "log"})) return false;
  if (s.contains("outputs")) {
    if (!s["outputs"].is_array()) return false;
    for (const auto& o : s["outputs"]) {
      if (!IsFileRecord(o)) return false;
    }
  }
  if (!s.contains("key_parts")) return true;
  const Json& k = s["key_parts"];
  if (!k.is_object()) return false;
  if (k.contains("tool") && !(k["tool"].is_object() && StringsOnly(k["tool"], {"version"}))) return false;
  if (k.contains("inputs") && k["inputs"].is_array()) {
    for (const auto& i : k["inputs"]) {
      if (!i.is_object() || !StringsOnly(i, {"path", "sha256"})) return false;
    }
  }
  if (k.contains("upstream")) {
    if (!k["upstream"].is_object()) return false;
    for (const auto& [id, key] : k["upstream"].items()) {
      if (!key.is_string()) return false;
    }
  }
  return true;
}

bool IsUsableReport(const Json& r) {
  if (!r.is_object() || r.value("tool", Json()) != "rk-run") return false;
  for (const char* records : {"inputs", "tools"}) {
    if (!r.contains(records)) continue;
    if (!r[records].is_object()) return false;
    for (const auto& [name, rec] : r[records].items()) {
      if (!IsFileRecord(rec)) return false;
    }
  }
  if (r.contains("trial") && !(r["trial"].is_object() && StringsOnly(r["trial"], {"manifest_sha256"}))) return false;
  if (r.contains("steps")) {
    if (!r["steps"].is_array()) return false;
    for (const auto& s : r["steps"]) {
      if (!IsStepRecord(s)) return false;
    }
  }
  return true;
}

std::map<std::string, const Json*> PreviousSteps(const Json& report) {
  std::map<std::string, const Json*> prev_steps;
  if (report.is_object() && report.contains("steps") && report["steps"].is_array()) {
    for (const auto& e : report["steps"]) {
      if (e.is_object() && e.contains("id") && e["id"].is_string()) prev_steps[e["id"].get<std::string>()] = &e;
    }
  }
  return prev_steps;
}

namespace {

// Calls `each` with every path under out/ that a step record of `report` names: its products, report
// and log, and (with `generated`) the files rk-run wrote for it.
void ForEachStepFile(const Json& report, bool generated, const std::function<void(const std::string&)>& each) {
  for (const auto& [id, p] : PreviousSteps(report)) {
    const Json outs = p->value("outputs", Json::array());
    if (outs.is_array()) {
      for (const auto& o : outs) {
        if (o.is_object()) each(o.value("path", ""));
      }
    }
    for (const char* f : {"report", "log"}) {
      if (p->contains(f) && (*p)[f].is_string()) each((*p)[f].get<std::string>());
    }
    const Json gen = generated ? p->value("key_parts", Json::object()).value("generated", Json()) : Json();
    if (gen.is_object()) {
      for (const auto& [path, digest] : gen.items()) each(path);
    }
  }
}

}  // namespace

std::map<std::string, OutFileState> ProbeOutFiles(const std::string& out_dir, const Json& report) {
  std::map<std::string, OutFileState> files;
  const fs::path out(out_dir);
  ForEachStepFile(report, false, [&](const std::string& path) {
    if (files.count(path)) return;
    OutFileState& f = files[path];
    f.stat_ok = StatFile((out / path).string(), &f.bytes, &f.mtime_ns);
    std::error_code ec;
    f.regular = fs::is_regular_file(out / path, ec);
  });
  return files;
}

std::set<std::string> PathsMadeByRun(const Json& report) {
  std::set<std::string> made;
  if (!report.is_object()) return made;
  ForEachStepFile(report, true, [&](const std::string& path) { made.insert(fs::path(path).lexically_normal().string()); });
  return made;
}

}  // namespace rk::run

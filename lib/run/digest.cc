#include "run/digest.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <regex>

#include "io/error.h"
#include "run/sha256.h"

namespace rk::run {
namespace fs = std::filesystem;
using io::Json;

Json FileDigest::ToJson() const {
  Json j = {{"bytes", bytes}, {"mtime_ns", mtime_ns}, {"sha256", sha256}};
  if (files != 1) j["files"] = files;
  return j;
}

bool StatFile(const std::string& path, std::uintmax_t* bytes, std::int64_t* mtime_ns) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  *bytes = static_cast<std::uintmax_t>(st.st_size);
  *mtime_ns = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
  return true;
}

namespace {

// "%06d" / "%d" in the file name → regex and width; false if the name has no such conversion.
bool SequenceRegex(const std::string& name, std::regex* re) {
  static const std::regex conv("%(0?)([0-9]*)d");
  std::smatch m;
  if (!std::regex_search(name, m, conv)) return false;
  const auto quote = [](const std::string& s) {
    static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
    return std::regex_replace(s, special, R"(\$&)");
  };
  const std::string width = m[2].str();
  // %d: any digits; %0Nd: at least N digits (zero-padded); %Nd: space-padded digits.
  const std::string digits =
      width.empty() ? "[0-9]+" : (m[1].str() == "0" ? "[0-9]{" + width + ",}" : " *[0-9]+");
  *re = std::regex("^" + quote(m.prefix().str()) + "(" + digits + ")" + quote(m.suffix().str()) + "$");
  return true;
}

}  // namespace

bool IsSequencePattern(const std::string& path) {
  std::regex re;
  return SequenceRegex(fs::path(path).filename().string(), &re);
}

std::vector<std::string> ExpandSequence(const std::string& pattern) {
  const fs::path p(pattern);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::regex re;
  if (!SequenceRegex(p.filename().string(), &re)) return {pattern};
  std::vector<std::pair<long long, std::string>> found;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::smatch m;
    if (std::regex_match(name, m, re)) {
      found.emplace_back(std::stoll(m[1].str()), (p.has_parent_path() ? (dir / name).string() : name));
    }
  }
  if (ec) throw IoError(dir.string(), std::string("cannot list the folder: ") + ec.message());
  std::sort(found.begin(), found.end());
  std::vector<std::string> out;
  for (auto& f : found) out.push_back(std::move(f.second));
  return out;
}

DigestCache::DigestCache(std::string base_dir, const Json& previous, bool trust_stat)
    : base_(std::move(base_dir)), previous_(previous.is_object() ? previous : Json::object()),
      trust_stat_(trust_stat) {}

std::string DigestCache::Resolve(const std::string& path) const {
  const fs::path p(path);
  return p.is_absolute() || base_.empty() ? path : (fs::path(base_) / p).string();
}

const FileDigest& DigestCache::Digest(const std::string& path) {
  auto found = digests_.find(path);
  if (found != digests_.end()) return found->second;
  FileDigest d;
  std::vector<std::string> files;
  const bool sequence = IsSequencePattern(path);
  if (sequence) {
    files = ExpandSequence(Resolve(path));
    if (files.empty()) throw IoError(Resolve(path), "no file matches this image-sequence pattern");
    d.files = files.size();
  } else {
    files = {Resolve(path)};
  }
  std::vector<std::pair<std::uintmax_t, std::int64_t>> stats;
  for (const auto& f : files) {
    std::uintmax_t b = 0;
    std::int64_t t = 0;
    if (!StatFile(f, &b, &t)) {
      std::error_code ec;
      throw IoError(f, fs::exists(f, ec) ? "is not a regular file" : "no such file (named in the manifest)");
    }
    d.bytes += b;
    d.mtime_ns = std::max(d.mtime_ns, t);
    stats.emplace_back(b, t);
  }
  if (trust_stat_ && previous_.contains(path)) {
    const Json& p = previous_.at(path);
    if (p.is_object() && p.value("bytes", std::uintmax_t{0}) == d.bytes &&
        p.value("mtime_ns", std::int64_t{0}) == d.mtime_ns && p.value("files", std::size_t{1}) == d.files &&
        p.contains("sha256") && p.at("sha256").is_string()) {
      d.sha256 = p.at("sha256").get<std::string>();
      ++files_trusted_;
      return digests_.emplace(path, d).first->second;
    }
  }
  if (sequence) {
    Sha256 h;
    for (const auto& f : files) {
      h.Update(fs::path(f).filename().string() + " " + Sha256File(f) + "\n");
    }
    d.sha256 = h.HexDigest();
  } else {
    d.sha256 = Sha256File(files[0]);
  }
  d.hashed = true;
  files_hashed_ += files.size();
  bytes_hashed_ += d.bytes;
  return digests_.emplace(path, d).first->second;
}

Json DigestCache::ToJson() const {
  Json j = Json::object();
  for (const auto& [path, d] : digests_) j[path] = d.ToJson();
  return j;
}

}  // namespace rk::run

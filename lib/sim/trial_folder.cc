#include "sim/trial_folder.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "io/error.h"
#include "io/file_util.h"

namespace rk::sim {
namespace fs = std::filesystem;
namespace {

std::string MakeTempDir(const fs::path& parent, const std::string& stem, const std::string& for_path) {
  std::string templ = (parent / ("." + stem + ".XXXXXX")).string();
  std::vector<char> buf(templ.begin(), templ.end());
  buf.push_back('\0');
  if (!::mkdtemp(buf.data())) {
    throw IoError(for_path, std::string("cannot create a folder beside it: ") + std::strerror(errno));
  }
  mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(buf.data(), 0777 & ~mask);
  return std::string(buf.data());
}

}  // namespace

TrialFolder::TrialFolder(const std::string& out_dir, bool force) {
  if (out_dir.empty() || out_dir == "-") throw UsageError("--out must name a folder");
  fs::path out = fs::path(out_dir).lexically_normal();
  if (!out.has_filename() && out.has_parent_path()) out = out.parent_path();
  out_ = out.string();
  if (out.filename() == "." || out.filename() == ".." || out_.empty()) {
    throw UsageError("--out '" + out_dir + "' must name a new folder");
  }
  // A link to a folder stays a link: the folder it leads to is what gets replaced (SPEC.md §2).
  out = fs::path(io::ResolveOutputFolder(out_));
  out_ = out.string();
  std::error_code ec;
  if (fs::exists(fs::symlink_status(out, ec))) {
    if (!fs::is_directory(out, ec)) throw UsageError("--out " + out_ + " exists and is not a folder");
    if (!fs::is_empty(out, ec) && !force) {
      throw UsageError("--out " + out_ + " exists and is not empty; use --force to replace it");
    }
  }
  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  parent_ = parent.string();
  io::MakeDirectories(parent_);
  stem_ = out.filename().string();
  tmp_ = MakeTempDir(parent, stem_, out_);
}

TrialFolder::~TrialFolder() {
  if (!committed_ && !tmp_.empty()) {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
  }
}

std::string TrialFolder::Path(const std::string& relative) const {
  return (fs::path(tmp_) / relative).string();
}

void TrialFolder::MakeSubfolder(const std::string& relative) const { io::MakeDirectories(Path(relative)); }

void TrialFolder::Commit() {
  std::error_code ec;
  std::string trash;
  if (fs::exists(fs::symlink_status(out_, ec))) {
    if (fs::is_directory(out_, ec) && fs::is_empty(out_, ec)) {
      fs::remove(out_, ec);
      if (ec) throw IoError(out_, "cannot replace the empty folder: " + ec.message());
    } else {
      trash = MakeTempDir(parent_, stem_ + ".old", out_);
      if (std::rename(out_.c_str(), trash.c_str()) != 0) {
        const int e = errno;
        fs::remove(trash, ec);
        throw IoError(out_, std::string("cannot move the old folder aside: ") + std::strerror(e));
      }
    }
  }
  if (std::rename(tmp_.c_str(), out_.c_str()) != 0) {
    const int e = errno;
    if (!trash.empty()) std::rename(trash.c_str(), out_.c_str());
    throw IoError(out_, std::string("cannot rename into place: ") + std::strerror(e));
  }
  committed_ = true;
  if (!trash.empty()) fs::remove_all(trash, ec);
}

}  // namespace rk::sim

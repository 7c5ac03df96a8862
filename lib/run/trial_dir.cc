#include "run/trial_dir.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <set>
#include <thread>

#include "io/error.h"
#include "io/file_util.h"

namespace rk::run {
namespace fs = std::filesystem;

namespace {

std::string NowUtc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

bool StartsWith(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }

// The folder that TRIAL/out (or rk-run --out DIR) stands for: the path itself, or the final target when
// it is a symbolic link (results kept on another disk). The link stays a link: the target is what is
// swapped, and its working and old folders are made beside it (a rename cannot cross file systems).
fs::path OutTarget(const std::string& out_path) { return fs::path(io::ResolveOutputFolder(out_path)); }

}  // namespace

std::unique_ptr<TrialLock> TrialLock::Acquire(const std::string& path, double wait_s, std::string* holder) {
  const int fd = io::OpenOwnFile(path, O_RDWR | O_CREAT);  // never through a link (threat model)
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(std::max(0.0, wait_s));
  for (;;) {
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) break;
    if (errno != EWOULDBLOCK && errno != EINTR) {
      const int e = errno;
      ::close(fd);
      throw IoError(path, std::string("cannot lock: ") + std::strerror(e));
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      char buf[256] = {0};
      const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
      std::string who = n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
      while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
      if (holder) *holder = who.empty() ? "another process" : who;
      ::close(fd);
      return nullptr;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const std::string me = "pid " + std::to_string(::getpid()) + " since " + NowUtc() + "\n";
  if (::ftruncate(fd, 0) == 0) {
    [[maybe_unused]] const ssize_t w = ::pwrite(fd, me.data(), me.size(), 0);
  }
  return std::unique_ptr<TrialLock>(new TrialLock(fd));
}

TrialLock::~TrialLock() {
  if (::ftruncate(fd_, 0) != 0) {
    // The holder text is informative only.
  }
  ::close(fd_);  // releases the flock
}

void RemoveOutTree(const std::string& path) {
  std::error_code ec;
  fs::remove(fs::path(path) / kReportFile, ec);
  fs::remove_all(path, ec);
}

std::vector<std::string> RecoverAndClean(const std::string& out_path) {
  std::vector<std::string> notes;
  const fs::path out = OutTarget(out_path);
  const fs::path dir = out.parent_path();
  const std::string stem = out.filename().string();
  std::vector<fs::path> tmps, olds;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    // A link named like a working folder is not one of ours: never followed, never removed.
    if (it->is_symlink(ec) || !it->is_directory(ec)) continue;
    if (StartsWith(name, stem + ".tmp.")) tmps.push_back(it->path());
    if (StartsWith(name, stem + ".old.")) olds.push_back(it->path());
  }
  if (ec) throw IoError(dir.string(), "cannot list the folder of out/: " + ec.message());
  std::error_code ec2;
  if (!fs::exists(out, ec2)) {
    // An interrupted two-rename swap: prefer the new complete folder, else the old one.
    const auto newest_complete = [](const std::vector<fs::path>& dirs) {
      fs::path best;
      fs::file_time_type best_t{};
      for (const auto& d : dirs) {
        std::error_code e;
        const fs::path r = d / kReportFile;
        if (!fs::is_regular_file(r, e)) continue;
        const auto t = fs::last_write_time(r, e);
        if (best.empty() || t > best_t) {
          best = d;
          best_t = t;
        }
      }
      return best;
    };
    fs::path pick = newest_complete(tmps);
    if (pick.empty()) pick = newest_complete(olds);
    if (!pick.empty()) {
      if (::rename(pick.c_str(), out.c_str()) != 0) {
        throw IoError(out.string(), std::string("cannot restore from ") + pick.filename().string() + ": " +
                                        std::strerror(errno));
      }
      notes.push_back("restored out/ from " + pick.filename().string() + " (a swap had been interrupted)");
    }
  }
  for (const auto* list : {&tmps, &olds}) {
    for (const auto& d : *list) {
      if (!fs::exists(d, ec2)) continue;  // the one restored above
      RemoveOutTree(d.string());
      notes.push_back("removed stale " + d.filename().string());
    }
  }
  return notes;
}

std::string MakeWorkDir(const std::string& out_path) {
  const fs::path out = OutTarget(out_path);
  std::string templ = (out.parent_path() / (out.filename().string() + ".tmp.XXXXXX")).string();
  std::vector<char> buf(templ.begin(), templ.end());
  buf.push_back('\0');
  if (!::mkdtemp(buf.data())) {
    throw IoError(out.parent_path().string(), std::string("cannot create a working folder: ") + std::strerror(errno));
  }
  // mkdtemp makes the folder 0700; out/ gets the mode of every other folder (0777 less the umask), so
  // that a web server or a colleague can open the pages the nightly index links to.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(buf.data(), 0777 & ~mask);
  return std::string(buf.data());
}

void LinkOrCopy(const std::string& src, const std::string& dst) {
  std::error_code ec;
  fs::create_directories(fs::path(dst).parent_path(), ec);
  if (ec) throw IoError(dst, "cannot create its folder: " + ec.message());
  if (::link(src.c_str(), dst.c_str()) == 0) return;
  fs::copy_file(src, dst, fs::copy_options::overwrite_existing, ec);
  if (ec) throw IoError(dst, "cannot copy " + src + ": " + ec.message());
  // Keep the modification time: the next run recognises an intact product by size and mtime.
  const auto t = fs::last_write_time(src, ec);
  if (!ec) fs::last_write_time(dst, t, ec);
}

void SyncPath(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

std::vector<std::string> KeepUserEntries(const std::string& out_dir, const std::string& work_dir,
                                         const std::set<std::string>& made_by_run, bool record_known) {
  std::vector<std::string> kept;
  std::error_code ec;
  const fs::path out(out_dir), work(work_dir);
  if (!fs::is_directory(out, ec)) return kept;
  fs::recursive_directory_iterator it(out, fs::directory_options::none, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const fs::path rel = it->path().lexically_relative(out).lexically_normal();
    const std::string name = rel.string();
    const bool link = it->is_symlink(ec);
    if (!link && it->is_directory(ec)) continue;  // folders are made as their files are kept
    if (made_by_run.count(name) || (StartsWith(name, "steps/") && rel.extension() == ".progress")) continue;
    const fs::path dst = work / rel;
    if (fs::exists(fs::symlink_status(dst, ec))) {
      if (!record_known) continue;  // no record of what rk-run made: the new product is taken for the old
      throw IoError((fs::path(kOutDir) / rel).string(),
                    "was not made by rk-run, and a step now writes the same path: move it out of out/ first "
                    "(nothing was changed)");
    }
    fs::create_directories(dst.parent_path(), ec);
    if (link) {
      fs::copy_symlink(it->path(), dst, ec);  // a link stays a link; its target is not touched
      if (ec) throw IoError(dst.string(), "cannot keep the link " + name + ": " + ec.message());
    } else {
      LinkOrCopy(it->path().string(), dst.string());
    }
    kept.push_back(name);
  }
  if (ec) throw IoError(out_dir, "cannot list: " + ec.message());
  return kept;
}

void CheckOutIsFolder(const std::string& out_path) {
  const fs::path out = OutTarget(out_path);
  std::error_code ec;
  const fs::file_status st = fs::status(out, ec);
  if (fs::exists(st) && !fs::is_directory(st)) {
    throw IoError(out_path, "exists and is not a folder: rk-run writes its products into the folder out/ and will not "
                  "replace a file (move it away)");
  }
}

std::string CommitOut(const std::string& out_path, const std::string& work_dir) {
  const fs::path out = OutTarget(out_path);
  SyncPath(work_dir);
  std::error_code ec;
  std::string how;
  if (!fs::exists(out, ec)) {
    if (::rename(work_dir.c_str(), out.c_str()) != 0) {
      throw IoError(out.string(),
                    std::string("cannot move the new out/ into place: ") + std::strerror(errno));
    }
    how = "rename";
  } else if (::renameat2(AT_FDCWD, work_dir.c_str(), AT_FDCWD, out.c_str(), RENAME_EXCHANGE) == 0) {
    // work_dir now holds the previous out/.
    RemoveOutTree(work_dir);
    how = "exchange";
  } else if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP || errno == EOPNOTSUPP) {
    std::string old_templ = (out.parent_path() / (out.filename().string() + ".old.XXXXXX")).string();
    std::vector<char> buf(old_templ.begin(), old_templ.end());
    buf.push_back('\0');
    if (!::mkdtemp(buf.data()))
      throw IoError(out.string(), std::string("cannot create its .old folder: ") + std::strerror(errno));
    const std::string old(buf.data());
    // rename(2) onto an empty folder replaces it.
    if (::rename(out.c_str(), old.c_str()) != 0) {
      throw IoError(out.string(),
                    std::string("cannot move the previous out/ aside: ") + std::strerror(errno));
    }
    if (::rename(work_dir.c_str(), out.c_str()) != 0) {
      const int e = errno;
      ::rename(old.c_str(), out.c_str());
      throw IoError(out.string(), std::string("cannot move the new out/ into place: ") + std::strerror(e));
    }
    RemoveOutTree(old);
    how = "two-renames";
  } else {
    throw IoError(out.string(), std::string("cannot swap in the new out/: ") + std::strerror(errno));
  }
  SyncPath(out.parent_path().string());
  return how;
}

}  // namespace rk::run

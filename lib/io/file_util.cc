#include "io/file_util.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <regex>
#include <sstream>

#include "io/csv_stream.h"
#include "io/error.h"
#include "io/run_record.h"

namespace rk::io {
namespace fs = std::filesystem;

bool IsStdStream(const std::string& path) { return path == "-"; }

std::string ReadFile(const std::string& path) {
  if (IsStdStream(path)) {
    std::ostringstream ss;
    ss << std::cin.rdbuf();
    std::string data = ss.str();
    RecordInputRead(path, data.size());
    return data;
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IoError(path, "is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path, std::string("cannot open for reading: ") + std::strerror(errno));
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw IoError(path, "read error");
  RecordInputRead(path, data.size());
  return data;
}

namespace {

std::string TempNameBeside(const std::string& final_path, int* fd_out) {
  fs::path p(final_path);
  fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::string templ = (dir / ("." + p.filename().string() + ".XXXXXX")).string();
  std::vector<char> buf(templ.begin(), templ.end());
  buf.push_back('\0');
  int fd = mkstemp(buf.data());
  if (fd < 0)
    throw IoError(final_path, std::string("cannot create a file in its folder: ") + std::strerror(errno));
  *fd_out = fd;
  return std::string(buf.data());
}

// "/dev/fd/N", "/proc/self/fd/N", "/proc/thread-self/fd/N", "/proc/<own pid>/fd/N" → N, else -1.
int OwnDescriptor(const std::string& path) {
  static const std::regex kFd(R"(^/(?:dev/fd|proc/(?:self|thread-self|(\d+))/fd)/(\d+)$)");
  std::smatch m;
  if (!std::regex_match(path, m, kFd)) return -1;
  if (m[1].matched && std::stol(m[1].str()) != static_cast<long>(::getpid())) return -1;
  return std::stoi(m[2].str());
}

// Follows a chain of symbolic links from `path` to the first name that is not a link (which may
// not exist). Stops early, returning the descriptor, at a link to one of this process's own
// descriptors: /proc/self/fd/N is a "magic" link whose text (pipe:[123], /dev/pts/0, a deleted
// file) is not a path to write to.
struct LinkEnd {
  std::string path;
  int fd = -1;
};
LinkEnd FollowLinks(const std::string& path) {
  std::string cur = path;
  for (int hops = 0; hops < 40; ++hops) {
    if (const int fd = OwnDescriptor(cur); fd >= 0) return {cur, fd};
    struct stat st {};
    if (::lstat(cur.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return {cur, -1};
    std::vector<char> buf(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 255) + 2);
    const ssize_t n = ::readlink(cur.c_str(), buf.data(), buf.size() - 1);
    if (n < 0) throw IoError(path, std::string("cannot read the link ") + cur + ": " + std::strerror(errno));
    fs::path target(std::string(buf.data(), static_cast<std::size_t>(n)));
    if (target.is_relative()) target = fs::path(cur).parent_path() / target;
    cur = target.lexically_normal().string();
  }
  throw IoError(path, "too many levels of symbolic links");
}

void WriteAll(int fd, std::string_view data, const std::string& name) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(name, std::string("write failed: ") + std::strerror(errno));
    }
    done += static_cast<std::size_t>(n);
  }
}

int OpenWriteThrough(const std::string& path) {
  // No O_CREAT: this path exists and is not a regular file; if it vanished meanwhile, creating a
  // regular file in its place is exactly what must not happen. No O_TRUNC: devices and FIFOs have
  // nothing to truncate.
  const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw IoError(path, std::string("cannot open for writing: ") + std::strerror(errno));
  return fd;
}

void WriteThrough(const std::string& path, const std::string& data) {
  const int fd = OpenWriteThrough(path);
  try {
    WriteAll(fd, data, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw IoError(path, std::string("write failed: ") + std::strerror(errno));
}

// The end of an atomic replacement: `fd`, the temporary file `tmp` beside `path` holding the whole data, is
// given its mode, flushed to disk, closed and renamed over `path`; on failure `tmp` is removed.
void FinishReplace(int fd, const std::string& tmp, const std::string& path) {
  // Files are created 0600 by mkstemp; give them the usual 0644 (less umask).
  mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    int e = errno;
    ::unlink(tmp.c_str());
    throw IoError(path, std::string("write failed: ") + std::strerror(e));
  }
  // Last check before the rename: a device or FIFO that appeared at the path since it was resolved is
  // never replaced.
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    ::unlink(tmp.c_str());
    throw IoError(path, "changed into something other than a regular file while being written; not replaced");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    int e = errno;
    ::unlink(tmp.c_str());
    throw IoError(path, std::string("cannot rename into place: ") + std::strerror(e));
  }
}

void ReplaceAtomically(const std::string& path, const std::string& data) {
  int fd = -1;
  std::string tmp = TempNameBeside(path, &fd);
  try {
    WriteAll(fd, data, path);
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  FinishReplace(fd, tmp, path);
}

// An unnamed temporary file (created and unlinked at once) in $TMPDIR, else /tmp, for OutputFile's spool.
int OpenSpool(const std::string& for_path) {
  const char* dir = std::getenv("TMPDIR");
  std::string templ = std::string(dir && *dir ? dir : "/tmp") + "/rk-output.XXXXXX";
  std::vector<char> buf(templ.begin(), templ.end());
  buf.push_back('\0');
  const int fd = ::mkstemp(buf.data());
  if (fd < 0) {
    throw IoError(for_path, std::string("cannot create a temporary file in ") + (dir && *dir ? dir : "/tmp") +
                                ": " + std::strerror(errno));
  }
  ::unlink(buf.data());
  return fd;
}

// Copies the spool `from` (from its start) to `to` through the one write loop.
void CopySpool(int from, int to, const std::string& name) {
  if (::lseek(from, 0, SEEK_SET) != 0) throw IoError(name, std::string("temporary file: ") + std::strerror(errno));
  std::vector<char> buf(std::size_t{1} << 20);
  for (;;) {
    const ssize_t n = ::read(from, buf.data(), buf.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(name, std::string("temporary file: ") + std::strerror(errno));
    }
    if (n == 0) return;
    WriteAll(to, std::string_view(buf.data(), static_cast<std::size_t>(n)), name);
  }
}

}  // namespace

OutputTarget ResolveOutput(const std::string& path) {
  if (IsStdStream(path)) return {OutputTarget::Kind::kDescriptor, STDOUT_FILENO, path};
  const LinkEnd end = FollowLinks(path);
  if (end.fd >= 0) return {OutputTarget::Kind::kDescriptor, end.fd, path};
  struct stat st {};
  if (::stat(end.path.c_str(), &st) != 0) {
    if (errno == ENOENT) return {OutputTarget::Kind::kReplace, -1, end.path};
    throw IoError(path, std::string("cannot examine: ") + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) return {OutputTarget::Kind::kReplace, -1, end.path};
  if (S_ISDIR(st.st_mode)) throw IoError(path, "is a folder, not a file");
  if (S_ISSOCK(st.st_mode)) throw IoError(path, "is a socket; cannot write a file there");
  return {OutputTarget::Kind::kWriteThrough, -1, path};
}

std::string ResolveOutputFolder(const std::string& path) {
  const LinkEnd end = FollowLinks(path);
  if (end.fd >= 0) throw IoError(path, "is a file descriptor, not a folder");
  return end.path;
}

void WriteFileAtomic(const std::string& path, const std::string& data) {
  const OutputTarget target = ResolveOutput(path);
  switch (target.kind) {
    case OutputTarget::Kind::kDescriptor:
      WriteToDescriptor(target.fd, data, path);
      return;
    case OutputTarget::Kind::kWriteThrough:
      WriteThrough(target.path, data);
      return;
    case OutputTarget::Kind::kReplace:
      ReplaceAtomically(target.path, data);
      return;
  }
}

OutputFile::OutputFile(const std::string& path) : path_(path), target_(ResolveOutput(path)) {
  if (target_.kind == OutputTarget::Kind::kReplace) {
    tmp_ = TempNameBeside(target_.path, &fd_);
  } else {
    fd_ = OpenSpool(path_);
  }
}

OutputFile::~OutputFile() {
  if (fd_ < 0) return;
  ::close(fd_);
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
}

void OutputFile::Write(std::string_view data) {
  RK_CHECK(fd_ >= 0, "OutputFile written after Commit");
  WriteAll(fd_, data, target_.kind == OutputTarget::Kind::kReplace ? target_.path : path_);
}

void OutputFile::Commit() {
  RK_CHECK(fd_ >= 0, "OutputFile committed twice");
  const int fd = fd_;
  fd_ = -1;  // from here FinishReplace (or the close below) owns it
  switch (target_.kind) {
    case OutputTarget::Kind::kReplace:
      FinishReplace(fd, tmp_, target_.path);
      return;
    case OutputTarget::Kind::kDescriptor:
      try {
        std::cout.flush();  // what std::cout buffered comes first, as in WriteToDescriptor
        CopySpool(fd, target_.fd, target_.fd == STDOUT_FILENO ? "<stdout>" : path_);
      } catch (...) {
        ::close(fd);
        throw;
      }
      ::close(fd);
      return;
    case OutputTarget::Kind::kWriteThrough: {
      int out = -1;
      try {
        out = OpenWriteThrough(target_.path);
        CopySpool(fd, out, target_.path);
      } catch (...) {
        ::close(fd);
        if (out >= 0) ::close(out);
        throw;
      }
      ::close(fd);
      if (::close(out) != 0) throw IoError(target_.path, std::string("write failed: ") + std::strerror(errno));
      return;
    }
  }
}

int StreamDescriptor(const std::string& path) {
  const OutputTarget target = ResolveOutput(path);
  return target.kind == OutputTarget::Kind::kDescriptor ? target.fd : -1;
}

void WriteToDescriptor(int fd, std::string_view data, const std::string& path) {
  // Whatever std::cout buffered must come first.
  std::cout.flush();
  WriteAll(fd, data, fd == STDOUT_FILENO ? "<stdout>" : path);
}

void CheckOutputNotInput(const std::string& output, const std::vector<std::string>& inputs) {
  if (IsStdStream(output)) return;
  ResolveOutput(output);  // a folder or a socket is refused now, before any work is done
  std::error_code ec;
  if (!fs::exists(output, ec)) return;
  for (const auto& in : inputs) {
    if (IsStdStream(in) || in.empty()) continue;
    if (fs::exists(in, ec) && fs::equivalent(output, in, ec)) {
      throw UsageError("output " + output + " is the input " + in + "; refusing to overwrite an input");
    }
  }
}

void MakeDirectories(const std::string& path) {
  std::error_code ec;
  fs::create_directories(path, ec);
  if (ec) throw IoError(path, "cannot create folder: " + ec.message());
}

void RefuseLink(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return;  // absent (or unreadable: the open or write says why)
  if (S_ISLNK(st.st_mode)) {
    throw IoError(path, "is a symbolic link; a file the tool makes for itself is never written through a link "
                        "(remove the link)");
  }
  if (!S_ISREG(st.st_mode)) throw IoError(path, "is not a regular file (remove it)");
}

void WriteOwnFileAtomic(const std::string& path, const std::string& data) {
  RefuseLink(path);
  ReplaceAtomically(path, data);
}

int OpenOwnFile(const std::string& path, int flags, unsigned mode) {
  RefuseLink(path);
  const int fd = ::open(path.c_str(), flags | O_NOFOLLOW | O_CLOEXEC, static_cast<mode_t>(mode));
  if (fd >= 0) return fd;
  const int e = errno;
  if (e == ELOOP) RefuseLink(path);  // made a link in between
  throw IoError(path, std::string("cannot open: ") + std::strerror(e));
}

bool IsInsideFolder(const std::string& folder, const std::string& path) {
  std::error_code ec1, ec2;
  const fs::path base = fs::weakly_canonical(fs::absolute(folder), ec1);
  const fs::path p = fs::weakly_canonical(fs::absolute(path), ec2);
  if (ec1 || ec2) return false;
  auto b = base.begin(), i = p.begin();
  for (; b != base.end(); ++b, ++i) {
    if (i == p.end() || *i != *b) return false;
  }
  return i != p.end();
}

}  // namespace rk::io

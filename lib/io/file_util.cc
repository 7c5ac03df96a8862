#include "io/file_util.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

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

std::string TempNameBeside(const std::string& final_path, const std::string& suffix, int* fd_out) {
  fs::path p(final_path);
  fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::string templ = (dir / ("." + p.filename().string() + ".XXXXXX")).string();
  std::vector<char> buf(templ.begin(), templ.end());
  buf.push_back('\0');
  int fd = mkstemp(buf.data());
  if (fd < 0) throw IoError(final_path, std::string("cannot create a file in its folder: ") + std::strerror(errno));
  std::string name(buf.data());
  if (!suffix.empty()) {
    // Writers such as ffmpeg pick the container from the extension.
    std::string with_suffix = name + suffix;
    if (std::rename(name.c_str(), with_suffix.c_str()) != 0) {
      ::close(fd);
      ::unlink(name.c_str());
      throw IoError(final_path, "cannot create a temporary file");
    }
    name = with_suffix;
  }
  *fd_out = fd;
  return name;
}

}  // namespace

void WriteFileAtomic(const std::string& path, const std::string& data) {
  if (IsStdStream(path)) {
    std::cout.write(data.data(), static_cast<std::streamsize>(data.size()));
    std::cout.flush();
    if (!std::cout) throw IoError("<stdout>", "write failed");
    return;
  }
  int fd = -1;
  std::string tmp = TempNameBeside(path, "", &fd);
  std::size_t done = 0;
  while (done < data.size()) {
    ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      int e = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      throw IoError(path, std::string("write failed: ") + std::strerror(e));
    }
    done += static_cast<std::size_t>(n);
  }
  // Files are created 0600 by mkstemp; give them the usual 0644 (less umask).
  mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    int e = errno;
    ::unlink(tmp.c_str());
    throw IoError(path, std::string("write failed: ") + std::strerror(e));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    int e = errno;
    ::unlink(tmp.c_str());
    throw IoError(path, std::string("cannot rename into place: ") + std::strerror(e));
  }
}

PendingFile::PendingFile(const std::string& final_path, const std::string& suffix) : final_path_(final_path) {
  int fd = -1;
  temp_path_ = TempNameBeside(final_path, suffix, &fd);
  mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  ::close(fd);
}

PendingFile::~PendingFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(temp_path_, ec);
  }
}

void PendingFile::Commit() {
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
    throw IoError(final_path_, std::string("cannot rename into place: ") + std::strerror(errno));
  }
  committed_ = true;
}

void CheckOutputNotInput(const std::string& output, const std::vector<std::string>& inputs) {
  if (IsStdStream(output)) return;
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

}  // namespace rk::io

#include "run/run_log.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "io/error.h"
#include "io/file_util.h"

namespace rk::run {
namespace fs = std::filesystem;

namespace {
constexpr std::uintmax_t kLogRotateBytes = 1u << 20;  // rk-run.log is rotated to rk-run.log.1 past 1 MiB
}  // namespace

std::string UtcNow() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[40];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  char out[48];
  std::snprintf(out, sizeof out, "%s.%03dZ", buf, static_cast<int>(ms));
  return out;
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double Round3(double x) { return std::round(x * 1000.0) / 1000.0; }

std::string Fmt(double x, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

RunLog::RunLog(const std::string& path) {
  const fs::path p(path);
  io::RefuseLink(p.string());  // never appended through a link (threat model)
  std::error_code ec;
  if (fs::exists(p, ec) && fs::file_size(p, ec) > kLogRotateBytes) {
    fs::rename(p, path + ".1", ec);
  }
  fd_ = io::OpenOwnFile(p.string(), O_WRONLY | O_CREAT | O_APPEND);
}

RunLog::~RunLog() {
  if (fd_ >= 0) ::close(fd_);
}

void RunLog::Line(const std::string& text) {
  const std::string s = UtcNow() + " [" + std::to_string(::getpid()) + "] " + text + "\n";
  [[maybe_unused]] const ssize_t n = ::write(fd_, s.data(), s.size());  // O_APPEND: one write per line
}

}  // namespace rk::run

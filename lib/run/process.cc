#include "run/process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string_view>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>

#include "io/error.h"

namespace rk::run {
namespace fs = std::filesystem;

namespace {

volatile sig_atomic_t g_stop_signal = 0;

void OnStopSignal(int sig) { g_stop_signal = sig; }

// Start times of running children, for their wall time.
std::map<pid_t, std::chrono::steady_clock::time_point>& StartTimes() {
  static std::map<pid_t, std::chrono::steady_clock::time_point> m;
  return m;
}

constexpr std::size_t kCapturedTailBytes = 64 * 1024;  // of a child's output kept in ChildResult::output

// Children whose output goes to a memfd (ChildSpec::capture): pid → the memfd and the log it belongs in.
struct Captured {
  int fd = -1;
  std::string log_path;
};
std::map<pid_t, Captured>& CapturedChildren() {
  static std::map<pid_t, Captured> m;
  return m;
}

void WriteAll(int fd, const char* s) {
  std::size_t n = std::strlen(s);
  while (n > 0) {
    const ssize_t w = ::write(fd, s, n);
    if (w <= 0) return;
    s += w;
    n -= static_cast<std::size_t>(w);
  }
}

}  // namespace

std::string ChildResult::Describe() const {
  if (signal != 0) {
    const char* name = ::strsignal(signal);
    return "killed by signal " + std::to_string(signal) + " (" + (name ? name : "?") + ")";
  }
  if (exit_code == 127) return "could not be started (exit code 127)";
  return "exited with code " + std::to_string(exit_code);
}

pid_t StartChild(const ChildSpec& spec) {
  if (spec.argv.empty()) throw IoError("<child>", "empty command line");
  // Everything the child needs is prepared before fork: after it only async-signal-safe calls.
  std::vector<char*> argv;
  for (const auto& a : spec.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  // The child's environment: rk-run's, with spec.env's entries added or replacing the same name.
  std::vector<char*> envp;
  for (char** e = environ; e && *e; ++e) {
    const std::string_view entry(*e);
    const auto eq = entry.find('=');
    bool replaced = false;
    for (const auto& x : spec.env) replaced = replaced || (eq != std::string_view::npos && x.compare(0, eq + 1, entry.substr(0, eq + 1)) == 0);
    if (!replaced) envp.push_back(*e);
  }
  for (const auto& x : spec.env) envp.push_back(const_cast<char*>(x.c_str()));
  envp.push_back(nullptr);
  const std::string log = spec.log_path.empty() ? std::string("/dev/null") : spec.log_path;
  const int memfd = spec.capture ? ::memfd_create("rk-run-step", MFD_CLOEXEC) : -1;
  if (spec.capture && memfd < 0) {
    throw IoError(spec.argv[0], std::string("cannot start: memfd_create failed: ") + std::strerror(errno));
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    if (memfd >= 0) ::close(memfd);
    throw IoError(spec.argv[0], std::string("cannot start: fork failed: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(126);  // rk-run died before prctl took effect
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = memfd >= 0 ? ::dup(memfd) : ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (in < 0 || out < 0) ::_exit(125);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(out, 2);
    if (in > 2) ::close(in);
    if (out > 2) ::close(out);
    if (!spec.cwd.empty() && ::chdir(spec.cwd.c_str()) != 0) {
      WriteAll(2, "rk-run: error: cannot enter the working folder of the step\n");
      ::_exit(125);
    }
    ::execve(argv[0], argv.data(), envp.data());
    WriteAll(2, "rk-run: error: cannot execute ");
    WriteAll(2, argv[0]);
    WriteAll(2, ": ");
    WriteAll(2, ::strerror(errno));
    WriteAll(2, "\n");
    ::_exit(127);
  }
  StartTimes()[pid] = std::chrono::steady_clock::now();
  if (memfd >= 0) CapturedChildren()[pid] = {memfd, spec.log_path};
  return pid;
}

std::string CollectChildOutput(pid_t pid, std::string* log_error) {
  auto it = CapturedChildren().find(pid);
  if (it == CapturedChildren().end()) return "";
  const Captured c = it->second;
  CapturedChildren().erase(it);
  std::string text;
  char buf[65536];
  for (off_t at = 0;;) {
    const ssize_t n = ::pread(c.fd, buf, sizeof buf, at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    at += n;
    text.append(buf, static_cast<std::size_t>(n));
  }
  ::close(c.fd);
  std::string why;
  if (!c.log_path.empty() && !text.empty()) {
    const int fd = ::open(c.log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    std::size_t done = 0;
    while (fd >= 0 && done < text.size()) {
      const ssize_t w = ::write(fd, text.data() + done, text.size() - done);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        why = std::strerror(w < 0 ? errno : ENOSPC);
        break;
      }
      done += static_cast<std::size_t>(w);
    }
    if (fd < 0) why = std::strerror(errno);
    if (fd >= 0 && ::close(fd) != 0 && why.empty()) why = std::strerror(errno);
  }
  if (log_error) *log_error = why.empty() ? "" : c.log_path + ": " + why;
  if (text.size() > kCapturedTailBytes) text.erase(0, text.size() - kCapturedTailBytes);
  return text;
}

bool WaitAnyChild(ChildResult* result) {
  for (;;) {
    if (g_stop_signal != 0) return false;
    int status = 0;
    struct rusage ru {};
    const pid_t pid = ::wait4(-1, &status, 0, &ru);
    if (pid < 0) {
      if (errno == EINTR) continue;  // the flag is checked at the top
      return false;                  // ECHILD: nothing to wait for
    }
    ChildResult r;
    r.pid = pid;
    if (WIFEXITED(status)) {
      r.exit_code = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
      r.signal = WTERMSIG(status);
    }
    auto it = StartTimes().find(pid);
    if (it != StartTimes().end()) {
      r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second).count();
      StartTimes().erase(it);
    }
    r.user_s = static_cast<double>(ru.ru_utime.tv_sec) + 1e-6 * static_cast<double>(ru.ru_utime.tv_usec);
    r.sys_s = static_cast<double>(ru.ru_stime.tv_sec) + 1e-6 * static_cast<double>(ru.ru_stime.tv_usec);
    r.max_rss_kb = ru.ru_maxrss;
    r.output = CollectChildOutput(pid, &r.log_error);
    *result = r;
    return true;
  }
}

int RunAndCapture(const std::vector<std::string>& args, std::string* stdout_text) {
  if (args.empty()) throw IoError("<child>", "empty command line");
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw IoError(args[0], std::string("cannot start: ") + std::strerror(errno));
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw IoError(args[0], std::string("cannot start: fork failed: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(126);
    const int in = ::open("/dev/null", O_RDWR);
    if (in >= 0) {
      ::dup2(in, 0);
      ::dup2(in, 2);
    }
    ::dup2(fds[1], 1);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  stdout_text->clear();
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    stdout_text->append(buf, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void InstallStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: wait4 returns EINTR
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
  ::sigaction(SIGHUP, &sa, nullptr);
}

int StopSignal() { return g_stop_signal; }

std::string SelfDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return "";
  return exe.parent_path().string();
}

std::string FindExecutable(const std::string& name, const std::vector<std::string>& dirs) {
  const auto ok = [](const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
  };
  for (const auto& d : dirs) {
    if (d.empty()) continue;
    const fs::path p = fs::path(d) / name;
    if (ok(p)) return fs::absolute(p).lexically_normal().string();
  }
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::string s(path);
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = s.find(':', start);
    const std::string dir = s.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!dir.empty()) {
      const fs::path p = fs::path(dir) / name;
      if (ok(p)) return fs::absolute(p).lexically_normal().string();
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return "";
}

}  // namespace rk::run

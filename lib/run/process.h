// Child processes for rk-run: the tools run as separate programs (fork/exec), each with its
// output and errors in a log file, stdin from /dev/null, and PR_SET_PDEATHSIG so that a tool never
// outlives the rk-run that started it (a kill -9 of rk-run, or of rk-nightly above it, stops the
// whole tree instead of leaving orphans that hold CPU). Single-threaded by design: PDEATHSIG fires
// when the *thread* that forked exits, so children are started and reaped from the main thread.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace rk::run {

struct ChildSpec {
  std::vector<std::string> argv;  // argv[0] = path of the executable (absolute)
  std::string cwd;                // working folder of the child
  std::string log_path;           // stdout and stderr are appended here ("" = /dev/null)
  std::vector<std::string> env;   // "NAME=VALUE" added to (or replacing in) rk-run's environment
  // Keep the output in memory too: the child writes into an in-memory file (memfd) that is appended to
  // log_path when it ends and returned in ChildResult::output, so that a tool's last error line is known
  // even when its log cannot be written (a full disk).
  bool capture = false;
};

struct ChildResult {
  pid_t pid = -1;
  int exit_code = -1;  // 0..255 when the child exited, -1 when a signal ended it
  int signal = 0;      // the signal that ended it, 0 if it exited
  double wall_s = 0.0, user_s = 0.0, sys_s = 0.0;
  long max_rss_kb = 0;
  std::string output;  // ChildSpec::capture: the child's stdout and stderr (its last 64 KiB)
  std::string log_error;  // ChildSpec::capture: why the output could not be appended to the log ("" = it was)
  std::string Describe() const;  // "exited with code 3", "killed by signal 9 (Killed)"
};

// Starts the child; throws IoError if fork fails. The exec failure of a missing or non-executable
// program is reported as exit code 127 (the child writes why into its log).
pid_t StartChild(const ChildSpec& spec);

// A child reaped elsewhere (waitpid after a stop signal): its captured output, appended to its log, and the
// memfd released. "" when it was not captured.
std::string CollectChildOutput(pid_t pid, std::string* log_error = nullptr);

// Waits for any child. Returns false (and leaves *result alone) when interrupted by a stop signal
// (see InstallStopHandlers) or when there are no children.
bool WaitAnyChild(ChildResult* result);

// Runs a program to completion and captures its stdout (tests, `--version`). Returns its exit code
// (-1 if a signal ended it). Throws IoError if it cannot be started.
int RunAndCapture(const std::vector<std::string>& argv, std::string* stdout_text);

// SIGINT, SIGTERM and SIGHUP set a flag instead of killing rk-run, so it can stop its children, remove
// its temporary folder and release the trial lock. StopSignal() is the signal received, or 0.
void InstallStopHandlers();
int StopSignal();

// Folder of the running executable (/proc/self/exe), "" if unknown.
std::string SelfDir();
// The first executable file `name` in `dirs`, then on PATH; "" if none.
std::string FindExecutable(const std::string& name, const std::vector<std::string>& dirs);

}  // namespace rk::run

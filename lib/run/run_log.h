// rk-run's clock, number formatting and TRIAL/rk-run.log (docs/rk-run.md, "What a trial folder holds").
#pragma once

#include <chrono>
#include <string>

namespace rk::run {

// Now in UTC, "2026-03-01T12:00:00.123Z".
std::string UtcNow();
// Seconds since `since`.
double Seconds(std::chrono::steady_clock::time_point since);
// x rounded to 3 decimals (the timings of the reports).
double Round3(double x);
// x with `decimals` decimals ("%.*f").
std::string Fmt(double x, int decimals = 2);

// TRIAL/rk-run.log: one timestamped line per event, appended (rotated past 1 MiB).
class RunLog {
 public:
  // Opens `path` (TRIAL/rk-run.log) for appending, never through a link; past 1 MiB it is first renamed
  // to PATH.1. Throws IoError when the log cannot be opened.
  explicit RunLog(const std::string& path);
  ~RunLog();
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;
  void Line(const std::string& text);

 private:
  int fd_ = -1;
};

}  // namespace rk::run

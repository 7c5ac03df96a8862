// Progress of long runs (SPEC.md §4: on stderr only when it is a terminal, never with --quiet).
#pragma once

#include <cstdint>
#include <string>

namespace rk::io {

// Progress of a long run on a terminal (SPEC.md §4: stderr only when it is a terminal, never with
// --quiet): "rk-extract: 1200/6000 frames (20%), 410/s, ETA 0:12", redrawn in place at most
// kRedrawsPerSecond times a second. total 0 = unknown (done and rate only). Finish() clears the line,
// so that the tool's own closing summary line starts on a clean line.
// For a parent that runs the tool (rk-run shows its running step's progress): when the environment
// names a file in kProgressFileEnv, the meter also rewrites that file with one line "DONE TOTAL UNIT"
// at the same pace, whether or not stderr is a terminal.
class ProgressMeter {
 public:
  static constexpr double kRedrawsPerSecond = 5.0;
  static constexpr const char* kProgressFileEnv = "RK_PROGRESS_FILE";
  ProgressMeter(std::string tool, std::string unit, std::int64_t total, bool enabled);
  ~ProgressMeter() { Finish(); }
  ProgressMeter(const ProgressMeter&) = delete;
  ProgressMeter& operator=(const ProgressMeter&) = delete;
  void set_total(std::int64_t total) { total_ = total; }
  void Update(std::int64_t done);
  void Finish();

 private:
  std::string tool_, unit_;
  std::int64_t total_ = 0;
  bool enabled_ = false;
  std::string progress_file_;  // kProgressFileEnv, empty when not set
  bool drawn_ = false;
  double start_s_ = 0.0;
  double last_draw_s_ = -1.0;
};
// The progress line for `done` of `total` (0 = unknown) after `elapsed_s` seconds: done/total, percent,
// rate per second, ETA as m:ss or h:mm:ss (ProgressMeter's text; a pure function for tests).
std::string FormatProgress(const std::string& tool, const std::string& unit, std::int64_t done, std::int64_t total,
                           double elapsed_s);

}  // namespace rk::io

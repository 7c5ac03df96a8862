// rk-run's display of its running steps' own progress (issue 19): each tool that reports progress
// (io::ProgressMeter) is started with RK_PROGRESS_FILE naming a file in the working folder's steps/,
// which it rewrites with "DONE TOTAL UNIT"; a watcher thread reads the files of the running steps about
// twice a second and hands one line to RunOptions::step_progress:
//   "extract-az: 1200/6000 frames (20%), 410/s, ETA 0:12 | locate-az: ..."
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace rk::run::internal {

class StepProgressFiles {
 public:
  static constexpr double kRedrawS = 0.5;  // watcher period (s)

  // Starts the watcher; `show` gets each line (from the watcher thread). Empty `show`: nothing runs.
  void Start(std::function<void(const std::string&)> show);
  // Stops and joins the watcher (also on destruction) and removes the files still listed.
  void Stop();
  ~StepProgressFiles() { Stop(); }

  bool active() const { return static_cast<bool>(show_); }
  // The file a step's tool is to write ("" when not active); the environment entry for it.
  std::string Add(const std::string& step_id, const std::string& file);
  void Remove(const std::string& step_id);
  // The line for the running steps now (pure reading of the files; for tests too).
  std::string Line() const;

 private:
  void Watch();
  struct Entry {
    std::string file;
    std::chrono::steady_clock::time_point start;
  };
  mutable std::mutex mu_;
  std::map<std::string, Entry> files_;
  std::function<void(const std::string&)> show_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace rk::run::internal

// Line logs of a trial directory that grow while recording: range.csv, turret.csv,
// <camera>/frames.csv and events.log.
//
// These are the one exception to the suite's rule that outputs are written atomically (whole file
// to a temporary, then renamed): a recording must be on disk while it happens. So they are
// append-only: the header is written and synced when the file is created, then each line goes to
// the file with a single write as it is produced (DurableFile), and the Syncer makes it durable
// within the sync period. A kill -9 leaves whole lines; a power cut can leave a torn last line,
// which `rk-capture recover` removes.
//
// Threads that stamp samples (serial devices, camera grabbers) must never wait for the disk (a
// write can block for a long time when the page cache is throttled), so they Post() lines: a
// worker thread of the log writes them in order as soon as it can.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "capture/durable_file.h"

namespace rk::capture {

class AppendLog {
 public:
  // Creates `path` (never replacing a file) and writes `header` (lines, each ending '\n'),
  // synced at once. Throws IoError if it cannot be created.
  AppendLog(const std::string& path, const std::string& header, Syncer* syncer);
  // Writes what was posted, then stops the worker.
  ~AppendLog();
  AppendLog(const AppendLog&) = delete;
  AppendLog& operator=(const AppendLog&) = delete;

  // Appends one line ('\n' added) now. Thread-safe. False with the reason if it could not be
  // written (nothing of it is then in the file).
  bool Append(std::string_view line, std::string* why);
  // Queues one line for the worker thread and returns at once; the outcome of each posted line is
  // passed to the result callback (on the worker thread).
  void Post(std::string line);
  // Called (on the worker thread) after each posted line: the line, ok, or the reason it was not
  // written. Set it before the first Post.
  void set_on_result(std::function<void(const std::string& line, bool ok, const std::string& why)> f) {
    on_result_ = std::move(f);
  }
  // Waits until every posted line is written (or failed).
  void Drain();

  std::int64_t lines() const { return lines_.load(); }
  std::int64_t failed() const { return failed_.load(); }
  const std::string& path() const { return file_->path(); }

 private:
  void Worker();
  std::shared_ptr<DurableFile> file_;
  std::mutex mutex_;
  std::atomic<std::int64_t> lines_{0};
  std::atomic<std::int64_t> failed_{0};
  std::string buffer_;
  // Posting.
  std::mutex queue_mutex_;
  std::condition_variable queue_cv_, drained_cv_;
  std::deque<std::string> queue_;
  bool stopping_ = false;
  bool busy_ = false;
  std::thread worker_;
  std::function<void(const std::string&, bool, const std::string&)> on_result_;
};

// Fixed-point text ("%.*f") without locale effects; "" for NaN and infinities.
std::string FormatFixed(double value, int decimals);

}  // namespace rk::capture

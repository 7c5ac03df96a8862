// Line logs of a trial directory that grow while recording: range.csv, turret.csv,
// <camera>/frames.csv and events.log.
//
// These are the one exception to the suite's rule that outputs are written atomically (whole file
// to a temporary, then renamed): a recording must be on disk while it happens. So they are
// append-only: the header is written and synced when the file is created, then each line goes to
// the file with a single write as it is produced (DurableFile), and the Syncer makes it durable
// within the sync period. A kill -9 leaves whole lines; a power cut can leave a torn last line,
// which `rk-capture recover` removes.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "capture/durable_file.h"

namespace rk::capture {

class AppendLog {
 public:
  // Creates `path` (never replacing a file) and writes `header` (lines, each ending '\n'),
  // synced at once. Throws IoError if it cannot be created.
  AppendLog(const std::string& path, const std::string& header, Syncer* syncer);
  // Appends one line ('\n' added). Thread-safe. False with the reason if it could not be written
  // (nothing of it is then in the file).
  bool Append(std::string_view line, std::string* why);
  std::int64_t lines() const { return lines_.load(); }
  std::int64_t failed() const { return failed_.load(); }
  const std::string& path() const { return file_->path(); }

 private:
  std::shared_ptr<DurableFile> file_;
  std::mutex mutex_;
  std::atomic<std::int64_t> lines_{0};
  std::atomic<std::int64_t> failed_{0};
  std::string buffer_;
};

// Fixed-point text ("%.*f") without locale effects.
std::string FormatFixed(double value, int decimals);

}  // namespace rk::capture

// Append-only files that survive a kill -9 and (within the sync period) a power cut, and stay
// readable when the disk fills up.
//
// - Every record (a CSV line, a video frame) is written with one pwritev(2) at the end of the file,
//   straight from the caller's buffer: nothing waits in a user-space buffer, so a kill -9 loses
//   only records not yet handed over. A short write (disk full, RLIMIT_FSIZE) is cut back with
//   ftruncate, so a file always ends at a record boundary.
// - A Syncer thread calls fdatasync on every open file once per period (≤ 1 s), so a power cut
//   loses at most that period; video files start write-back after each frame (sync_file_range)
//   so the fdatasync finds little left to do, and synced video pages are dropped from the page
//   cache (posix_fadvise DONTNEED) instead of evicting everything else at 200 MB/s.
// - The Syncer also measures the free space of the trial's file system (statvfs) each period.
#pragma once

#include <sys/uio.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace rk::capture {

class DurableFile {
 public:
  // Creates `path`; refuses to replace an existing file (O_EXCL). nullptr + reason on failure.
  static std::shared_ptr<DurableFile> Create(const std::string& path, bool video, std::string* why);
  ~DurableFile();
  DurableFile(const DurableFile&) = delete;
  DurableFile& operator=(const DurableFile&) = delete;

  // Appends the parts as one record, all or nothing. False with the reason (e.g. "No space left on
  // device") on failure; the file is then as before the call.
  bool Append(const iovec* parts, int count, std::string* why);
  bool Append(std::string_view data, std::string* why);
  // Cuts the file back to `bytes` (to undo the last record).
  bool TruncateTo(std::int64_t bytes, std::string* why);
  // Starts write-back of the bytes appended since the last call, without waiting (video files).
  void StartWriteback();
  // fdatasync, then (video) drops the synced pages from the page cache.
  bool Sync(std::string* why);

  std::int64_t size() const { return size_.load(); }
  const std::string& path() const { return path_; }
  // errno of the last failed Append (EFBIG: the file reached the size limit; ENOSPC: disk full).
  int last_error() const { return last_error_; }
  // No more appends will come: the Syncer syncs it once more and lets it go.
  void Retire() { retired_.store(true); }
  bool retired() const { return retired_.load(); }

 private:
  DurableFile(std::string path, int fd, bool video) : path_(std::move(path)), fd_(fd), video_(video) {}
  std::string path_;
  int fd_ = -1;
  bool video_ = false;
  std::mutex append_mutex_;
  std::atomic<std::int64_t> size_{0};
  std::int64_t writeback_from_ = 0;
  std::int64_t dropped_until_ = 0;  // page-cache drop done up to here (Syncer thread only)
  std::atomic<bool> retired_{false};
  int last_error_ = 0;
};

class Syncer {
 public:
  // Syncs every `period_s` seconds; measures free space under `dir`.
  Syncer(std::string dir, double period_s);
  ~Syncer();
  void Start();
  // Final pass (every file synced, directories too) and thread end.
  void Stop();

  void Add(std::shared_ptr<DurableFile> file);
  // The folder's entries changed (a file created or renamed): fsync it at the next pass.
  void DirectoryChanged(const std::string& dir);
  // Runs one pass now (also used by tests).
  void SyncNow();

  // Free bytes for unprivileged writers under `dir`: the last pass's reading minus what was noted as
  // written since (-1 if unknown).
  std::int64_t free_bytes() const;
  // Bytes just written (video frames), so that free_bytes() follows a fast writer between passes.
  void NoteWritten(std::int64_t bytes) { written_since_probe_ += bytes; }
  // Sync failures (EIO, ENOSPC on write-back) are passed here.
  void set_on_error(std::function<void(const std::string&)> f) { on_error_ = std::move(f); }
  // Replaces the free-space probe (tests).
  void set_free_space_probe(std::function<std::int64_t()> f) { probe_ = std::move(f); }
  std::int64_t passes() const { return passes_.load(); }
  double max_pass_s() const;

 private:
  void Loop();
  std::string dir_;
  double period_s_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stopping_ = false;
  std::vector<std::shared_ptr<DurableFile>> files_;
  std::set<std::string> dirs_;
  std::thread thread_;
  std::mutex pass_mutex_;
  std::atomic<std::int64_t> free_bytes_{-1};
  std::atomic<std::int64_t> written_since_probe_{0};
  std::atomic<std::int64_t> passes_{0};
  std::atomic<std::int64_t> max_pass_ns_{0};
  std::function<void(const std::string&)> on_error_;
  std::function<std::int64_t()> probe_;
};

// fsyncs a folder (its entries: created and renamed files). False with the reason on failure.
bool SyncDirectory(const std::string& dir, std::string* why);

}  // namespace rk::capture

#include "capture/durable_file.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <chrono>
#include <cstring>

#include "capture/clock.h"

namespace rk::capture {

std::shared_ptr<DurableFile> DurableFile::Create(const std::string& path, bool video, std::string* why) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (why) *why = "cannot create " + path + ": " + std::strerror(errno);
    return nullptr;
  }
  return std::shared_ptr<DurableFile>(new DurableFile(path, fd, video));
}

DurableFile::~DurableFile() {
  if (fd_ >= 0) ::close(fd_);
}

bool DurableFile::Append(const iovec* parts, int count, std::string* why) {
  std::lock_guard<std::mutex> lock(append_mutex_);
  std::size_t total = 0;
  for (int i = 0; i < count; ++i) total += parts[i].iov_len;
  const std::int64_t start = size_.load();
  std::size_t done = 0;
  std::vector<iovec> rest(parts, parts + count);
  int first = 0;
  while (done < total) {
    const ssize_t n = ::pwritev(fd_, rest.data() + first, count - first, static_cast<off_t>(start + done));
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      last_error_ = e;
      if (done > 0 && ::ftruncate(fd_, static_cast<off_t>(start)) != 0) {
        // Could not cut back: keep the size consistent with the file so later records stay aligned.
        size_.store(start + static_cast<std::int64_t>(done));
        if (why) *why = std::string(std::strerror(e)) + " (and the partial record could not be removed)";
        return false;
      }
      if (why) *why = std::strerror(e);
      return false;
    }
    if (n == 0) {
      if (done > 0) (void)!::ftruncate(fd_, static_cast<off_t>(start));
      if (why) *why = "write made no progress";
      return false;
    }
    done += static_cast<std::size_t>(n);
    // Advance the iovec window past what was written.
    std::size_t skip = static_cast<std::size_t>(n);
    while (first < count && skip >= rest[first].iov_len) {
      skip -= rest[first].iov_len;
      ++first;
    }
    if (first < count && skip > 0) {
      rest[first].iov_base = static_cast<char*>(rest[first].iov_base) + skip;
      rest[first].iov_len -= skip;
    }
  }
  size_.store(start + static_cast<std::int64_t>(total));
  return true;
}

bool DurableFile::Append(std::string_view data, std::string* why) {
  iovec v{const_cast<char*>(data.data()), data.size()};
  return Append(&v, 1, why);
}

bool DurableFile::TruncateTo(std::int64_t bytes, std::string* why) {
  std::lock_guard<std::mutex> lock(append_mutex_);
  if (::ftruncate(fd_, static_cast<off_t>(bytes)) != 0) {
    if (why) *why = std::string("cannot truncate ") + path_ + ": " + std::strerror(errno);
    return false;
  }
  size_.store(bytes);
  if (writeback_from_ > bytes) writeback_from_ = bytes;
  return true;
}

void DurableFile::StartWriteback() {
  const std::int64_t end = size_.load();
  if (end > writeback_from_) {
    ::sync_file_range(fd_, writeback_from_, end - writeback_from_, SYNC_FILE_RANGE_WRITE);
    writeback_from_ = end;
  }
}

bool DurableFile::Sync(std::string* why) {
  const std::int64_t end = size_.load();
  if (::fdatasync(fd_) != 0) {
    if (why) *why = "fdatasync " + path_ + ": " + std::strerror(errno);
    return false;
  }
  if (video_ && end > dropped_until_) {
    ::posix_fadvise(fd_, dropped_until_, end - dropped_until_, POSIX_FADV_DONTNEED);
    dropped_until_ = end;
  }
  return true;
}

bool SyncDirectory(const std::string& dir, std::string* why) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    if (why) *why = "cannot open folder " + dir + ": " + std::strerror(errno);
    return false;
  }
  const bool ok = ::fsync(fd) == 0;
  if (!ok && why) *why = "fsync folder " + dir + ": " + std::strerror(errno);
  ::close(fd);
  return ok;
}

Syncer::Syncer(std::string dir, double period_s) : dir_(std::move(dir)), period_s_(period_s) {}

Syncer::~Syncer() { Stop(); }

void Syncer::Start() {
  SyncNow();  // first free-space reading before anything is written
  thread_ = std::thread([this] { Loop(); });
}

void Syncer::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ && !thread_.joinable()) return;
    stopping_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
  SyncNow();
}

void Syncer::Add(std::shared_ptr<DurableFile> file) {
  std::lock_guard<std::mutex> lock(mutex_);
  files_.push_back(std::move(file));
}

void Syncer::DirectoryChanged(const std::string& dir) {
  std::lock_guard<std::mutex> lock(mutex_);
  dirs_.insert(dir);
}

std::int64_t Syncer::free_bytes() const {
  const std::int64_t f = free_bytes_.load();
  if (f < 0) return f;
  return std::max<std::int64_t>(0, f - written_since_probe_.load());
}

double Syncer::max_pass_s() const { return static_cast<double>(max_pass_ns_.load()) * 1e-9; }

void Syncer::SyncNow() {
  std::lock_guard<std::mutex> pass(pass_mutex_);
  const std::int64_t t0 = MonoNowNs();
  std::vector<std::shared_ptr<DurableFile>> files;
  std::set<std::string> dirs;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // A retired file is synced one last time in this pass and then let go.
    files = files_;
    std::vector<std::shared_ptr<DurableFile>> keep;
    for (auto& f : files_) {
      if (!f->retired()) keep.push_back(f);
    }
    files_.swap(keep);
    dirs.swap(dirs_);
  }
  for (auto& f : files) {
    std::string why;
    if (!f->Sync(&why) && on_error_) on_error_(why);
  }
  for (const auto& d : dirs) {
    std::string why;
    if (!SyncDirectory(d, &why) && on_error_) on_error_(why);
  }
  written_since_probe_.store(0);  // reset before the reading, so nothing written after it is lost
  if (probe_) {
    free_bytes_.store(probe_());
  } else {
    struct statvfs s {};
    if (::statvfs(dir_.c_str(), &s) == 0) {
      free_bytes_.store(static_cast<std::int64_t>(s.f_bavail) * static_cast<std::int64_t>(s.f_frsize));
    }
  }
  ++passes_;
  const std::int64_t dt = MonoNowNs() - t0;
  if (dt > max_pass_ns_.load()) max_pass_ns_.store(dt);
}

void Syncer::Loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    cv_.wait_for(lock, std::chrono::duration<double>(period_s_));
    if (stopping_) break;
    lock.unlock();
    SyncNow();
    lock.lock();
  }
}

}  // namespace rk::capture

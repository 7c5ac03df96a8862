#include "capture/append_log.h"

#include <cmath>
#include <cstdio>

#include "io/error.h"

namespace rk::capture {

std::string FormatFixed(double value, int decimals) {
  if (!std::isfinite(value)) return "";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, value);
  return b;
}

AppendLog::AppendLog(const std::string& path, const std::string& header, Syncer* syncer) {
  std::string why;
  file_ = DurableFile::Create(path, false, &why);
  if (!file_) throw IoError(path, why);
  if (!header.empty() && (!file_->Append(header, &why) || !file_->Sync(&why))) throw IoError(path, why);
  if (syncer) syncer->Add(file_);
}

AppendLog::~AppendLog() {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    stopping_ = true;
  }
  queue_cv_.notify_all();
  if (worker_.joinable()) worker_.join();
}

bool AppendLog::Append(std::string_view line, std::string* why) {
  std::lock_guard<std::mutex> lock(mutex_);
  buffer_.assign(line);
  buffer_.push_back('\n');
  if (!file_->Append(buffer_, why)) {
    ++failed_;
    return false;
  }
  ++lines_;
  return true;
}

void AppendLog::Post(std::string line) {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queue_.push_back(std::move(line));
    if (!worker_.joinable()) worker_ = std::thread([this] { Worker(); });
  }
  queue_cv_.notify_one();
}

void AppendLog::Drain() {
  std::unique_lock<std::mutex> lock(queue_mutex_);
  drained_cv_.wait(lock, [&] { return queue_.empty() && !busy_; });
}

void AppendLog::Worker() {
  std::unique_lock<std::mutex> lock(queue_mutex_);
  while (true) {
    queue_cv_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) break;  // stopping and nothing left
    std::string line = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    std::string why;
    const bool ok = Append(line, &why);
    if (on_result_) on_result_(line, ok, why);
    lock.lock();
    busy_ = false;
    if (queue_.empty()) drained_cv_.notify_all();
  }
  drained_cv_.notify_all();
}

}  // namespace rk::capture

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

}  // namespace rk::capture

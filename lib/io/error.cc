#include "io/error.h"

#include <string>

namespace rk {

Error DataError(const std::string& file, std::size_t line, std::size_t column, const std::string& what) {
  // Built with append(): GCC 12 warns falsely (-Wrestrict, PR 105329) on chains of operator+.
  std::string msg;
  msg.reserve(file.size() + what.size() + 32);
  msg.append(file);
  if (line > 0) {
    msg.append(":").append(std::to_string(line));
    if (column > 0) msg.append(":").append(std::to_string(column));
  }
  msg.append(": ").append(what);
  return Error(ExitCode::kInvalidData, msg);
}

Error ByteOffsetError(const std::string& file, std::uint64_t offset, const std::string& what) {
  std::string msg;
  msg.reserve(file.size() + what.size() + 40);
  msg.append(file).append(": byte ").append(std::to_string(offset)).append(": ").append(what);
  return Error(ExitCode::kInvalidData, msg);
}

Error TooFewSamplesError(const std::string& file, const std::string& what) {
  return Error(ExitCode::kInvalidData, DataError(file, 0, 0, what).what(), kTooFewSamples);
}

Error IoError(const std::string& path, const std::string& what) {
  return Error(ExitCode::kIo, path + ": " + what);
}

Error UsageError(const std::string& what) { return Error(ExitCode::kUsage, what); }

Error ProcessingError(const std::string& what) { return Error(ExitCode::kProcessing, what); }

}  // namespace rk

// Shared by the capture tests: a fresh, empty folder per test and process.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace rk::capture {

inline std::string TempDir(const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("rk_capture_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

}  // namespace rk::capture

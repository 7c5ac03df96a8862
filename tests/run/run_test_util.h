// Helpers shared by the tests of lib/run: a temporary folder removed at the end of the test, and
// writing / reading small files.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "io/file_util.h"
#include "rk_test/temp_dir.h"

namespace rk::run::testing {

namespace fs = std::filesystem;

using TempDir = rk::test::TempDir;  // tests/support: a fresh folder removed at the end of the test

inline void Write(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << text;
}

inline std::string Read(const std::string& path) { return io::ReadFile(path); }

}  // namespace rk::run::testing

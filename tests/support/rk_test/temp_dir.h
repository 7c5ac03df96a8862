// A fresh, empty temporary folder per test, removed with everything in it when the test ends
// (mkdtemp under $TMPDIR or /tmp: unique per process and per object, so tests may run in parallel).
#pragma once

#include <filesystem>
#include <string>

namespace rk::test {

class TempDir {
 public:
  // `tag` names the folder (rk_<tag>.XXXXXX) so that a leftover one says which test made it.
  explicit TempDir(const std::string& tag = "test");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::string& path() const { return path_; }
  // path()/rel as a string (rel may name a file in a subfolder; the subfolder is not made).
  std::string operator/(const std::string& rel) const { return (std::filesystem::path(path_) / rel).string(); }

 private:
  std::string path_;
};

// Writes `text` to `path` (parent folders made); ASSERT-style failure if it cannot.
void WriteFile(const std::string& path, const std::string& text);

}  // namespace rk::test

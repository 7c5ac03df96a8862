// File access shared by every tool: whole-file reads ("-" = stdin), atomic
// writes ("-" = stdout), and the guard that an output never replaces an input.
#pragma once

#include <string>
#include <vector>

namespace rk::io {

// Reads a whole file, or stdin for "-". Throws IoError if it cannot be read.
std::string ReadFile(const std::string& path);

// Writes `data` to `path` atomically: a temporary file in the same folder is
// written, flushed to disk and renamed over `path`, so a reader never sees a
// half-written file and a failed run leaves nothing behind. "-" writes stdout.
void WriteFileAtomic(const std::string& path, const std::string& data);

// A temporary path beside `final_path` for writers that stream (video). Commit()
// renames it into place; the destructor removes it if Commit() was not called.
class PendingFile {
 public:
  explicit PendingFile(const std::string& final_path, const std::string& suffix = "");
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;
  const std::string& temp_path() const { return temp_path_; }
  const std::string& final_path() const { return final_path_; }
  void Commit();

 private:
  std::string final_path_;
  std::string temp_path_;
  bool committed_ = false;
};

// Throws UsageError if `output` names the same file as one of `inputs`
// (nothing the user gave is overwritten). "-" is never compared.
void CheckOutputNotInput(const std::string& output, const std::vector<std::string>& inputs);

// Creates a folder (and parents); throws IoError on failure.
void MakeDirectories(const std::string& path);

bool IsStdStream(const std::string& path);

}  // namespace rk::io

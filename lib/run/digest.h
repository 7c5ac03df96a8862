// Content digests of trial files with the "size + mtime first" shortcut (docs/rk-run.md,
// "Skipping"). A file whose size and modification time (ns) equal those recorded by the last
// successful run keeps its recorded SHA-256 without being read; any other file is hashed, so a
// `touch` or a copy with the same content does not cause reprocessing, and a changed content always
// does (unless size and mtime were forged back, which `rk-run --rehash` guards against).
// An image-sequence pattern ("att/%06d.png") is digested as the sorted list of its files: bytes =
// sum, mtime = latest, files = count, SHA-256 over "name sha256\n" of every file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/json_util.h"

namespace rk::run {

struct FileDigest {
  std::uintmax_t bytes = 0;
  std::int64_t mtime_ns = 0;
  std::size_t files = 1;  // > 1 (or 0) for image sequences
  std::string sha256;
  bool hashed = false;  // read and hashed by this run (false: trusted from the previous record)
  io::Json ToJson() const;
};

// True when `path` is an image-sequence pattern (printf-style %d / %0Nd in the file name).
bool IsSequencePattern(const std::string& path);
// Files of a sequence pattern, in frame order (absolute or relative as the pattern is).
std::vector<std::string> ExpandSequence(const std::string& pattern);

class DigestCache {
 public:
  // `base_dir`: folder that relative paths are relative to. `previous`: the "files" object of the
  // last report ({path: {bytes, mtime_ns, files, sha256}}), may be null. `trust_stat`: use the
  // size+mtime shortcut (false = hash everything, --rehash).
  DigestCache(std::string base_dir, const io::Json& previous, bool trust_stat);
  // Digest of a file or sequence; throws IoError if it does not exist or cannot be read.
  const FileDigest& Digest(const std::string& path);
  // Every digest used by this run, {path: {...}} (for the next run's shortcut).
  io::Json ToJson() const;
  std::size_t files_hashed() const { return files_hashed_; }
  std::uintmax_t bytes_hashed() const { return bytes_hashed_; }
  std::size_t files_trusted() const { return files_trusted_; }

 private:
  std::string Resolve(const std::string& path) const;
  std::string base_;
  io::Json previous_;
  bool trust_stat_;
  std::map<std::string, FileDigest> digests_;
  std::size_t files_hashed_ = 0, files_trusted_ = 0;
  std::uintmax_t bytes_hashed_ = 0;
};

// size and mtime (ns) of a file; false if it does not exist.
bool StatFile(const std::string& path, std::uintmax_t* bytes, std::int64_t* mtime_ns);

}  // namespace rk::run

// Atomic creation of a trial folder (SPEC.md §2 "writes are atomic", §6 trial directory): everything is
// written into a temporary sibling "<parent>/.<name>.XXXXXX", which Commit() renames onto the output path.
// A failed run (no Commit) leaves nothing behind. An existing non-empty output folder is refused
// (UsageError) unless `force`, in which case it is replaced as a whole (moved aside, then removed).
// (The same protocol as WriteBeaconTrial / WritePoseTrack, as a reusable class.)
#pragma once

#include <string>

namespace rk::sim {

class TrialDir {
 public:
  // Validates `out_dir` and creates the temporary folder. Throws UsageError / IoError.
  TrialDir(const std::string& out_dir, bool force);
  ~TrialDir();
  TrialDir(const TrialDir&) = delete;
  TrialDir& operator=(const TrialDir&) = delete;

  // Temporary root to write into, and a path inside it.
  const std::string& root() const { return tmp_; }
  std::string Path(const std::string& relative) const;
  // Folder name of the output (default trial name).
  const std::string& stem() const { return stem_; }
  // Moves the temporary folder into place. Throws IoError.
  void Commit();

 private:
  std::string out_, parent_, stem_, tmp_;
  bool committed_ = false;
};

}  // namespace rk::sim

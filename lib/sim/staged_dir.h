// An output folder written atomically (SPEC.md §2 "writes are atomic", applied to a trial
// directory): everything goes into a fresh temporary sibling "<parent>/.<name>.XXXXXX", which
// Commit() renames onto the output path. A failed run (exception before Commit) removes the
// temporary folder and leaves the output untouched. An existing non-empty output folder is
// refused (UsageError) unless `force`, in which case it is replaced as a whole (moved aside,
// then removed after the switch; put back if the switch fails).
// Same protocol as sim/beacon_trial.cc and sim/posetrack.cc (which keep their own copies).
#pragma once

#include <string>

namespace rk::sim {

class StagedDir {
 public:
  // Validates `out_dir` and creates the temporary folder. Throws UsageError (bad path, existing
  // non-empty folder without force, a file in the way) or IoError (cannot create).
  StagedDir(const std::string& out_dir, bool force);
  ~StagedDir();
  StagedDir(const StagedDir&) = delete;
  StagedDir& operator=(const StagedDir&) = delete;

  // The temporary folder to write into, and a path inside it.
  const std::string& root() const { return tmp_; }
  std::string Path(const std::string& relative) const;
  const std::string& out() const { return out_; }        // the final folder
  const std::string& name() const { return stem_; }      // its last path component

  // Renames the temporary folder onto the output path. Throws IoError on failure.
  void Commit();

 private:
  std::string out_, parent_, stem_, tmp_;
  bool committed_ = false;
};

}  // namespace rk::sim

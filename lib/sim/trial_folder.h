// Writing a simulated trial folder atomically (SPEC.md §2 "writes are atomic", applied to a trial
// directory; every rk-sim subcommand that writes a folder uses it): the files are written into a
// fresh temporary sibling folder "<parent>/.<name>.XXXXXX", which Commit() renames onto the output.
// An existing non-empty output is refused (UsageError) unless `force`, which replaces it as a whole
// (moved aside, removed after the switch, put back if the switch fails); a failure before Commit()
// leaves the output untouched and removes the temporary folder.
#pragma once

#include <string>

namespace rk::sim {

class TrialFolder {
 public:
  // Throws UsageError for an unusable --out, IoError if the temporary folder cannot be made.
  TrialFolder(const std::string& out_dir, bool force);
  ~TrialFolder();
  TrialFolder(const TrialFolder&) = delete;
  TrialFolder& operator=(const TrialFolder&) = delete;

  // Path of a file (or sub-folder) inside the temporary folder.
  std::string Path(const std::string& relative) const;
  // Creates a sub-folder of the temporary folder.
  void MakeSubfolder(const std::string& relative) const;
  const std::string& out() const { return out_; }
  // Last path component of the output (the default trial name).
  const std::string& stem() const { return stem_; }
  // Moves the folder into place (IoError on failure; the old output is then kept).
  void Commit();

 private:
  std::string out_, parent_, stem_, tmp_;
  bool committed_ = false;
};

}  // namespace rk::sim

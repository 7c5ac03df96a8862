// The trial folder's safety mechanisms (docs/rk-run.md, "Safety"):
// - TrialLock: flock(2) on TRIAL/.rk-run.lock, so two runs of one trial never overlap. The kernel
//   releases it when the process dies (kill -9 included); the descriptor is close-on-exec so the
//   tools never inherit it.
// - The new out/ is built in TRIAL/out.tmp.XXXXXX and swapped in with one renameat2(RENAME_EXCHANGE)
//   (old and new exchanged atomically), then the old one is removed. Where the file system cannot
//   exchange (EINVAL/ENOTSUP, e.g. NFS), two renames are used (out → out.old.XXXXXX, tmp → out) and
//   RecoverAndClean() completes an interrupted swap. A folder counts as complete when it holds
//   report.json, which is written last.
// - TRIAL/out may be a symbolic link (to keep products on another disk): the link stays a link; its
//   target folder T is swapped, with T.tmp.XXXXXX / T.old.XXXXXX made beside T (SPEC.md §2).
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace rk::run {

inline constexpr const char* kOutDir = "out";
inline constexpr const char* kLockFile = ".rk-run.lock";
inline constexpr const char* kLastRunFile = "last-run.json";
inline constexpr const char* kRunLogFile = "rk-run.log";
inline constexpr const char* kReportFile = "report.json";  // written last: marks a complete out/

class TrialLock {
 public:
  // Takes the lock on `lock_file` (TRIAL/.rk-run.lock), waiting up to `wait_s` seconds (0 = try once).
  // Returns null when another process holds it; *holder then says who ("pid 123 since 2026-...Z").
  // Throws IoError if the lock file cannot be created or is a link.
  static std::unique_ptr<TrialLock> Acquire(const std::string& lock_file, double wait_s, std::string* holder);
  ~TrialLock();
  TrialLock(const TrialLock&) = delete;
  TrialLock& operator=(const TrialLock&) = delete;

 private:
  explicit TrialLock(int fd) : fd_(fd) {}
  int fd_;
};

// With the lock held: finishes a swap that a kill interrupted (no out/ but a complete out.tmp.* or
// out.old.*: the newest complete one becomes out/), then removes every other out.tmp.* / out.old.*.
// Returns one line per action, for the log.
// `out_path` is TRIAL/out, or rk-run --out DIR, everywhere below.
std::vector<std::string> RecoverAndClean(const std::string& out_path);

// Creates TRIAL/out.tmp.XXXXXX (beside the link target when out/ is a link) and returns its path.
std::string MakeWorkDir(const std::string& out_path);

// Hard-links src to dst (copies, keeping the modification time, where links are impossible); dst's
// folder is created.
void LinkOrCopy(const std::string& src, const std::string& dst);

// fsync of a file or folder (errors ignored where the file system does not support it).
void SyncPath(const std::string& path);

// Makes `work_dir` (complete, with report.json) the trial's out/, atomically; the previous out/
// is removed afterwards. Returns "exchange", "rename" (no previous out/) or "two-renames".
std::string CommitOut(const std::string& out_path, const std::string& work_dir);

// Everything in the old `out_dir` that rk-run did not make (not in `made_by_run`, relative paths; notes,
// an analysis/ folder a user put there) is hard-linked (copied where links are impossible; a link kept
// as a link) into `work_dir` at the same path, so that the swap keeps it. Returns the paths kept.
// Throws IoError, naming it, for such an entry whose path a step of this run has written: the run then
// fails and the old out/ stays as it was. Without `record_known` (the old report.json is missing or
// damaged, so what rk-run made is not known) such an entry is taken for an old product and replaced.
std::vector<std::string> KeepUserEntries(const std::string& out_dir, const std::string& work_dir,
                                         const std::set<std::string>& made_by_run, bool record_known);

// Throws IoError (exit 4) when TRIAL/out (or the folder its link leads to) exists and is not a folder.
void CheckOutIsFolder(const std::string& out_path);

// Removes a folder tree, its report.json first (so that a removal cut short never looks complete).
void RemoveOutTree(const std::string& path);

}  // namespace rk::run

// File access shared by every tool: whole-file reads ("-" = stdin), atomic
// writes ("-" = stdout), and the guard that an output never replaces an input.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rk::io {

// Reads a whole file, or stdin for "-". Throws IoError if it cannot be read.
std::string ReadFile(const std::string& path);

// Where and how an output path is written (SPEC.md §2, "Writes are atomic"). The one place that
// decides it, for every writer of files and folders:
//  - "-", and links that lead to one of this process's own descriptors (/dev/stdout, /dev/fd/N,
//    /proc/self/fd/N): written to that descriptor, as the shell opened it;
//  - a path that does not exist, or a regular file: replaced atomically (temporary file beside it,
//    then rename);
//  - a symbolic link (any chain of them): the link stays a link; its final target is replaced
//    atomically, or written through if it is not a regular file;
//  - an existing file that is not a regular file (a device such as /dev/null, a FIFO, a process
//    substitution): written through in place, never replaced, never created — as root too.
struct OutputTarget {
  enum class Kind { kDescriptor, kReplace, kWriteThrough };
  Kind kind = Kind::kReplace;
  int fd = -1;       // kDescriptor: the descriptor to write to
  std::string path;  // kReplace: the file to replace (a link's final target); kWriteThrough: the path to open
};
// Throws IoError for a folder, a socket, or a link chain that cannot be followed.
OutputTarget ResolveOutput(const std::string& path);

// The folder an output folder path stands for: the path itself, or, for a symbolic link (chain), its
// final target, so that a tool replacing a whole folder (rk-run's out/, rk-sim's trial folders)
// replaces the target and keeps the link. What is there (nothing, a folder, something else) is the
// caller's to check. Throws IoError for a link to a file descriptor or a chain that cannot be followed.
std::string ResolveOutputFolder(const std::string& path);

// Writes `data` to `path` as ResolveOutput says: atomically for files (a temporary file in the same
// folder is written, flushed to disk and renamed over the file, so a reader never sees a
// half-written file and a failed run leaves nothing behind), in place for devices and FIFOs,
// to the descriptor for "-" and /dev/stdout.
void WriteFileAtomic(const std::string& path, const std::string& data);

// An output written in pieces, for data too large to hold in memory whole (rk-smooth singer on a long log),
// with WriteFileAtomic's guarantees: nothing appears at `path` before Commit(), and an OutputFile destroyed
// without Commit() (a failed run) leaves nothing anywhere. A file (ResolveOutput's kReplace) is written
// straight into the temporary file beside it and renamed over it at Commit(); a descriptor ("-") or a
// device / FIFO gets the whole data at Commit(), copied from a spool (an unnamed temporary file in $TMPDIR,
// else /tmp), so that a failed run writes nothing there either.
class OutputFile {
 public:
  // Resolves `path` (ResolveOutput) and creates the temporary file or the spool; IoError as WriteFileAtomic.
  explicit OutputFile(const std::string& path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();  // without Commit(): the temporary file is removed
  void Write(std::string_view data);
  // Flushed to disk and renamed into place (kReplace), or the spool copied to its descriptor or device.
  void Commit();

 private:
  std::string path_;
  OutputTarget target_;
  int fd_ = -1;      // the temporary file beside the target (kReplace) or the spool
  std::string tmp_;  // kReplace: the temporary file's name, removed unless committed
};

// Files a tool makes for itself in a folder it works in (rk-run's TRIAL/.rk-run.lock, rk-run.log,
// last-run.json), as opposed to outputs the user names: they never go through a symbolic link, so that
// whoever can write the folder cannot point them at a file elsewhere (docs/conventions.md "Threat model").
// RefuseLink throws IoError when `path` is a link or exists and is not a regular file.
void RefuseLink(const std::string& path);
// Replaces `path` atomically (temporary file beside it, then rename) after RefuseLink.
void WriteOwnFileAtomic(const std::string& path, const std::string& data);
// open(2) with O_NOFOLLOW | O_CLOEXEC added; throws IoError (naming the link) when it is a link or fails.
int OpenOwnFile(const std::string& path, int flags, unsigned mode = 0644);

// Throws UsageError if `output` names the same file as one of `inputs`
// (nothing the user gave is overwritten), IoError if it cannot be an output file at all (a folder:
// ResolveOutput), so that tools refuse it before doing any work. "-" is never compared.
void CheckOutputNotInput(const std::string& output, const std::vector<std::string>& inputs);

// Creates a folder (and parents); throws IoError on failure.
void MakeDirectories(const std::string& path);

bool IsStdStream(const std::string& path);

// True when `path`, with every symbolic link resolved (also in a part that does not exist yet), lies
// inside `folder` (also resolved) and is not the folder itself. The guard of every tool that writes to
// a path a trial folder names (docs/conventions.md "Threat model"): a trial's writer must not reach
// a file outside it through `../`, an absolute path or a link.
bool IsInsideFolder(const std::string& folder, const std::string& path);

}  // namespace rk::io

// Streaming a row-wise tool's CSV to stdout as its rows are made (docs/conventions.md "Streaming to
// stdout"). What an output path is stays io::ResolveOutput's to decide (file_util.h): only its descriptors
// ("-", /dev/stdout, /dev/fd/N) are streamed; files, devices and FIFOs named by path are still written
// once, atomically, at the end (io::CsvWriter::Write). What was streamed cannot be taken back: a run that
// fails later leaves it in the pipe, and its error line and exit code still come.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "io/csv.h"

namespace rk::io {

// The descriptor an output path streams to: ResolveOutput's kDescriptor, else -1 (file_util.cc).
int StreamDescriptor(const std::string& path);
// Writes `data` in full to descriptor `fd`, std::cout flushed first (what it buffered comes first);
// IoError naming `path` ("<stdout>" for descriptor 1) if the write fails (file_util.cc: the same write
// loop as every other output).
void WriteToDescriptor(int fd, std::string_view data, const std::string& path);

// Streams the rows of `writer` (which must outlive it) to `path`:
//   CsvWriter w = SomeCsv({});  CsvStream out(w, path);
//   per unit of work (a frame): add its rows to w, then out.Flush();
//   at the end: out.Finish() instead of w.Write(path).
// Flush() is one write(2) of the whole rows added since the last one (the header with the first), or
// nothing when `path` is not a descriptor.
class CsvStream {
 public:
  CsvStream(const CsvWriter& writer, std::string path);
  void Flush();
  // Streaming: the rows not sent yet (RK_CHECK: no unfinished row). Otherwise: writer.Write(path), atomic.
  void Finish();
  bool streaming() const { return fd_ >= 0; }

 private:
  const CsvWriter& writer_;
  std::string path_;
  int fd_ = -1;
  std::size_t sent_ = 0;  // bytes of writer_.str() already written
};

}  // namespace rk::io

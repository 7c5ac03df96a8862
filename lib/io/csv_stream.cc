#include "io/csv_stream.h"

#include <utility>

#include "io/error.h"

namespace rk::io {

CsvStream::CsvStream(const CsvWriter& writer, std::string path)
    : writer_(writer), path_(std::move(path)), fd_(StreamDescriptor(path_)) {}

void CsvStream::Flush() {
  if (fd_ < 0) return;
  // Whole rows only: a row being built (after the last newline) waits for the next flush.
  const std::string& text = writer_.str();
  const std::size_t end = text.rfind('\n') + 1;  // npos + 1 = 0: nothing yet
  if (end <= sent_) return;
  WriteToDescriptor(fd_, std::string_view(text).substr(sent_, end - sent_), path_);
  sent_ = end;
}

void CsvStream::Finish() {
  if (fd_ < 0) {
    writer_.Write(path_);
    return;
  }
  const std::string& text = writer_.str();
  RK_CHECK(text.empty() || text.back() == '\n', "unfinished row");
  Flush();
}

}  // namespace rk::io

// Errors that reach the command line, and the exit codes of SPEC.md §4.
//
// Recoverable problems (bad files, unreadable paths, degenerate data, no
// convergence) are thrown as rk::Error carrying the exit code the CLI edge must
// return. Messages are one line; data errors name file, line and column as
// "FILE:LINE:COL: message" so that editors and shells can jump to them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

namespace rk {

enum class ExitCode : int {
  kOk = 0,
  kProcessing = 1,   // processing failed (no convergence, nothing detected)
  kUsage = 2,        // bad or missing option
  kInvalidData = 3,  // invalid input data (message names file, line, column)
  kIo = 4,           // cannot read or write a path
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message, std::string kind = "")
      : std::runtime_error(message), code_(code), kind_(std::move(kind)) {}
  ExitCode code() const { return code_; }
  // A machine-readable kind for errors a caller may treat differently (written to the run report as
  // "error_kind"); "" for most. kTooFewSamples: the input is valid but holds too little for this method.
  const std::string& kind() const { return kind_; }

 private:
  ExitCode code_;
  std::string kind_;
};

// Error kinds (Error::kind(), the report's "error_kind").
inline constexpr const char* kTooFewSamples = "too-few-samples";

// "file:line:col: what" — line and column are 1-based; 0 omits them.
Error DataError(const std::string& file, std::size_t line, std::size_t column, const std::string& what);
// A DataError (exit 3) of kind kTooFewSamples: a valid input that holds too few usable samples for the
// method (a beacon seen in two frames cannot be smoothed). rk-run keeps what the chain could make.
// A DataError in a binary file: "file: byte OFFSET: what" (OFFSET 0-based, where the fault was found:
// a camera file's header field, a block past the end of the file, a record that cannot be decoded).
Error ByteOffsetError(const std::string& file, std::uint64_t offset, const std::string& what);
Error TooFewSamplesError(const std::string& file, const std::string& what);
Error IoError(const std::string& path, const std::string& what);
Error UsageError(const std::string& what);
Error ProcessingError(const std::string& what);

// Broken invariant inside the library (a bug, not bad input): throws std::logic_error.
#define RK_CHECK(cond, msg)                                                                  \
  do {                                                                                       \
    if (!(cond)) throw std::logic_error(std::string("check failed: " #cond ": ") + (msg)); \
  } while (0)

}  // namespace rk

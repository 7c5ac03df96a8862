// What this process has read, and where its warnings go: the process-wide record behind the
// run report (SPEC.md §2 "inputs"). Every place that opens an input (io::ReadFile, hence
// CsvTable::Read and LoadJson; the video readers) records it here, so that a run that fails
// half-way can still report the inputs it read (cli::Run writes that report).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rk::io {

struct InputRead {
  std::string path;                     // as given ("-" = stdin)
  std::optional<std::uintmax_t> bytes;  // size of a regular file (none for stdin, patterns, devices)
  bool csv = false;                     // read as a CSV table
  std::size_t rows_skipped = 0;         // bad rows skipped under --bad-rows skip (CSV only)
};

// Records that `path` was opened for reading (again: updates the entry). `bytes` = size read.
void RecordInputRead(const std::string& path, std::optional<std::uintmax_t> bytes);
// Marks `path` as a CSV read and adds `rows_skipped` to its count of skipped bad rows.
void RecordCsvRead(const std::string& path, std::size_t rows_skipped);
// Entries in the order first read.
std::vector<InputRead> InputsRead();
// The entry of `path`, if it was read.
std::optional<InputRead> FindInputRead(const std::string& path);
// Forgets everything (tests).
void ClearInputsRead();

// Warnings from library code that has no tool name (e.g. "skipped a bad row"). The CLI edge
// sets a sink that prefixes "rk-<tool>: warning: " and honours --quiet; the default writes
// "warning: <text>" to stderr.
void SetWarningSink(std::function<void(const std::string&)> sink);
void EmitWarning(const std::string& text);

}  // namespace rk::io

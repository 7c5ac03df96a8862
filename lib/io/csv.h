// CSV per SPEC.md §2: UTF-8, comma-separated, one header row, '.' decimal point,
// '#' comment lines anywhere, columns found by name, empty field = not available,
// RFC 4180 quoted fields ("a,b", "" for a quote, newlines inside quotes).
//
// CsvTable keeps little per row (docs/conventions.md "CSV reading and memory"): a
// regular file is indexed once (byte offset and line of each data row) and its rows
// are re-read from the file, a window at a time, when a cell is asked for; numbers
// are parsed on demand and a column read as text is kept once. Any complaint about a
// value still names "file:line:col". CsvWriter builds the whole output in memory and
// writes it atomically (or to stdout for "-"), so a tool that fails half-way leaves
// no partial file.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/error.h"

namespace rk::io {

// ---- Bad rows (--bad-rows): what a reader does with a data row it cannot use. ----

// kError (default): the first bad row stops the run with exit 3 and file:line:col.
// kSkip: bad rows are dropped, each with a warning naming file:line:col and the reason.
enum class BadRows { kError, kSkip };
// "error" / "skip"; false for anything else.
bool ParseBadRows(std::string_view text, BadRows* out);

// What a reader needs of every data row, by column name (columns absent from the header are
// not checked here: a missing column is the reader's file-level error). A row breaks the rule
// when a listed cell does not hold what is listed, or when it is not in the longest in-order run
// of the `non_decreasing` column (a row that jumped back, or one wild time far ahead: only that
// row goes). Rows with a wrong field count are always bad.
struct CsvRowRule {
  std::vector<std::string> numbers;            // a finite number (not empty, not NaN/inf)
  std::vector<std::string> optional_numbers;   // empty, or a finite number
  std::vector<std::string> integers;           // an integer (not empty)
  std::vector<std::string> optional_integers;  // empty, or an integer
  std::vector<std::string> texts;              // not empty
  std::string non_decreasing;                  // a number column that never goes backwards ("t_s")
  bool increasing = false;                     // ... nor repeats a value
  // ... nor repeats a value among the rows of one value of this column (a points track's ids share their
  // frames' times); over the whole file, as `increasing`, when the file has no such column.
  std::string increasing_per;
};

struct CsvReadOptions {
  BadRows bad_rows = BadRows::kError;
  CsvRowRule rule;  // used under kSkip; under kError the reader's own checks find the first bad row
};

// A data row dropped under BadRows::kSkip.
struct SkippedRow {
  std::size_t line = 0;    // 1-based line in the file
  std::size_t column = 0;  // 1-based character column of the offending cell
  std::string reason;
};

// At most this many skipped rows are warned about one by one per file; then one line counts them all.
inline constexpr std::size_t kMaxSkippedRowWarnings = 20;

class CsvTable {
 public:
  // Reads `path` ("-" = stdin). Throws IoError if unreadable, DataError if the
  // header is missing or (under BadRows::kError) a row has a different number of
  // fields than the header. Under BadRows::kSkip, rows that break `options.rule`
  // are dropped with a warning (io::EmitWarning) and counted in the run record
  // (io::RecordCsvRead), so the reader sees only usable rows.
  static CsvTable Read(const std::string& path, const CsvReadOptions& options = {});
  // Parses text already in memory; `name` is used in messages.
  static CsvTable Parse(std::string_view text, const std::string& name, const CsvReadOptions& options = {});

  const std::string& name() const { return name_; }
  const std::vector<std::string>& header() const { return header_; }
  std::size_t rows() const { return line_.size(); }

  // Index of a column, or -1 if absent.
  int Column(std::string_view column) const;
  // Index of a column; throws DataError naming the header line if absent.
  int RequireColumn(std::string_view column) const;
  bool HasColumn(std::string_view column) const { return Column(column) >= 0; }

  std::string_view Cell(std::size_t row, int col) const;
  bool IsEmpty(std::size_t row, int col) const;
  // A finite number; throws DataError at file:line:col if empty, not a number,
  // NaN or infinite.
  double Double(std::size_t row, int col) const;
  // Empty field → nullopt; otherwise as Double().
  std::optional<double> OptionalDouble(std::size_t row, int col) const;
  // An integer: integer text, or a finite number whose value is an exact integer ("+0", "0.0",
  // "0e0", as pandas writes them); throws DataError if not one.
  std::int64_t Int(std::size_t row, int col) const;

  // 1-based line in the file of a data row, and 1-based character column of a cell.
  std::size_t Line(std::size_t row) const { return line_[row]; }
  std::size_t CharColumn(std::size_t row, int col) const;
  std::size_t header_line() const { return header_line_; }

  // Throws DataError at the first row whose value in `col` is smaller than the
  // previous one (e.g. time going backwards). Empty values are errors.
  void RequireNonDecreasing(int col) const;
  // Same, but strictly increasing (duplicate times rejected too).
  void RequireIncreasing(int col) const;

  // Builds a DataError for a cell.
  [[nodiscard]] Error CellError(std::size_t row, int col, const std::string& what) const;

  // Rows dropped under BadRows::kSkip, in file order.
  const std::vector<SkippedRow>& skipped() const { return skipped_; }

  // Heap bytes the table holds now (row index, read window, columns kept as text, and the
  // whole text when it did not come from a regular file), for the memory tests and benchmarks.
  std::size_t HeldBytes() const;

 private:
  struct Source;      // the text: a regular file read again by windows, or text held in memory
  struct RowCache;    // the fields of the row read last; the columns kept as text
  struct Field;       // one field of a row
  class Indexer;      // the one pass that finds the header and every data row

  CsvTable() = default;
  // Splits the row at the start of `s` into *fields. Returns the row's length with its line end, or
  // npos when the row may go on past the end of `s` (never when `at_eof`, except for a quote never
  // closed: *open_quote is where it opened). *text_end: where the row's text ends (before "\r\n").
  static std::size_t SplitRow(std::string_view s, bool at_eof, std::vector<Field>* fields, std::size_t* text_end,
                              std::size_t* open_quote);
  static CsvTable Index(std::shared_ptr<Source> src, const std::string& name, const CsvReadOptions& options);
  // Under kSkip: drops the rows that break `rule` (recording them in skipped_): rows with a cell the
  // reader cannot use, then, for the order column, every row outside the longest in-order run of the
  // rest (one wild time costs one row).
  void DropBadRows(const CsvRowRule& rule);
  // The reason `row`'s cells break `rule` (the cell's line and character column in *line, *col), or ""
  // if they do not.
  std::string RowProblem(std::size_t row, const CsvRowRule& rule, std::size_t* line, std::size_t* col) const;
  // Warns about the skipped rows (one line each up to kMaxSkippedRowWarnings, then a count).
  void WarnSkipped() const;
  // Keeps the rows r with keep[r], in order.
  void KeepRows(const std::vector<bool>& keep);

  // The field `col` of `row` (the row is read from the source if it is not the one read last); the
  // view is valid until another row is read.
  const Field& FieldAt(std::size_t row, int col) const;
  std::string_view Content(const Field& f) const;
  // A cell's text with "" escapes undone (for messages and the text columns).
  std::string CellText(std::size_t row, int col) const;
  // 1-based file line and character column where a cell starts (a quoted field may span lines).
  void CellPosition(std::size_t row, int col, std::size_t* line, std::size_t* column) const;
  // A DataError at a cell's line and column, `what` as given.
  [[nodiscard]] Error PositionError(std::size_t row, int col, const std::string& what) const;
  std::uint64_t RowStart(std::size_t row) const;
  // Reserves the row index for a file of `file_bytes`, judging by the rows in its first `bytes_so_far`.
  void ReserveRows(std::uint64_t file_bytes, std::uint64_t bytes_so_far);

  std::string name_;
  std::size_t header_line_ = 0;
  std::vector<std::string> header_;
  std::shared_ptr<Source> src_;
  // Byte offset of each data row: low 32 bits, and the first row of each further 4 GiB.
  std::vector<std::uint32_t> start_lo_;
  std::vector<std::size_t> start_hi_;  // start_hi_[k]: first row whose offset is >= (k + 1) << 32
  std::vector<std::uint32_t> line_;    // 1-based line of each data row
  std::shared_ptr<RowCache> cache_;    // shared by copies (same rows); a table is read by one thread at a time
  std::vector<SkippedRow> skipped_;
};

class OutputFile;  // io/file_util.h

class CsvWriter {
 public:
  explicit CsvWriter(std::vector<std::string> columns);

  // "# text" line; allowed anywhere.
  void Comment(std::string_view text);
  CsvWriter& Add(std::string_view text);
  CsvWriter& Add(std::int64_t value);
  CsvWriter& Add(int value) { return Add(static_cast<std::int64_t>(value)); }
  // Fixed-point with `decimals` digits; NaN is written as an empty field.
  CsvWriter& Add(double value, int decimals);
  CsvWriter& Add(std::optional<double> value, int decimals);
  CsvWriter& AddEmpty();
  // Ends the row; RK_CHECKs that it has as many fields as the header.
  void EndRow();

  const std::string& str() const { return text_; }
  std::size_t rows() const { return rows_; }
  // Atomic write to `path`, or stdout for "-".
  void Write(const std::string& path) const;
  // Moves out the text written so far (the header first), for an output written in pieces
  // (io::OutputFile); RK_CHECKs that no row is unfinished. rows() still counts every row.
  std::string TakeText();
  // Writes the text so far to `file` and clears it, keeping its memory: a large output written in pieces
  // without a new allocation (and its page faults) per piece. RK_CHECKs that no row is unfinished.
  void DrainTo(OutputFile* file);

 private:
  std::vector<std::string> columns_;
  std::string text_;
  std::size_t fields_in_row_ = 0;
  std::size_t rows_ = 0;
};

// Splits "a,b,c" into names (used for --columns).
std::vector<std::string> SplitList(std::string_view list, char sep = ',');

}  // namespace rk::io

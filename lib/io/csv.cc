#include "io/csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "io/error.h"
#include "io/file_util.h"
#include "io/run_record.h"

namespace rk::io {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Splits one line into fields; supports double-quoted fields with "" escapes.
void SplitLine(std::string_view line, std::vector<std::string>* cells, std::vector<std::size_t>* cols) {
  cells->clear();
  cols->clear();
  std::size_t i = 0;
  while (true) {
    std::size_t start = i;
    std::string cell;
    // Skip leading blanks to find a quote.
    std::size_t j = i;
    while (j < line.size() && (line[j] == ' ' || line[j] == '\t')) ++j;
    if (j < line.size() && line[j] == '"') {
      ++j;
      while (j < line.size()) {
        if (line[j] == '"') {
          if (j + 1 < line.size() && line[j + 1] == '"') {
            cell.push_back('"');
            j += 2;
            continue;
          }
          ++j;
          break;
        }
        cell.push_back(line[j++]);
      }
      while (j < line.size() && line[j] != ',') ++j;
      i = j;
    } else {
      while (i < line.size() && line[i] != ',') ++i;
      cell = std::string(Trim(line.substr(start, i - start)));
    }
    cells->push_back(std::move(cell));
    cols->push_back(start + 1);
    if (i >= line.size()) break;
    ++i;  // skip ','
  }
}

}  // namespace

CsvTable CsvTable::Parse(std::string_view text, const std::string& name, const CsvReadOptions& options) {
  CsvTable t;
  t.name_ = name;
  std::size_t pos = 0, line_no = 0;
  bool have_header = false;
  std::vector<std::string> cells;
  std::vector<std::size_t> cols;
  if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF &&
      static_cast<unsigned char>(text[1]) == 0xBB && static_cast<unsigned char>(text[2]) == 0xBF) {
    pos = 3;  // UTF-8 byte-order mark
  }
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    std::string_view trimmed = Trim(line);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    SplitLine(line, &cells, &cols);
    if (!have_header) {
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (cells[c].empty()) throw DataError(name, line_no, cols[c], "empty column name in header");
        for (std::size_t k = 0; k < c; ++k) {
          if (cells[k] == cells[c])
            throw DataError(name, line_no, cols[c], "duplicate column '" + cells[c] + "'");
        }
      }
      t.header_ = cells;
      t.header_line_ = line_no;
      have_header = true;
      continue;
    }
    if (cells.size() != t.header_.size()) {
      std::size_t col = cells.size() > t.header_.size() ? cols[t.header_.size()] : line.size() + 1;
      const std::string what = "row has " + std::to_string(cells.size()) + " fields, header has " +
                               std::to_string(t.header_.size());
      if (options.bad_rows == BadRows::kSkip) {
        t.skipped_.push_back(SkippedRow{line_no, col, what});
        continue;
      }
      throw DataError(name, line_no, col, what);
    }
    t.rows_.push_back(Row{line_no, cells, cols});
  }
  if (!have_header) throw DataError(name, line_no > 0 ? line_no : 1, 1, "no header row (file is empty)");
  if (options.bad_rows == BadRows::kSkip) {
    t.DropBadRows(options.rule);
    t.WarnSkipped();
  }
  return t;
}

CsvTable CsvTable::Read(const std::string& path, const CsvReadOptions& options) {
  std::string text = ReadFile(path);
  CsvTable t = Parse(text, IsStdStream(path) ? std::string("<stdin>") : path, options);
  RecordCsvRead(path, t.skipped_.size());
  return t;
}

int CsvTable::Column(std::string_view column) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == column) return static_cast<int>(i);
  }
  return -1;
}

int CsvTable::RequireColumn(std::string_view column) const {
  int c = Column(column);
  if (c < 0) throw DataError(name_, header_line_, 1, "missing column '" + std::string(column) + "'");
  return c;
}

std::string_view CsvTable::Cell(std::size_t row, int col) const {
  return rows_[row].cells[static_cast<std::size_t>(col)];
}

std::size_t CsvTable::CharColumn(std::size_t row, int col) const {
  return rows_[row].char_col[static_cast<std::size_t>(col)];
}

Error CsvTable::CellError(std::size_t row, int col, const std::string& what) const {
  return DataError(name_, Line(row), CharColumn(row, col),
                   "column '" + header_[static_cast<std::size_t>(col)] + "': " + what);
}

namespace {
// "" when `s` is a finite number (stored in *v), else why it is not. One leading '+' is allowed
// (from_chars takes none); a sign after it ("+-5") is not a number.
std::string NumberProblem(std::string_view s, double* v) {
  if (s.empty()) return "empty value";
  const char* first = s.data();
  if (*first == '+') {
    ++first;
    if (first == s.data() + s.size() || *first == '+' || *first == '-')
      return "'" + std::string(s) + "' is not a number";
  }
  auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), *v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return "'" + std::string(s) + "' is not a number";
  if (!std::isfinite(*v)) return "'" + std::string(s) + "' is not a finite number";
  return "";
}

}  // namespace

double CsvTable::Double(std::size_t row, int col) const {
  double v = 0.0;
  const std::string problem = NumberProblem(Cell(row, col), &v);
  if (!problem.empty()) throw CellError(row, col, problem);
  return v;
}

std::optional<double> CsvTable::OptionalDouble(std::size_t row, int col) const {
  if (IsEmpty(row, col)) return std::nullopt;
  return Double(row, col);
}

std::int64_t CsvTable::Int(std::size_t row, int col) const {
  std::string_view s = Cell(row, col);
  std::int64_t v = 0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size()) {
    throw DataError(name_, Line(row), CharColumn(row, col),
                    "column '" + header_[col] + "': '" + std::string(s) + "' is not an integer");
  }
  return v;
}

void CsvTable::RequireNonDecreasing(int col) const {
  for (std::size_t r = 1; r < rows(); ++r) {
    double prev = Double(r - 1, col), cur = Double(r, col);
    if (cur < prev) {
      throw DataError(name_, Line(r), CharColumn(r, col),
                      "column '" + header_[col] + "' goes backwards (" + std::string(Cell(r, col)) +
                          " after " + std::string(Cell(r - 1, col)) + ")");
    }
  }
  if (rows() == 1) (void)Double(0, col);
}

void CsvTable::RequireIncreasing(int col) const {
  RequireNonDecreasing(col);
  for (std::size_t r = 1; r < rows(); ++r) {
    if (Double(r, col) == Double(r - 1, col)) {
      throw DataError(name_, Line(r), CharColumn(r, col),
                      "column '" + header_[col] + "' repeats the value " + std::string(Cell(r, col)));
    }
  }
}

// ---- Bad rows (BadRows::kSkip) ----

bool ParseBadRows(std::string_view text, BadRows* out) {
  if (text == "error") {
    *out = BadRows::kError;
  } else if (text == "skip") {
    *out = BadRows::kSkip;
  } else {
    return false;
  }
  return true;
}

namespace {

std::string IntegerProblem(std::string_view s) {
  if (s.empty()) return "empty value";
  std::int64_t v = 0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return "'" + std::string(s) + "' is not an integer";
  return "";
}

}  // namespace

std::string CsvTable::RowProblem(std::size_t row, const CsvRowRule& rule, std::size_t* col) const {
  std::string why;
  const auto check = [&](const std::vector<std::string>& names, bool optional, bool integer) {
    for (const std::string& name : names) {
      const int c = Column(name);
      if (c < 0 || !why.empty()) continue;
      const std::string_view s = Cell(row, c);
      if (optional && s.empty()) continue;
      double v = 0.0;
      const std::string p = integer ? IntegerProblem(s) : NumberProblem(s, &v);
      if (!p.empty()) {
        why = "column '" + name + "': " + p;
        *col = CharColumn(row, c);
      }
    }
  };
  check(rule.numbers, false, false);
  check(rule.optional_numbers, true, false);
  check(rule.integers, false, true);
  check(rule.optional_integers, true, true);
  for (const std::string& name : rule.texts) {
    const int c = Column(name);
    if (c >= 0 && why.empty() && Cell(row, c).empty()) {
      why = "column '" + name + "': empty value";
      *col = CharColumn(row, c);
    }
  }
  const int c_order = rule.non_decreasing.empty() ? -1 : Column(rule.non_decreasing);
  if (why.empty() && c_order >= 0) {
    double v = 0.0;
    const std::string p = NumberProblem(Cell(row, c_order), &v);
    if (!p.empty()) {
      why = "column '" + rule.non_decreasing + "': " + p;
      *col = CharColumn(row, c_order);
    }
  }
  return why;
}

void CsvTable::DropBadRows(const CsvRowRule& rule) {
  // 1. Rows whose cells the reader cannot use.
  std::vector<std::size_t> usable;
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    std::size_t col = 1;
    const std::string why = RowProblem(r, rule, &col);
    if (why.empty()) {
      usable.push_back(r);
    } else {
      skipped_.push_back(SkippedRow{rows_[r].line, col, why});
    }
  }
  // 2. Time order: keep the longest run of usable rows in order (non-decreasing, or increasing), so
  // that one wild time far ahead costs that one row, not every row after it, and a row that jumped
  // back costs only itself. Patience sorting, O(n log n).
  std::vector<bool> keep(rows_.size(), false);
  const int c_order = rule.non_decreasing.empty() ? -1 : Column(rule.non_decreasing);
  if (c_order < 0) {
    for (std::size_t r : usable) keep[r] = true;
  } else {
    std::vector<double> t(usable.size());
    for (std::size_t i = 0; i < usable.size(); ++i) t[i] = Double(usable[i], c_order);
    // Built from the last row back (times negated), so that among equally long runs the one of the
    // earliest rows wins: a repeated or stepped-back time costs the later row.
    std::vector<std::size_t> tails;  // tails[k]: index (in usable) starting a run of k+1
    std::vector<std::ptrdiff_t> after(usable.size(), -1);  // the next element of i's run
    for (std::size_t i = usable.size(); i-- > 0;) {
      const auto less = [&](std::size_t a, std::size_t b) {
        return rule.increasing ? -t[a] <= -t[b] : -t[a] < -t[b];
      };
      const auto at = std::upper_bound(tails.begin(), tails.end(), i, less);
      const std::size_t k = static_cast<std::size_t>(at - tails.begin());
      if (k > 0) after[i] = static_cast<std::ptrdiff_t>(tails[k - 1]);
      if (at == tails.end()) {
        tails.push_back(i);
      } else {
        *at = i;
      }
    }
    std::vector<bool> in_run(usable.size(), false);
    for (std::ptrdiff_t i = tails.empty() ? -1 : static_cast<std::ptrdiff_t>(tails.back()); i >= 0;
         i = after[i]) {
      in_run[static_cast<std::size_t>(i)] = true;
    }
    std::ptrdiff_t prev_kept = -1;  // in usable
    for (std::size_t i = 0; i < usable.size(); ++i) {
      if (in_run[i]) {
        keep[usable[i]] = true;
        prev_kept = static_cast<std::ptrdiff_t>(i);
        continue;
      }
      std::string why = "column '" + rule.non_decreasing + "' ";
      const std::size_t r = usable[i];
      if (prev_kept >= 0 && t[i] <= t[static_cast<std::size_t>(prev_kept)]) {
        const std::size_t p = usable[static_cast<std::size_t>(prev_kept)];
        why += std::string(t[i] < t[static_cast<std::size_t>(prev_kept)] ? "goes backwards" : "repeats") +
               " (" + std::string(Cell(r, c_order)) + " after " + std::string(Cell(p, c_order)) +
               " on line " + std::to_string(Line(p)) + ")";
      } else {
        std::size_t next = i + 1;
        while (next < usable.size() && !in_run[next]) ++next;
        why += "jumps ahead of the rows after it (" + std::string(Cell(r, c_order)) +
               (next < usable.size() ? " before " + std::string(Cell(usable[next], c_order)) + " on line " +
                                           std::to_string(Line(usable[next]))
                                     : std::string()) +
               ")";
      }
      skipped_.push_back(SkippedRow{rows_[r].line, CharColumn(r, c_order), why});
    }
  }
  std::size_t n = 0;
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (!keep[r]) continue;
    if (n != r) rows_[n] = std::move(rows_[r]);
    ++n;
  }
  rows_.resize(n);
  std::stable_sort(skipped_.begin(), skipped_.end(),
                   [](const SkippedRow& a, const SkippedRow& b) { return a.line < b.line; });
}

void CsvTable::WarnSkipped() const {
  for (std::size_t i = 0; i < skipped_.size() && i < kMaxSkippedRowWarnings; ++i) {
    const SkippedRow& s = skipped_[i];
    EmitWarning(name_ + ":" + std::to_string(s.line) + ":" + std::to_string(s.column) +
                ": skipped bad row: " + s.reason);
  }
  if (skipped_.size() > kMaxSkippedRowWarnings) {
    EmitWarning(name_ + ": skipped " + std::to_string(skipped_.size()) + " bad rows in all (only the first " +
                std::to_string(kMaxSkippedRowWarnings) + " are listed)");
  }
}

CsvWriter::CsvWriter(std::vector<std::string> columns) : columns_(std::move(columns)) {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i) text_.push_back(',');
    text_ += columns_[i];
  }
  text_.push_back('\n');
}

void CsvWriter::Comment(std::string_view text) {
  RK_CHECK(fields_in_row_ == 0, "comment inside a row");
  text_ += "# ";
  text_ += text;
  text_.push_back('\n');
}

CsvWriter& CsvWriter::Add(std::string_view text) {
  if (fields_in_row_++) text_.push_back(',');
  bool quote = text.find_first_of(",\"\n") != std::string_view::npos;
  if (!quote) {
    text_ += text;
  } else {
    text_.push_back('"');
    for (char c : text) {
      if (c == '"') text_.push_back('"');
      text_.push_back(c);
    }
    text_.push_back('"');
  }
  return *this;
}

CsvWriter& CsvWriter::Add(std::int64_t value) {
  if (fields_in_row_++) text_.push_back(',');
  text_ += std::to_string(value);
  return *this;
}

CsvWriter& CsvWriter::Add(double value, int decimals) {
  if (fields_in_row_++) text_.push_back(',');
  if (std::isfinite(value)) {
    char buf[64];
    int n = std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    // Never write "-0.000".
    if (n > 0 && buf[0] == '-') {
      bool all_zero = true;
      for (int i = 1; i < n; ++i) {
        if (buf[i] != '0' && buf[i] != '.') all_zero = false;
      }
      if (all_zero) {
        text_.append(buf + 1, static_cast<std::size_t>(n - 1));
        return *this;
      }
    }
    text_.append(buf, static_cast<std::size_t>(n));
  }
  return *this;
}

CsvWriter& CsvWriter::Add(std::optional<double> value, int decimals) {
  if (value) return Add(*value, decimals);
  return AddEmpty();
}

CsvWriter& CsvWriter::AddEmpty() {
  if (fields_in_row_++) text_.push_back(',');
  return *this;
}

void CsvWriter::EndRow() {
  RK_CHECK(fields_in_row_ == columns_.size(), "row has " + std::to_string(fields_in_row_) +
                                                  " fields, header " + std::to_string(columns_.size()));
  text_.push_back('\n');
  fields_in_row_ = 0;
  ++rows_;
}

void CsvWriter::Write(const std::string& path) const {
  RK_CHECK(fields_in_row_ == 0, "unfinished row");
  WriteFileAtomic(path, text_);
}

std::vector<std::string> SplitList(std::string_view list, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t end = list.find(sep, start);
    if (end == std::string_view::npos) end = list.size();
    std::string_view item = Trim(list.substr(start, end - start));
    if (!item.empty()) out.emplace_back(item);
    start = end + 1;
  }
  return out;
}

}  // namespace rk::io

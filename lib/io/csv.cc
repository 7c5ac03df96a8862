#include "io/csv.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <string>

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

// Bytes read from a regular file at a time, when indexing it and when its rows are read again.
constexpr std::size_t kWindowBytes = std::size_t{1} << 20;

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

// "" when `s` is an integer (stored in *v): integer text, or a finite number (NumberProblem's rules)
// whose value is an exact integer within int64 ("+0", "0.0", "0e0", "1e3" as pandas writes them).
std::string IntegerProblem(std::string_view s, std::int64_t* v) {
  if (s.empty()) return "empty value";
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), *v);
  if (ec == std::errc() && ptr == s.data() + s.size()) return "";
  double d = 0.0;
  // 2^63 is exact in a double; every integral double below it in magnitude fits int64.
  constexpr double kTwo63 = 9223372036854775808.0;
  if (NumberProblem(s, &d).empty() && d == std::trunc(d) && d >= -kTwo63 && d < kTwo63) {
    *v = static_cast<std::int64_t>(d);
    return "";
  }
  return "'" + std::string(s) + "' is not an integer";
}

std::string Unescape(std::string_view quoted) {
  std::string out;
  out.reserve(quoted.size());
  for (std::size_t i = 0; i < quoted.size(); ++i) {
    out.push_back(quoted[i]);
    if (quoted[i] == '"' && i + 1 < quoted.size() && quoted[i + 1] == '"') ++i;
  }
  return out;
}

}  // namespace

// One field of a row; offsets are relative to the row's first byte.
struct CsvTable::Field {
  std::uint32_t start = 0;  // where the field starts (after the previous comma): its column
  std::uint32_t begin = 0;  // its content: between the quotes, or trimmed of blanks
  std::uint32_t end = 0;
  bool escaped = false;     // quoted content holding "" (to be undone)
};

// Splits the row at the start of `s` (the caller has skipped blank and comment lines). Returns the
// length of the row with its line end, or std::string_view::npos when the row may go on past the end
// of `s` (more bytes needed; never when `at_eof`). *text_end: where the row's text ends (before
// "\r\n"). A quote still open at the end of the file throws DataError naming *open_quote's offset.
std::size_t CsvTable::SplitRow(std::string_view s, bool at_eof, std::vector<Field>* fields, std::size_t* text_end,
                              std::size_t* open_quote) {
  fields->clear();
  const std::size_t n = s.size();
  // The common row: one line without a quote, split at its commas only (the general loop below gives the
  // same fields; this one is what every number of a long log goes through). memchr finds each byte
  // several bytes at a time.
  const char* d = s.data();
  const char* nl = static_cast<const char*>(std::memchr(d, '\n', n));
  const std::size_t line_len = nl ? static_cast<std::size_t>(nl - d) : n;
  if (std::memchr(d, '"', line_len) == nullptr) {
    if (nl == nullptr && !at_eof) return std::string_view::npos;
    std::size_t from = 0;
    while (true) {
      const char* c = static_cast<const char*>(std::memchr(d + from, ',', line_len - from));
      const std::size_t to = c ? static_cast<std::size_t>(c - d) : line_len;
      std::size_t b = from, e = to;
      if (b < e && (d[b] == ' ' || d[b] == '\t')) {
        while (b < e && (d[b] == ' ' || d[b] == '\t')) ++b;
      }
      while (e > b && (d[e - 1] == ' ' || d[e - 1] == '\t' || d[e - 1] == '\r')) --e;
      fields->push_back(Field{static_cast<std::uint32_t>(from), static_cast<std::uint32_t>(b),
                              static_cast<std::uint32_t>(e), false});
      if (c == nullptr) break;
      from = to + 1;
    }
    *text_end = (line_len > 0 && d[line_len - 1] == '\r') ? line_len - 1 : line_len;
    return nl ? line_len + 1 : line_len;
  }
  std::size_t i = 0;
  while (true) {
    Field f;
    f.start = static_cast<std::uint32_t>(i);
    std::size_t j = i;
    while (j < n && (s[j] == ' ' || s[j] == '\t')) ++j;
    if (j < n && s[j] == '"') {
      *open_quote = j;
      f.begin = static_cast<std::uint32_t>(++j);
      while (true) {
        const void* q = j < n ? std::memchr(s.data() + j, '"', n - j) : nullptr;
        if (q == nullptr) {
          if (!at_eof) return std::string_view::npos;
          return std::string_view::npos;  // never closed: *open_quote says where it opened
        }
        j = static_cast<std::size_t>(static_cast<const char*>(q) - s.data());
        if (j + 1 < n && s[j + 1] == '"') {
          f.escaped = true;
          j += 2;
          continue;
        }
        if (j + 1 >= n && !at_eof) return std::string_view::npos;  // "" may follow
        break;
      }
      f.end = static_cast<std::uint32_t>(j);
      ++j;
      while (j < n && s[j] != ',' && s[j] != '\n') ++j;
      i = j;
    } else {
      while (i < n && s[i] != ',' && s[i] != '\n') ++i;
      const std::string_view t = Trim(s.substr(f.start, i - f.start));
      f.begin = static_cast<std::uint32_t>(t.data() - s.data());
      f.end = static_cast<std::uint32_t>(f.begin + t.size());
    }
    fields->push_back(f);
    if (i < n && s[i] == ',') {
      ++i;
      continue;
    }
    if (i >= n && !at_eof) return std::string_view::npos;
    *text_end = (i > 0 && s[i - 1] == '\r') ? i - 1 : i;
    return i < n ? i + 1 : i;
  }
}

// Where the text comes from. A regular file stays open and is read again by windows; anything else
// (stdin, a pipe, text given to Parse) is held in memory whole.
struct CsvTable::Source {
  int fd = -1;
  std::string text;  // the whole text (fd < 0), or the current window of the file
  std::uint64_t size = 0;
  std::uint64_t window_at = 0;  // file offset of text[0]
  ~Source() {
    if (fd >= 0) ::close(fd);
  }
  // At least `min_bytes` from `at` (fewer only at the end of the text).
  std::string_view Bytes(std::uint64_t at, std::size_t min_bytes, const std::string& name) {
    if (fd < 0) return std::string_view(text).substr(static_cast<std::size_t>(std::min<std::uint64_t>(at, size)));
    const std::uint64_t want_end = std::min<std::uint64_t>(size, at + min_bytes);
    if (at < window_at || want_end > window_at + text.size()) {
      // Reading on: the window starts at `at`. Reading back (at before the window): it ends a little
      // after `at`, so that a walk back through the rows reads each part of the file once.
      const std::uint64_t from = at < window_at && at > kWindowBytes / 2 ? at - kWindowBytes / 2 : at;
      const std::size_t len = static_cast<std::size_t>(
          std::min<std::uint64_t>(size - from, std::max<std::uint64_t>(at - from + min_bytes, kWindowBytes)));
      text.resize(len);
      std::size_t got = 0;
      while (got < len) {
        const ssize_t r = ::pread(fd, text.data() + got, len - got, static_cast<off_t>(from + got));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) throw IoError(name, r < 0 ? std::string("read error: ") + std::strerror(errno)
                                              : std::string("file shrank while being read"));
        got += static_cast<std::size_t>(r);
      }
      window_at = from;
    }
    return std::string_view(text).substr(static_cast<std::size_t>(at - window_at));
  }
};

struct CsvTable::RowCache {
  std::size_t row = static_cast<std::size_t>(-1);
  std::string_view text;  // the row read last (into the source's window)
  std::vector<Field> fields;
  // Columns asked for as text (Cell): each cell's text, end offsets per row.
  struct TextColumn {
    std::string data;
    std::vector<std::uint64_t> end;
  };
  std::vector<std::unique_ptr<TextColumn>> text_columns;
};

// The one pass over the text: header, then every data row's offset, line and field count.
class CsvTable::Indexer {
 public:
  Indexer(CsvTable* t, const CsvReadOptions& options) : t_(t), options_(options) {}

  // Indexes the rows that start in `s` (file offset `at`). Returns the bytes used: complete rows
  // (and blank or comment lines), fewer than s.size() when the last row may continue.
  std::size_t Feed(std::string_view s, std::uint64_t at, bool at_eof);
  void Finish() const {
    if (t_->header_.empty())
      throw DataError(t_->name_, line_no_ > 0 ? line_no_ : 1, 1, "no header row (file is empty)");
  }

 private:
  void Header(std::string_view row, std::size_t text_end);
  void Row(std::string_view row, std::uint64_t at, std::size_t nfields, std::size_t text_end);
  // 1-based line and column of offset `k` in `row` (which starts line line_no_).
  void Position(std::string_view row, std::size_t k, std::size_t* line, std::size_t* col) const;

  CsvTable* t_;
  const CsvReadOptions& options_;
  std::size_t line_no_ = 0;  // lines before the current one
  std::vector<Field> fields_;
};

void CsvTable::Indexer::Position(std::string_view row, std::size_t k, std::size_t* line, std::size_t* col) const {
  const std::string_view before = row.substr(0, k);
  const std::size_t nl = before.rfind('\n');
  *line = line_no_ + 1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  *col = nl == std::string_view::npos ? k + 1 : k - nl;
}

std::size_t CsvTable::Indexer::Feed(std::string_view s, std::uint64_t at, bool at_eof) {
  std::size_t pos = 0;
  std::size_t ncols = t_->header_.size();  // 0 until the header is read
  while (pos < s.size()) {
    const std::string_view rest = s.substr(pos);
    const void* nlp = std::memchr(rest.data(), '\n', rest.size());
    const bool nl = nlp != nullptr;
    if (!nl && !at_eof) break;
    const std::size_t len = nl ? static_cast<std::size_t>(static_cast<const char*>(nlp) - rest.data()) : rest.size();
    // Its commas, and whether it has a quote (then the row may span lines): two vectorised counts.
    const std::size_t commas = static_cast<std::size_t>(std::count(rest.data(), rest.data() + len, ','));
    const bool quoted = std::memchr(rest.data(), '"', len) != nullptr;
    const std::string_view line = rest.substr(0, len);
    const char first = len > 0 ? line[0] : '\n';
    if (first == ' ' || first == '\t' || first == '\r' || first == '#' || first == '\n') {
      const std::string_view trimmed = Trim(line);
      if (trimmed.empty() || trimmed.front() == '#') {
        pos += nl ? len + 1 : len;
        ++line_no_;
        continue;
      }
    }
    if (!quoted && ncols > 0) {  // the common row: one line, no quotes
      const std::size_t text_end = (len > 0 && line[len - 1] == '\r') ? len - 1 : len;
      Row(line, at + pos, commas + 1, text_end);
      ++line_no_;
      pos += nl ? len + 1 : len;
      continue;
    }
    std::size_t open_quote = 0, text_end = 0;
    const std::size_t used = SplitRow(rest, at_eof, &fields_, &text_end, &open_quote);
    if (used == std::string_view::npos) {
      if (!at_eof) break;
      std::size_t l = 0, c = 0;
      Position(rest, open_quote, &l, &c);
      throw DataError(t_->name_, l, c, "a quoted field is never closed (a '\"' is missing)");
    }
    const std::string_view row = rest.substr(0, used);
    if (ncols == 0) {
      Header(row, text_end);
      ncols = t_->header_.size();
    } else {
      Row(row, at + pos, fields_.size(), text_end);
    }
    line_no_ += static_cast<std::size_t>(std::count(row.begin(), row.end(), '\n'));
    if (!row.empty() && row.back() != '\n') ++line_no_;  // the last line, without '\n'
    pos += used;
  }
  return pos;
}

void CsvTable::Indexer::Header(std::string_view row, std::size_t text_end) {
  std::size_t open_quote = 0;
  SplitRow(row, true, &fields_, &text_end, &open_quote);
  std::vector<std::string> cells;
  for (const Field& f : fields_) {
    const std::string_view c = row.substr(f.begin, f.end - f.begin);
    cells.push_back(f.escaped ? Unescape(c) : std::string(c));
  }
  for (std::size_t c = 0; c < cells.size(); ++c) {
    std::size_t l = 0, col = 0;
    Position(row, fields_[c].start, &l, &col);
    if (cells[c].empty()) throw DataError(t_->name_, l, col, "empty column name in header");
    for (std::size_t k = 0; k < c; ++k) {
      if (cells[k] == cells[c]) throw DataError(t_->name_, l, col, "duplicate column '" + cells[c] + "'");
    }
  }
  t_->header_ = std::move(cells);
  t_->header_line_ = line_no_ + 1;
}

void CsvTable::Indexer::Row(std::string_view row, std::uint64_t at, std::size_t nfields, std::size_t text_end) {
  const std::size_t ncols = t_->header_.size();
  if (nfields != ncols) {
    std::size_t k = text_end;
    if (nfields > ncols) {
      std::size_t open_quote = 0, e = 0;
      SplitRow(row, true, &fields_, &e, &open_quote);
      k = fields_[ncols].start;
    }
    std::size_t l = 0, col = 0;
    Position(row, k, &l, &col);
    const std::string what =
        "row has " + std::to_string(nfields) + " fields, header has " + std::to_string(ncols);
    if (options_.bad_rows == BadRows::kSkip) {
      t_->skipped_.push_back(SkippedRow{l, col, what});
      return;
    }
    throw DataError(t_->name_, l, col, what);
  }
  if (line_no_ + 1 > std::numeric_limits<std::uint32_t>::max())
    throw DataError(t_->name_, line_no_ + 1, 0, "more than 4294967295 lines");
  const std::size_t r = t_->line_.size();
  while (at >> 32 > t_->start_hi_.size()) t_->start_hi_.push_back(r);
  t_->start_lo_.push_back(static_cast<std::uint32_t>(at));
  t_->line_.push_back(static_cast<std::uint32_t>(line_no_ + 1));
}

namespace {

// UTF-16 (a byte-order mark FF FE / FE FF, or NUL bytes, as ASCII text in UTF-16 has) is not CSV text.
void RequireNotUtf16(std::string_view head, const std::string& name) {
  const auto b = [&](std::size_t i) { return static_cast<unsigned char>(head[i]); };
  const bool bom = head.size() >= 2 && ((b(0) == 0xFF && b(1) == 0xFE) || (b(0) == 0xFE && b(1) == 0xFF));
  if (bom || head.find('\0') != std::string_view::npos) throw DataError(name, 0, 0, "not UTF-8 text (UTF-16?)");
}

// Length of a UTF-8 byte-order mark at the start of `head` (skipped: columns count from after it).
std::size_t Utf8BomLength(std::string_view head) {
  return head.size() >= 3 && static_cast<unsigned char>(head[0]) == 0xEF &&
                 static_cast<unsigned char>(head[1]) == 0xBB && static_cast<unsigned char>(head[2]) == 0xBF
             ? 3
             : 0;
}

}  // namespace

CsvTable CsvTable::Index(std::shared_ptr<Source> src, const std::string& name, const CsvReadOptions& options) {
  CsvTable t;
  t.name_ = name;
  t.cache_ = std::make_shared<RowCache>();
  Indexer indexer(&t, options);
  if (src->fd < 0) {
    const std::string_view text = src->text;
    RequireNotUtf16(text.substr(0, 4096), name);
    const std::size_t bom = Utf8BomLength(text);
    indexer.Feed(text.substr(bom), bom, true);
  } else {
    // The file once through a window: only the part of a row that spans two reads is kept over.
    std::string buf;
    std::uint64_t at = 0;  // file offset of buf[0]
    std::uint64_t read_to = 0;
    bool first = true;
    struct stat st {};
    const std::uint64_t file_size = ::fstat(src->fd, &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
    while (true) {
      const std::size_t kept = buf.size();
      buf.resize(kept + kWindowBytes);
      ssize_t r = 0;
      do {
        r = ::read(src->fd, buf.data() + kept, kWindowBytes);
      } while (r < 0 && errno == EINTR);
      if (r < 0) throw IoError(name, std::string("read error: ") + std::strerror(errno));
      buf.resize(kept + static_cast<std::size_t>(r));
      read_to += static_cast<std::uint64_t>(r);
      const bool eof = r == 0;
      std::size_t skip = 0;
      if (first && (buf.size() >= 4096 || eof)) {
        RequireNotUtf16(std::string_view(buf).substr(0, 4096), name);
        skip = Utf8BomLength(buf);
        first = false;
      } else if (first) {
        continue;
      }
      const std::size_t used = skip + indexer.Feed(std::string_view(buf).substr(skip), at + skip, eof);
      if (at == 0 && used > 0 && file_size > used) t.ReserveRows(file_size, used);
      buf.erase(0, used);
      at += used;
      if (eof) break;
    }
    src->size = read_to;
    src->text.clear();
    src->text.shrink_to_fit();
    src->window_at = 0;
  }
  indexer.Finish();
  t.src_ = std::move(src);
  t.cache_->text_columns.resize(t.header_.size());
  if (options.bad_rows == BadRows::kSkip) {
    t.DropBadRows(options.rule);
    t.WarnSkipped();
  }
  // Capacity left over from the estimate (or the vectors' growth) is given back when it is worth it.
  if (t.start_lo_.capacity() > t.rows() + t.rows() / 16 + 4096) {
    t.start_lo_.shrink_to_fit();
    t.line_.shrink_to_fit();
  }
  return t;
}

CsvTable CsvTable::Parse(std::string_view text, const std::string& name, const CsvReadOptions& options) {
  auto src = std::make_shared<Source>();
  src->text = std::string(text);
  src->size = text.size();
  return Index(std::move(src), name, options);
}

CsvTable CsvTable::Read(const std::string& path, const CsvReadOptions& options) {
  const std::string name = IsStdStream(path) ? std::string("<stdin>") : path;
  auto src = std::make_shared<Source>();
  struct stat st {};
  if (!IsStdStream(path) && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
    src->fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (src->fd < 0) throw IoError(path, std::string("cannot open for reading: ") + std::strerror(errno));
    // Recorded before the text is judged, so that the report of a run failed by this file names it.
    RecordInputRead(path, static_cast<std::uintmax_t>(st.st_size));
  }
  if (src->fd < 0) {
    src->text = ReadFile(path);  // stdin, a pipe, a device: held in memory
    src->size = src->text.size();
  }
  CsvTable t = Index(std::move(src), name, options);
  if (t.src_->fd >= 0) RecordInputRead(path, t.src_->size);  // what was read, should the file have grown
  RecordCsvRead(path, t.skipped_.size());
  return t;
}

void CsvTable::ReserveRows(std::uint64_t file_bytes, std::uint64_t bytes_so_far) {
  // The rows of the whole file by those of its first part, 2 % over (a log's rows are much alike).
  const double estimate = static_cast<double>(rows()) * static_cast<double>(file_bytes) /
                              static_cast<double>(bytes_so_far) * 1.02 + 1024.0;
  if (estimate < 4e9) {
    start_lo_.reserve(static_cast<std::size_t>(estimate));
    line_.reserve(static_cast<std::size_t>(estimate));
  }
}

std::uint64_t CsvTable::RowStart(std::size_t row) const {
  const std::uint64_t hi = static_cast<std::uint64_t>(
      std::upper_bound(start_hi_.begin(), start_hi_.end(), row) - start_hi_.begin());
  return (hi << 32) | start_lo_[row];
}

const CsvTable::Field& CsvTable::FieldAt(std::size_t row, int col) const {
  RowCache& c = *cache_;
  if (c.row != row) {
    const std::uint64_t at = RowStart(row);
    std::size_t want = 256;
    while (true) {
      const std::string_view s = src_->Bytes(at, want, name_);
      const bool eof = at + s.size() >= src_->size;
      std::size_t text_end = 0, open_quote = 0;
      const std::size_t used = SplitRow(s, eof, &c.fields, &text_end, &open_quote);
      if (used != std::string_view::npos) {
        c.text = s.substr(0, used);
        break;
      }
      if (eof) throw IoError(name_, "changed while being read");
      want = std::max(want * 2, s.size() + 1);
    }
    if (c.fields.size() != header_.size()) {
      c.row = static_cast<std::size_t>(-1);
      throw IoError(name_, "changed while being read");
    }
    c.row = row;
  }
  return c.fields[static_cast<std::size_t>(col)];
}

std::string_view CsvTable::Content(const Field& f) const { return cache_->text.substr(f.begin, f.end - f.begin); }

std::string CsvTable::CellText(std::size_t row, int col) const {
  const Field& f = FieldAt(row, col);
  return f.escaped ? Unescape(Content(f)) : std::string(Content(f));
}

void CsvTable::CellPosition(std::size_t row, int col, std::size_t* line, std::size_t* column) const {
  const Field& f = FieldAt(row, col);
  const std::string_view before = cache_->text.substr(0, f.start);
  const std::size_t nl = before.rfind('\n');
  *line = Line(row) + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  *column = nl == std::string_view::npos ? f.start + 1 : f.start - nl;
}

std::size_t CsvTable::HeldBytes() const {
  std::size_t n = start_lo_.capacity() * sizeof(std::uint32_t) + start_hi_.capacity() * sizeof(std::size_t) +
                  line_.capacity() * sizeof(std::uint32_t) + skipped_.capacity() * sizeof(SkippedRow);
  if (src_) n += src_->text.capacity();
  if (cache_) {
    n += cache_->fields.capacity() * sizeof(Field);
    for (const auto& tc : cache_->text_columns) {
      if (tc) n += tc->data.capacity() + tc->end.capacity() * sizeof(std::uint64_t);
    }
  }
  return n;
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
  // Text held in memory: the cell itself (unless its "" escapes must be undone).
  if (src_->fd < 0) {
    const Field& f = FieldAt(row, col);
    if (!f.escaped) return Content(f);
  }
  // A file: the column is read once as text and kept (a column asked for as text is usually read whole).
  auto& tc = cache_->text_columns[static_cast<std::size_t>(col)];
  if (!tc) {
    tc = std::make_unique<RowCache::TextColumn>();
    tc->end.reserve(rows());
    for (std::size_t r = 0; r < rows(); ++r) {
      const Field& f = FieldAt(r, col);
      if (f.escaped) {
        tc->data += Unescape(Content(f));
      } else {
        tc->data += Content(f);
      }
      tc->end.push_back(tc->data.size());
    }
    tc->data.shrink_to_fit();
  }
  const std::size_t b = row == 0 ? 0 : static_cast<std::size_t>(tc->end[row - 1]);
  return std::string_view(tc->data).substr(b, static_cast<std::size_t>(tc->end[row]) - b);
}

std::size_t CsvTable::CharColumn(std::size_t row, int col) const {
  std::size_t line = 0, column = 0;
  CellPosition(row, col, &line, &column);
  return column;
}

Error CsvTable::PositionError(std::size_t row, int col, const std::string& what) const {
  std::size_t line = 0, column = 0;
  CellPosition(row, col, &line, &column);
  return DataError(name_, line, column, what);
}

Error CsvTable::CellError(std::size_t row, int col, const std::string& what) const {
  return PositionError(row, col, "column '" + header_[static_cast<std::size_t>(col)] + "': " + what);
}

double CsvTable::Double(std::size_t row, int col) const {
  double v = 0.0;
  const Field& f = FieldAt(row, col);
  const std::string_view s = Content(f);
  if (!f.escaped && !s.empty() && s.front() != '+') {
    // The common case, without building a message.
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc() && ptr == s.data() + s.size() && std::isfinite(v)) return v;
  }
  const std::string problem = NumberProblem(CellText(row, col), &v);
  if (!problem.empty()) throw CellError(row, col, problem);
  return v;
}

std::optional<double> CsvTable::OptionalDouble(std::size_t row, int col) const {
  if (IsEmpty(row, col)) return std::nullopt;
  return Double(row, col);
}

bool CsvTable::IsEmpty(std::size_t row, int col) const {
  const Field& f = FieldAt(row, col);
  return f.begin == f.end;
}

std::int64_t CsvTable::Int(std::size_t row, int col) const {
  const std::string s = CellText(row, col);
  std::int64_t v = 0;
  if (!IntegerProblem(s, &v).empty()) {
    throw CellError(row, col, "'" + s + "' is not an integer");
  }
  return v;
}

void CsvTable::RequireNonDecreasing(int col) const {
  double prev = rows() > 0 ? Double(0, col) : 0.0;
  for (std::size_t r = 1; r < rows(); ++r) {
    const double cur = Double(r, col);
    if (cur < prev) {
      throw PositionError(r, col, "column '" + header_[static_cast<std::size_t>(col)] + "' goes backwards (" +
                                      CellText(r, col) + " after " + CellText(r - 1, col) + ")");
    }
    prev = cur;
  }
}

void CsvTable::RequireIncreasing(int col) const {
  RequireNonDecreasing(col);
  double prev = rows() > 0 ? Double(0, col) : 0.0;
  for (std::size_t r = 1; r < rows(); ++r) {
    const double cur = Double(r, col);
    if (cur == prev) {
      throw PositionError(r, col, "column '" + header_[static_cast<std::size_t>(col)] + "' repeats the value " +
                                      CellText(r, col));
    }
    prev = cur;
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

std::string CsvTable::RowProblem(std::size_t row, const CsvRowRule& rule, std::size_t* line,
                                 std::size_t* col) const {
  std::string why;
  const auto check = [&](const std::vector<std::string>& names, bool optional, bool integer) {
    for (const std::string& name : names) {
      const int c = Column(name);
      if (c < 0 || !why.empty()) continue;
      if (optional && IsEmpty(row, c)) continue;
      const std::string s = CellText(row, c);
      double v = 0.0;
      std::int64_t k = 0;
      const std::string p = integer ? IntegerProblem(s, &k) : NumberProblem(s, &v);
      if (!p.empty()) {
        why = "column '" + name + "': " + p;
        CellPosition(row, c, line, col);
      }
    }
  };
  check(rule.numbers, false, false);
  check(rule.optional_numbers, true, false);
  check(rule.integers, false, true);
  check(rule.optional_integers, true, true);
  for (const std::string& name : rule.texts) {
    const int c = Column(name);
    if (c >= 0 && why.empty() && IsEmpty(row, c)) {
      why = "column '" + name + "': empty value";
      CellPosition(row, c, line, col);
    }
  }
  const int c_order = rule.non_decreasing.empty() ? -1 : Column(rule.non_decreasing);
  if (why.empty() && c_order >= 0) {
    double v = 0.0;
    const std::string p = NumberProblem(CellText(row, c_order), &v);
    if (!p.empty()) {
      why = "column '" + rule.non_decreasing + "': " + p;
      CellPosition(row, c_order, line, col);
    }
  }
  return why;
}

void CsvTable::DropBadRows(const CsvRowRule& rule) {
  // 1. Rows whose cells the reader cannot use.
  std::vector<std::size_t> usable;
  for (std::size_t r = 0; r < rows(); ++r) {
    std::size_t line = Line(r), col = 1;
    const std::string why = RowProblem(r, rule, &line, &col);
    if (why.empty()) {
      usable.push_back(r);
    } else {
      skipped_.push_back(SkippedRow{line, col, why});
    }
  }
  // 2. Time order: keep the longest run of usable rows in order (non-decreasing, or increasing), so
  // that one wild time far ahead costs that one row, not every row after it, and a row that jumped
  // back costs only itself. Patience sorting, O(n log n).
  std::vector<bool> keep(rows(), false);
  const int c_order = rule.non_decreasing.empty() ? -1 : Column(rule.non_decreasing);
  const int c_per = rule.increasing_per.empty() ? -1 : Column(rule.increasing_per);
  const bool strict = rule.increasing || (!rule.increasing_per.empty() && c_per < 0);
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
        return strict ? -t[a] <= -t[b] : -t[a] < -t[b];
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
               " (" + CellText(r, c_order) + " after " + CellText(p, c_order) +
               " on line " + std::to_string(Line(p)) + ")";
      } else {
        std::size_t next = i + 1;
        while (next < usable.size() && !in_run[next]) ++next;
        why += "jumps ahead of the rows after it (" + CellText(r, c_order) +
               (next < usable.size() ? " before " + CellText(usable[next], c_order) + " on line " +
                                           std::to_string(Line(usable[next]))
                                     : std::string()) +
               ")";
      }
      std::size_t line = 0, col = 0;
      CellPosition(r, c_order, &line, &col);
      skipped_.push_back(SkippedRow{line, col, why});
    }
    // 3. Within each value of `increasing_per` (the run above is in order overall): a repeated time is a
    // duplicated record; the later row goes.
    if (c_per >= 0) {
      std::map<std::string, std::size_t, std::less<>> last;  // value → its last kept row (in usable)
      for (std::size_t i = 0; i < usable.size(); ++i) {
        if (!in_run[i]) continue;
        const std::size_t r = usable[i];
        const auto [it, first] = last.try_emplace(CellText(r, c_per), i);
        if (first) continue;
        if (t[i] > t[it->second]) {
          it->second = i;
          continue;
        }
        keep[r] = false;
        std::size_t line = 0, col = 0;
        CellPosition(r, c_order, &line, &col);
        skipped_.push_back(SkippedRow{line, col, "column '" + rule.non_decreasing + "' repeats for " +
                                                     rule.increasing_per + " '" + it->first + "' (" +
                                                     CellText(r, c_order) + " on line " +
                                                     std::to_string(Line(usable[it->second])) + ")"});
      }
    }
  }
  KeepRows(keep);
  std::stable_sort(skipped_.begin(), skipped_.end(),
                   [](const SkippedRow& a, const SkippedRow& b) { return a.line < b.line; });
}

void CsvTable::KeepRows(const std::vector<bool>& keep) {
  std::vector<std::size_t> hi;
  std::size_t n = 0;
  for (std::size_t r = 0; r < rows(); ++r) {
    if (!keep[r]) continue;
    const std::uint64_t at = RowStart(r);
    while (at >> 32 > hi.size()) hi.push_back(n);
    start_lo_[n] = start_lo_[r];
    line_[n] = line_[r];
    ++n;
  }
  start_lo_.resize(n);
  line_.resize(n);
  start_hi_ = std::move(hi);
  cache_->row = static_cast<std::size_t>(-1);
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
    // std::to_chars: the exactly rounded decimal, as printf's "%.*f" gives it (ties to even), ≈ 5× faster.
    char buf[400];
    const std::to_chars_result res = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, decimals);
    RK_CHECK(res.ec == std::errc(), "a finite number with at most 17 decimals fits 400 characters");
    const int n = static_cast<int>(res.ptr - buf);
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

std::string CsvWriter::TakeText() {
  RK_CHECK(fields_in_row_ == 0, "unfinished row");
  std::string out = std::move(text_);
  text_.clear();
  return out;
}

void CsvWriter::DrainTo(OutputFile* file) {
  RK_CHECK(fields_in_row_ == 0, "unfinished row");
  file->Write(text_);
  text_.clear();
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

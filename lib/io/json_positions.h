// Where each value of a JSON text sits (line and column), so that errors about a JSON file's fields
// (trial.json, pointing.json) can say "trial.json:7:22: ..." like every other input error (SPEC.md §4). nlohmann-json
// keeps no positions, so this is a small scanner over the text that nlohmann already accepted
// (it understands the same // and /* */ comments that io::ParseJson allows).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>

namespace rk::io {

struct TextPosition {
  std::size_t line = 0;    // 1-based; 0 = unknown
  std::size_t column = 0;  // 1-based
};

// Nesting deeper than this is not indexed, and io::ParseJson refuses it: no real file nests so deep, and
// nlohmann's writer and copies recurse once per level (a 5000-deep key overflowed rk-run's stack).
inline constexpr std::size_t kMaxJsonDepth = 512;

// A key that stands twice in one object (nlohmann keeps the last silently).
struct JsonDuplicateKey {
  std::string pointer;   // "/cameras/az/role"
  TextPosition at;       // the second occurrence
  TextPosition first;    // the first
};

class JsonPositions {
 public:
  JsonPositions() = default;
  // Indexes every value by its JSON pointer ("" = root, "/cameras/az/role", "/cameras/az/video/0").
  // Text that is not valid JSON leaves the index partial (positions are a convenience).
  explicit JsonPositions(const std::string& text);
  // Position of the value at `pointer`, or of its nearest indexed ancestor.
  TextPosition At(const std::string& pointer) const;
  // Position of the key naming the value at `pointer` (e.g. an unknown key), else At(pointer).
  TextPosition KeyAt(const std::string& pointer) const;
  // The first key that stands twice in one object, if any. A UTF-8 byte-order mark at the start is
  // skipped (positions count from the character after it); nesting deeper than kMaxJsonDepth is not indexed.
  const std::optional<JsonDuplicateKey>& duplicate() const { return duplicate_; }
  // Where the text first nests deeper than kMaxJsonDepth, if it does.
  const std::optional<TextPosition>& too_deep() const { return too_deep_; }

 private:
  std::map<std::string, TextPosition> values_;
  std::map<std::string, TextPosition> keys_;
  std::optional<JsonDuplicateKey> duplicate_;
  std::optional<TextPosition> too_deep_;
};

// JSON pointer escaping of one reference token (~ → ~0, / → ~1).
std::string PointerToken(const std::string& key);

}  // namespace rk::io

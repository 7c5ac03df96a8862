#include "io/json_util.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "io/error.h"
#include "io/file_util.h"
#include "io/json_positions.h"

namespace rk::io {

namespace {

// 1-based line and column of byte `offset` (0-based) of `text`.
std::pair<std::size_t, std::size_t> LineColumn(const std::string& text, std::size_t offset) {
  std::size_t line = 1, col = 1;
  const std::size_t end = std::min(offset, text.size());
  const std::size_t bom = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // not a column
  for (std::size_t i = std::min(bom, end); i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

std::string FromParseError(const std::string& what) {
  const auto p = what.find("parse error");
  return p == std::string::npos ? what : what.substr(p);
}

}  // namespace

Json ParseJson(const std::string& text, const std::string& name) {
  const JsonPositions positions(text);
  if (const auto& deep = positions.too_deep()) {
    throw DataError(name, deep->line, deep->column,
                    "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels (no rangekit file does that)");
  }
  try {
    Json j = Json::parse(text, nullptr, true, /*ignore_comments=*/true);
    // A key given twice would silently lose its first value: refused, at the second.
    if (const auto& d = positions.duplicate()) {
      const std::string key = d->pointer.substr(d->pointer.rfind('/') + 1);
      throw DataError(name, d->at.line, d->at.column,
                      "duplicate key '" + key + "' (first at line " + std::to_string(d->first.line) + ":" +
                          std::to_string(d->first.column) + "); a key may stand only once in an object");
    }
    return j;
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset of the offending byte.
    const auto [line, col] = LineColumn(text, e.byte > 0 ? e.byte - 1 : 0);
    throw DataError(name, line, col, "invalid JSON: " + FromParseError(e.what()));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number too large for a double (1e400) is reported as out_of_range 406 "number overflow parsing
    // '<token>'", without a position: find the token in the text.
    const std::string what = e.what();
    const auto q = what.find('\''), r = what.rfind('\'');
    const std::string token = q < r && r != std::string::npos ? what.substr(q + 1, r - q - 1) : std::string();
    const std::size_t at = token.empty() ? std::string::npos : text.find(token);
    const auto [line, col] = at == std::string::npos ? std::pair<std::size_t, std::size_t>{0, 0} : LineColumn(text, at);
    throw DataError(name, line, col, "invalid JSON: number out of range '" + token + "'");
  }
}

Json LoadJson(const std::string& path) {
  return ParseJson(ReadFile(path), IsStdStream(path) ? "<stdin>" : path);
}

double RequireNumber(const Json& j, const std::string& key, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) throw DataError(where, 0, 0, "missing field '" + key + "'");
  const Json& v = j.at(key);
  if (!v.is_number()) throw DataError(where, 0, 0, "field '" + key + "' must be a number");
  double d = v.get<double>();
  if (!std::isfinite(d)) throw DataError(where, 0, 0, "field '" + key + "' is not finite");
  return d;
}

double NumberOr(const Json& j, const std::string& key, double fallback, const std::string& where) {
  if (!j.is_object() || !j.contains(key) || j.at(key).is_null()) return fallback;
  return RequireNumber(j, key, where);
}

std::vector<double> RequireNumbers(const Json& j, const std::string& key, std::size_t min_n, std::size_t max_n,
                                   const std::string& where) {
  if (!j.is_object() || !j.contains(key)) throw DataError(where, 0, 0, "missing field '" + key + "'");
  const Json& v = j.at(key);
  if (!v.is_array() || v.size() < min_n || v.size() > max_n) {
    throw DataError(where, 0, 0,
                    "field '" + key + "' must be an array of " +
                        (min_n == max_n ? std::to_string(min_n)
                                        : std::to_string(min_n) + " to " + std::to_string(max_n)) +
                        " numbers");
  }
  std::vector<double> out;
  for (const auto& e : v) {
    if (!e.is_number() || !std::isfinite(e.get<double>())) {
      throw DataError(where, 0, 0, "field '" + key + "' must contain only finite numbers");
    }
    out.push_back(e.get<double>());
  }
  return out;
}

std::string RequireString(const Json& j, const std::string& key, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) throw DataError(where, 0, 0, "missing field '" + key + "'");
  if (!j.at(key).is_string()) throw DataError(where, 0, 0, "field '" + key + "' must be a string");
  return j.at(key).get<std::string>();
}

// Strings taken from input files (a CSV cell quoted in a problem message, a file name) need not be valid
// UTF-8; nlohmann::json would throw type_error 316 while writing them. Invalid bytes become U+FFFD.
std::string JsonText(const Json& j) { return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

void WriteJson(const std::string& path, const Json& j) { WriteFileAtomic(path, JsonText(j)); }

}  // namespace rk::io

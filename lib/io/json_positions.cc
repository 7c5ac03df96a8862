#include "io/json_positions.h"

#include <cctype>
#include <set>

namespace rk::io {
namespace {

class Scanner {
 public:
  Scanner(const std::string& text, std::map<std::string, TextPosition>* values,
          std::map<std::string, TextPosition>* keys, std::optional<JsonDuplicateKey>* duplicate,
          std::optional<TextPosition>* too_deep)
      : s_(text), values_(values), keys_(keys), duplicate_(duplicate), too_deep_(too_deep) {
    // A UTF-8 byte-order mark is not part of the text an editor shows: line 1 starts after it.
    if (s_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = 3;
  }

  bool Value(const std::string& pointer) {
    Skip();
    // Nesting deeper than any real file: the rest is not indexed (no recursion without bound).
    if (depth_ >= kMaxDepth) {
      if (!*too_deep_) *too_deep_ = Here();
      return false;
    }
    if (i_ >= s_.size()) return false;
    (*values_)[pointer] = Here();
    const char c = s_[i_];
    if (c == '{') return Object(pointer);
    if (c == '[') return Array(pointer);
    if (c == '"') {
      std::string ignored;
      return String(&ignored);
    }
    // number, true, false, null
    while (i_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[i_])) && s_[i_] != ',' &&
           s_[i_] != ']' && s_[i_] != '}' && s_[i_] != '/') {
      Advance();
    }
    return true;
  }

 private:
  TextPosition Here() const { return {line_, col_}; }
  void Advance() {
    if (s_[i_] == '\n') {
      ++line_;
      col_ = 1;
    } else {
      ++col_;
    }
    ++i_;
  }
  void Skip() {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (std::isspace(static_cast<unsigned char>(c))) {
        Advance();
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/') {
        while (i_ < s_.size() && s_[i_] != '\n') Advance();
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '*') {
        Advance();
        Advance();
        while (i_ + 1 < s_.size() && !(s_[i_] == '*' && s_[i_ + 1] == '/')) Advance();
        if (i_ + 1 < s_.size()) {
          Advance();
          Advance();
        } else {
          i_ = s_.size();
        }
      } else {
        return;
      }
    }
  }
  bool String(std::string* out) {
    Advance();  // opening quote
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\') {
        Advance();
        if (i_ >= s_.size()) return false;
        const char e = s_[i_];
        switch (e) {
          case 'n': out->push_back('\n'); break;
          case 't': out->push_back('\t'); break;
          case 'r': out->push_back('\r'); break;
          case 'b': out->push_back('\b'); break;
          case 'f': out->push_back('\f'); break;
          case 'u': out->append("\\u"); break;  // keys with \u escapes are not expected in manifests
          default: out->push_back(e); break;
        }
        Advance();
        continue;
      }
      out->push_back(s_[i_]);
      Advance();
    }
    if (i_ >= s_.size()) return false;
    Advance();  // closing quote
    return true;
  }
  struct Depth {
    explicit Depth(std::size_t* d) : d_(d) { ++*d_; }
    ~Depth() { --*d_; }
    std::size_t* d_;
  };
  bool Object(const std::string& pointer) {
    const Depth depth(&depth_);
    std::set<std::string> seen;
    Advance();
    Skip();
    if (i_ < s_.size() && s_[i_] == '}') {
      Advance();
      return true;
    }
    while (i_ < s_.size()) {
      Skip();
      if (i_ >= s_.size() || s_[i_] != '"') return false;
      const TextPosition key_pos = Here();
      std::string key;
      if (!String(&key)) return false;
      const std::string child = pointer + "/" + PointerToken(key);
      if (!seen.insert(key).second && !*duplicate_) {
        *duplicate_ = JsonDuplicateKey{child, key_pos, (*keys_)[child]};
      }
      (*keys_)[child] = key_pos;
      Skip();
      if (i_ >= s_.size() || s_[i_] != ':') return false;
      Advance();
      if (!Value(child)) return false;
      Skip();
      if (i_ >= s_.size()) return false;
      if (s_[i_] == ',') {
        Advance();
        continue;
      }
      if (s_[i_] == '}') {
        Advance();
        return true;
      }
      return false;
    }
    return false;
  }
  bool Array(const std::string& pointer) {
    const Depth depth(&depth_);
    Advance();
    Skip();
    if (i_ < s_.size() && s_[i_] == ']') {
      Advance();
      return true;
    }
    for (std::size_t k = 0; i_ < s_.size(); ++k) {
      if (!Value(pointer + "/" + std::to_string(k))) return false;
      Skip();
      if (i_ >= s_.size()) return false;
      if (s_[i_] == ',') {
        Advance();
        continue;
      }
      if (s_[i_] == ']') {
        Advance();
        return true;
      }
      return false;
    }
    return false;
  }

  const std::string& s_;
  std::map<std::string, TextPosition>* values_;
  std::map<std::string, TextPosition>* keys_;
  std::optional<JsonDuplicateKey>* duplicate_;
  std::optional<TextPosition>* too_deep_;
  static constexpr std::size_t kMaxDepth = kMaxJsonDepth;
  std::size_t i_ = 0, line_ = 1, col_ = 1, depth_ = 0;
};

}  // namespace

std::string PointerToken(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out.push_back(c);
  }
  return out;
}

JsonPositions::JsonPositions(const std::string& text) {
  Scanner scanner(text, &values_, &keys_, &duplicate_, &too_deep_);
  scanner.Value("");
}

TextPosition JsonPositions::At(const std::string& pointer) const {
  std::string p = pointer;
  for (;;) {
    auto it = values_.find(p);
    if (it != values_.end()) return it->second;
    if (p.empty()) return {};
    const auto slash = p.rfind('/');
    p = slash == std::string::npos ? std::string() : p.substr(0, slash);
  }
}

TextPosition JsonPositions::KeyAt(const std::string& pointer) const {
  auto it = keys_.find(pointer);
  if (it != keys_.end()) return it->second;
  return At(pointer);
}

}  // namespace rk::io

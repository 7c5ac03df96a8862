// stations.json reader; see stations.h.
#include "intersect/stations.h"

#include <cctype>
#include <cmath>
#include <filesystem>

#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"

namespace rk::intersect {
namespace {

// Byte offsets of JSON values in the text, found by a small scanner over text nlohmann has already
// accepted (nlohmann keeps no positions): a path of object keys and array indices → offset of that value.
class JsonLocator {
 public:
  explicit JsonLocator(const std::string& text) : s_(text) {}

  // Offset of the value at `path` (keys as strings, indices as "#<i>"), or of the deepest part found.
  std::size_t Find(const std::vector<std::string>& path) const {
    std::size_t at = SkipWs(0), found = at;
    for (const std::string& step : path) {
      if (at >= s_.size()) break;
      const std::size_t next = Child(at, step);
      if (next == std::string::npos) break;
      at = found = next;
    }
    return found;
  }

  // 1-based line and column of an offset.
  void LineCol(std::size_t offset, std::size_t* line, std::size_t* col) const {
    *line = 1, *col = 1;
    for (std::size_t i = 0; i < offset && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++*line, *col = 1;
      } else {
        ++*col;
      }
    }
  }

 private:
  std::size_t SkipWs(std::size_t i) const {
    while (i < s_.size() && std::isspace(static_cast<unsigned char>(s_[i]))) ++i;
    return i;
  }
  std::size_t SkipString(std::size_t i) const {  // at '"' → after the closing '"'
    for (++i; i < s_.size() && s_[i] != '"'; ++i) {
      if (s_[i] == '\\') ++i;
    }
    return i + 1;
  }
  std::size_t SkipValue(std::size_t i) const {  // at a value → after it
    if (s_[i] == '"') return SkipString(i);
    if (s_[i] != '{' && s_[i] != '[') {
      while (i < s_.size() && s_[i] != ',' && s_[i] != '}' && s_[i] != ']' && !std::isspace(static_cast<unsigned char>(s_[i]))) ++i;
      return i;
    }
    int depth = 0;
    for (; i < s_.size(); ++i) {
      if (s_[i] == '"') {
        i = SkipString(i) - 1;
      } else if (s_[i] == '{' || s_[i] == '[') {
        ++depth;
      } else if ((s_[i] == '}' || s_[i] == ']') && --depth == 0) {
        return i + 1;
      }
    }
    return i;
  }
  // Offset of member `step` of the object / array starting at `at`, npos if absent.
  std::size_t Child(std::size_t at, const std::string& step) const {
    const bool array = s_[at] == '[';
    if (!array && s_[at] != '{') return std::string::npos;
    const long want = array && step.size() > 1 && step[0] == '#' ? std::stol(step.substr(1)) : -1;
    std::size_t i = SkipWs(at + 1);
    for (long index = 0; i < s_.size() && s_[i] != '}' && s_[i] != ']'; ++index) {
      std::string key;
      if (!array) {
        const std::size_t end = SkipString(i);
        key = s_.substr(i + 1, end - i - 2);
        i = SkipWs(SkipWs(end) + 1);  // past ':'
      }
      if ((array && index == want) || (!array && key == step)) return i;
      i = SkipWs(SkipValue(i));
      if (i < s_.size() && s_[i] == ',') i = SkipWs(i + 1);
    }
    return std::string::npos;
  }

  const std::string& s_;
};

struct Context {
  const std::string& path;
  const JsonLocator& loc;
  [[nodiscard]] Error At(const std::vector<std::string>& where, const std::string& what) const {
    std::size_t line = 0, col = 0;
    loc.LineCol(loc.Find(where), &line, &col);
    return DataError(path, line, col, what);
  }
};

double Number(const Context& ctx, const io::Json& obj, std::vector<std::string> where, const std::string& key,
              double lo, double hi) {
  const std::string name = where.size() > 1 ? "stations[" + where[1].substr(1) + "]." + key : where[0] + "." + key;
  if (!obj.contains(key)) throw ctx.At(where, name + " is missing (the station's WGS-84 position is required)");
  where.push_back(key);
  const io::Json& v = obj[key];
  if (!v.is_number()) throw ctx.At(where, name + " must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) {
    throw ctx.At(where, name + " must be in [" + io::Json(lo).dump() + ", " + io::Json(hi).dump() + "]");
  }
  return x;
}

geo::Geodetic Position(const Context& ctx, const io::Json& obj, const std::vector<std::string>& where) {
  if (!obj.is_object()) throw ctx.At(where, "expected an object with lat_deg, lon_deg, h_m");
  geo::Geodetic g;
  g.lat_deg = Number(ctx, obj, where, "lat_deg", -90.0, 90.0);
  g.lon_deg = Number(ctx, obj, where, "lon_deg", -540.0, 540.0);
  g.h_m = Number(ctx, obj, where, "h_m", -1.0e5, 1.0e6);
  return g;
}

bool GoodName(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') return false;
  }
  return true;
}

StationSpec Station(const Context& ctx, const io::Json& st, std::size_t i, const std::filesystem::path& dir) {
  const std::vector<std::string> where = {"stations", "#" + std::to_string(i)};
  if (!st.is_object()) throw ctx.At(where, "stations[" + std::to_string(i) + "] must be an object");
  StationSpec s;
  for (const char* key : {"name", "located"}) {
    if (!st.contains(key) || !st[key].is_string() || st[key].get<std::string>().empty()) {
      std::vector<std::string> w = where;
      if (st.contains(key)) w.push_back(key);
      throw ctx.At(w, "stations[" + std::to_string(i) + "]." + key + " must be a non-empty string");
    }
  }
  s.name = st["name"].get<std::string>();
  if (!GoodName(s.name)) {
    throw ctx.At({where[0], where[1], "name"}, "station name '" + s.name + "' may hold only letters, digits, _ . -");
  }
  s.position = Position(ctx, st, where);
  const std::filesystem::path located = st["located"].get<std::string>();
  s.located = located.is_absolute() || dir.empty() ? located.string() : (dir / located).string();
  ctx.loc.LineCol(ctx.loc.Find(where), &s.line, &s.column);
  return s;
}

}  // namespace

StationsFile ParseStations(const std::string& text, const std::string& path) {
  const io::Json j = io::ParseJson(text, path);
  const JsonLocator loc(text);
  const Context ctx{path, loc};
  if (!j.is_object()) throw ctx.At({}, "expected an object with \"stations\"");
  StationsFile f;
  f.path = path;
  if (!j.contains("stations") || !j["stations"].is_array()) {
    throw ctx.At({"stations"}, "\"stations\" must be an array of at least two stations");
  }
  const std::filesystem::path dir = path == "-" ? std::filesystem::path() : std::filesystem::path(path).parent_path();
  const io::Json& list = j["stations"];
  if (list.size() < 2) throw ctx.At({"stations"}, "rk-intersect needs at least two stations (got " + std::to_string(list.size()) + ")");
  if (list.size() > static_cast<std::size_t>(kMaxStations)) {
    throw ctx.At({"stations"}, "at most " + std::to_string(kMaxStations) + " stations");
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    f.stations.push_back(Station(ctx, list[i], i, dir));
    for (std::size_t k = 0; k < i; ++k) {
      if (f.stations[k].name == f.stations[i].name) {
        throw ctx.At({"stations", "#" + std::to_string(i), "name"}, "station name '" + f.stations[i].name + "' repeats");
      }
    }
  }
  f.origin = f.stations.front().position;
  if (j.contains("origin")) {
    f.origin = Position(ctx, j["origin"], {"origin"});
    f.origin_given = true;
  }
  return f;
}

StationsFile LoadStations(const std::string& path) { return ParseStations(io::ReadFile(path), path); }

}  // namespace rk::intersect

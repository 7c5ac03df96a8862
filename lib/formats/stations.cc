// stations.json reader and writer; see stations.h.
#include "formats/stations.h"

#include <cctype>
#include <cmath>
#include <filesystem>

#include "io/error.h"
#include "io/file_util.h"
#include "io/json_positions.h"
#include "io/json_util.h"

namespace rk::formats {
namespace {

constexpr double kMaxTimeOffsetS = 86400.0;  // a clock a day off is a wrong file, not an offset

struct Context {
  const std::string& path;
  const io::JsonPositions& pos;
  // `where`: object keys and array indices as "#<i>", e.g. {"stations", "#1", "name"}.
  [[nodiscard]] Error At(const std::vector<std::string>& where, const std::string& what) const {
    const io::TextPosition p = pos.At(Pointer(where));
    return DataError(path, p.line, p.column, what);
  }
  static std::string Pointer(const std::vector<std::string>& where) {
    std::string pointer;
    for (const std::string& step : where) {
      pointer += "/" + (step.size() > 1 && step[0] == '#' ? step.substr(1) : io::PointerToken(step));
    }
    return pointer;
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
  if (st.contains("time_offset_s")) {
    const io::Json& v = st["time_offset_s"];
    std::vector<std::string> w = where;
    w.push_back("time_offset_s");
    const std::string name = "stations[" + std::to_string(i) + "].time_offset_s";
    if (!v.is_number()) throw ctx.At(w, name + " must be a number (seconds added to the station's t_s)");
    s.time_offset_s = v.get<double>();
    if (!std::isfinite(s.time_offset_s) || std::abs(s.time_offset_s) > kMaxTimeOffsetS) {
      throw ctx.At(w, name + " must be within ±" + io::Json(kMaxTimeOffsetS).dump() + " s");
    }
    s.time_offset_given = true;
  }
  if (st.contains("time_reference")) {
    std::vector<std::string> w = where;
    w.push_back("time_reference");
    if (!st["time_reference"].is_boolean()) {
      throw ctx.At(w, "stations[" + std::to_string(i) + "].time_reference must be true or false");
    }
    s.time_reference = st["time_reference"].get<bool>();
  }
  const std::filesystem::path located = st["located"].get<std::string>();
  s.located = located.is_absolute() || dir.empty() ? located.string() : (dir / located).string();
  const io::TextPosition p = ctx.pos.At(Context::Pointer(where));
  s.line = p.line;
  s.column = p.column;
  return s;
}

}  // namespace

bool GoodName(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') return false;
  }
  return true;
}

StationsFile ParseStations(const std::string& text, const std::string& path) {
  const io::Json j = io::ParseJson(text, path);
  const io::JsonPositions pos(text);
  const Context ctx{path, pos};
  if (!j.is_object()) throw ctx.At({}, "expected an object with \"stations\"");
  StationsFile f;
  f.path = path;
  if (!j.contains("stations") || !j["stations"].is_array()) {
    throw ctx.At({"stations"}, "\"stations\" must be an array of at least two stations");
  }
  const std::filesystem::path dir = path == "-" ? std::filesystem::path() : std::filesystem::path(path).parent_path();
  const io::Json& list = j["stations"];
  if (list.size() < 2) throw ctx.At({"stations"}, "rk-intersect needs at least two stations (got " + std::to_string(list.size()) + ")");
  if (list.size() > kMaxStations) throw ctx.At({"stations"}, "at most " + std::to_string(kMaxStations) + " stations");
  for (std::size_t i = 0; i < list.size(); ++i) {
    f.stations.push_back(Station(ctx, list[i], i, dir));
    for (std::size_t k = 0; k < i; ++k) {
      if (f.stations[k].time_reference && f.stations[i].time_reference) {
        throw ctx.At({"stations", "#" + std::to_string(i), "time_reference"},
                     "two stations are the time reference ('" + f.stations[k].name + "' and '" + f.stations[i].name +
                         "'): mark one");
      }
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

std::size_t StationsFile::TimeReference() const {
  for (std::size_t i = 0; i < stations.size(); ++i) {
    if (stations[i].time_reference) return i;
  }
  return 0;
}

StationsFile LoadStations(const std::string& path) { return ParseStations(io::ReadFile(path), path); }

io::Json StationsJson(const StationsFile& f) {
  io::Json j = io::Json::object();
  auto position = [](const geo::Geodetic& g) {
    return io::Json{{"lat_deg", g.lat_deg}, {"lon_deg", g.lon_deg}, {"h_m", g.h_m}};
  };
  if (f.origin_given) j["origin"] = position(f.origin);
  j["stations"] = io::Json::array();
  for (const StationSpec& s : f.stations) {
    io::Json st = position(s.position);
    st["name"] = s.name;
    st["located"] = s.located;
    if (s.time_offset_given) st["time_offset_s"] = s.time_offset_s;
    if (s.time_reference) st["time_reference"] = true;
    j["stations"].push_back(st);
  }
  return j;
}

}  // namespace rk::formats

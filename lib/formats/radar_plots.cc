// Radar plots writer (ASTERIX columns) and radars.json reader; see radar_plots.h.
#include "formats/radar_plots.h"

#include <cctype>
#include <cmath>
#include <string_view>

#include "formats/stations.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_positions.h"
#include "io/json_util.h"
#include "io/number_text.h"

namespace rk::formats {

const char* ElevationSourceName(ElevationSource s) {
  switch (s) {
    case ElevationSource::k3d: return "3d";
    case ElevationSource::kModeC: return "mode_c";
    case ElevationSource::kNone: break;
  }
  return "";
}

void WriteAsterixPlots(const std::string& path, const std::vector<std::string>& radar_names,
                       const std::vector<AsterixPlotRow>& rows, const std::vector<std::string>& comments) {
  // Written in pieces of about 4 MB (io::OutputFile): a feed of millions of plots never sits in memory as text.
  io::OutputFile file(path);
  io::CsvWriter out(io::SplitList(kAsterixPlotsColumns));
  for (const std::string& c : comments) out.Comment(c);
  constexpr std::size_t kPiece = 4 << 20;
  // Decimals that hold each item's resolution exactly or below it: time 1/128 s (7 decimals), ρ 1/256 NM
  // (7.234375 m: 4 decimals to 0.1 mm), θ 360/2^16 deg (0.0054931640625: 8 decimals to 1e-8 deg), height 25 ft.
  for (const AsterixPlotRow& r : rows) {
    out.Add(r.t_s, 7).Add(radar_names.at(r.radar)).Add(r.range_m, 4).Add(r.az_deg, 8).Add(r.el_deg, 6);
    if (r.track_id >= 0) out.Add(std::int64_t{r.track_id}); else out.AddEmpty();
    out.Add(int{r.sac}).Add(int{r.sic}).Add(double{r.flight_level}, 2).Add(double{r.height_m}, 2);
    if (r.mode3a >= 0) {  // four octal digits
      const char m[4] = {static_cast<char>('0' + ((r.mode3a >> 9) & 7)), static_cast<char>('0' + ((r.mode3a >> 6) & 7)),
                         static_cast<char>('0' + ((r.mode3a >> 3) & 7)), static_cast<char>('0' + (r.mode3a & 7))};
      out.Add(std::string_view(m, 4));
    } else {
      out.AddEmpty();
    }
    if (r.address >= 0) {  // six upper-case hexadecimal digits
      char a[6];
      for (int k = 0; k < 6; ++k) a[k] = "0123456789ABCDEF"[(r.address >> (20 - 4 * k)) & 15];
      out.Add(std::string_view(a, 6));
    } else {
      out.AddEmpty();
    }
    out.Add(ElevationSourceName(r.el_source)).EndRow();
    if (out.str().size() >= kPiece) out.DrainTo(&file);
  }
  out.DrainTo(&file);
  file.Commit();
}

namespace {

struct Where {
  const std::string& path;
  const io::JsonPositions& pos;
  [[nodiscard]] Error At(const std::string& pointer, const std::string& what) const {
    const io::TextPosition p = pos.At(pointer);
    return DataError(path, p.line, p.column, what);
  }
};

double Number(const Where& w, const io::Json& obj, const std::string& at, const std::string& key, double lo,
              double hi) {
  const io::Json& v = obj[key];
  const std::string name = "radars[" + at.substr(8) + "]." + key;  // at = "/radars/3"
  if (!v.is_number()) throw w.At(at + "/" + key, name + " must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) {
    throw w.At(at + "/" + key, name + " must be in [" + io::NumberText(lo) + ", " + io::NumberText(hi) + "]");
  }
  return x;
}

}  // namespace

std::vector<RadarSite> ParseRadars(const std::string& text, const std::string& path) {
  const io::Json j = io::ParseJson(text, path);
  const io::JsonPositions pos(text);
  const Where w{path, pos};
  if (!j.is_object() || !j.contains("radars") || !j["radars"].is_array()) {
    throw w.At(j.is_object() && j.contains("radars") ? "/radars" : "", "expected an object with a \"radars\" array");
  }
  std::vector<RadarSite> sites;
  const io::Json& list = j["radars"];
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string at = "/radars/" + std::to_string(i);
    const io::Json& r = list[i];
    if (!r.is_object()) throw w.At(at, "radars[" + std::to_string(i) + "] must be an object");
    RadarSite s;
    if (!r.contains("name") || !r["name"].is_string() || !GoodName(r["name"].get<std::string>())) {
      throw w.At(r.contains("name") ? at + "/name" : at,
                 "radars[" + std::to_string(i) + "].name must be a name of letters, digits, _ . -");
    }
    s.name = r["name"].get<std::string>();
    for (const char* key : {"sac", "sic"}) {
      if (!r.contains(key)) throw w.At(at, "radars[" + std::to_string(i) + "]." + key + " is missing");
      const double v = Number(w, r, at, key, 0, 255);
      if (v != std::floor(v)) throw w.At(at + "/" + key, std::string(key) + " must be an integer in [0, 255]");
      (key[1] == 'a' ? s.sac : s.sic) = static_cast<int>(v);
    }
    const int given = static_cast<int>(r.contains("lat_deg")) + r.contains("lon_deg") + r.contains("h_m");
    if (given == 3) {
      geo::Geodetic g;
      g.lat_deg = Number(w, r, at, "lat_deg", -90, 90);
      g.lon_deg = Number(w, r, at, "lon_deg", -180, 360);
      g.h_m = Number(w, r, at, "h_m", -1.0e4, 1.0e5);
      s.position = g;
    } else if (given != 0) {
      throw w.At(at, "radars[" + std::to_string(i) + "]: give all of lat_deg, lon_deg, h_m or none");
    }
    for (const RadarSite& o : sites) {
      if (o.name == s.name) throw w.At(at + "/name", "radar name '" + s.name + "' repeats");
      if (o.sac == s.sac && o.sic == s.sic) {
        throw w.At(at + "/sic", "SAC " + std::to_string(s.sac) + " SIC " + std::to_string(s.sic) + " repeats (radar " +
                                    o.name + ")");
      }
    }
    sites.push_back(std::move(s));
  }
  return sites;
}

std::vector<RadarSite> LoadRadars(const std::string& path) { return ParseRadars(io::ReadFile(path), path); }

}  // namespace rk::formats

// CZML writer; the packets in czml.h.
#include "exports/czml.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "io/utc_time.h"

namespace rk::exports {
namespace {

using Ordered = nlohmann::ordered_json;

// `v` rounded to `decimals` digits after the point: nlohmann then writes the shortest text that reads back as
// that double, i.e. at most those digits.
double Rounded(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;
}

Ordered Rgba(std::size_t index) {
  const auto c = PathColour(index);
  return Ordered{{"rgba", {c[0], c[1], c[2], c[3]}}};
}

class CzmlDocument {
 public:
  CzmlDocument(const GeoTrack& track, const ExportHeader& header, const CzmlOptions& o)
      : t_(track), h_(header), o_(o), epoch_s_(header.epoch_unix_s ? *header.epoch_unix_s : kStandInEpochUnixS) {
    epoch_text_ = io::FormatUtcIso(epoch_s_, kUtcDecimals);
  }

  std::string Text() const {
    std::string out = "[\n" + DocumentPacket().dump();
    for (std::size_t i = 0; i < t_.paths.size(); ++i) {
      if (!t_.paths[i].samples.empty()) out += ",\n" + PathPacket(i).dump();
    }
    return out + "\n]\n";
  }

 private:
  std::string Utc(double t_s, io::Rounding r) const { return io::FormatUtcIso(epoch_s_ + t_s, kUtcDecimals, r); }
  std::string Interval(double t0, double t1) const {
    return Utc(t0, io::Rounding::kDown) + "/" + Utc(t1, io::Rounding::kUp);
  }

  Ordered DocumentPacket() const {
    double t0 = INFINITY, t1 = -INFINITY;
    for (const GeoPath& p : t_.paths) {
      if (p.samples.empty()) continue;
      t0 = std::min(t0, p.samples.front().t_s);
      t1 = std::max(t1, p.samples.back().t_s);
    }
    std::string d = "rk-export czml of the " + std::string(InputKindWords(t_.kind)) + " " + h_.source + ": " +
                    std::to_string(t_.placed) + " of " + std::to_string(t_.rows) + " rows placed, " +
                    std::to_string(t_.Runs()) + (t_.Runs() == 1 ? " run" : " runs") + "; heights above the WGS-84 ellipsoid. ";
    d += h_.epoch_unix_s ? "Times: t_s after the epoch " + h_.epoch_text + "."
                         : "No epoch was given: t_s = 0 is shown at " + std::string(kStandInEpoch) +
                               ", a stand-in (the clock's dates mean nothing).";
    Ordered doc;
    doc["id"] = "document";
    doc["name"] = h_.name.empty() ? h_.source : h_.name;
    doc["version"] = "1.0";
    doc["description"] = d;
    const std::string start = Utc(t0, io::Rounding::kDown);
    doc["clock"] = {{"interval", start + "/" + Utc(t1, io::Rounding::kUp)},
                    {"currentTime", start},
                    {"multiplier", 1},
                    {"range", "LOOP_STOP"},
                    {"step", "SYSTEM_CLOCK_MULTIPLIER"}};
    return doc;
  }

  // σ per axis, time-tagged where the rows give them; nothing when no row does.
  void Sigmas(const GeoPath& path, Ordered* properties) const {
    const char* names[3] = {"sigma_e_m", "sigma_n_m", "sigma_u_m"};
    for (int c = 0; c < 3; ++c) {
      Ordered number = Ordered::array();
      for (const PathSample& s : path.samples) {
        if (!s.sigma_enu_m) continue;
        number.push_back(Rounded(s.t_s, kTimeDecimals));
        number.push_back(Rounded((*s.sigma_enu_m)(c), kSigmaDecimals));
      }
      if (!number.empty()) (*properties)[names[c]] = {{"epoch", epoch_text_}, {"number", std::move(number)}};
    }
  }

  // The status over time: an interval per stretch of one status within a run (to the next sample's time).
  Ordered Status(const GeoPath& path) const {
    Ordered intervals = Ordered::array();
    for (const auto& [b, e] : path.runs) {
      std::size_t j = b;
      while (j < e) {
        std::size_t k = j + 1;
        while (k < e && path.samples[k].status == path.samples[j].status) ++k;
        const double stop = k < e ? path.samples[k].t_s : path.samples[e - 1].t_s;
        intervals.push_back({{"interval", Interval(path.samples[j].t_s, stop)},
                             {"string", RowStatusName(path.samples[j].status)}});
        j = k;
      }
    }
    return intervals;
  }

  Ordered PathPacket(std::size_t i) const {
    const GeoPath& path = t_.paths[i];
    Ordered p;
    p["id"] = path.id.empty() ? std::string("trajectory") : "trajectory/" + path.id;
    p["name"] = path.id.empty() ? std::string(InputKindName(t_.kind)) : path.id;
    p["description"] = std::to_string(path.samples.size()) + " of " + std::to_string(path.rows) + " rows placed, " +
                       std::to_string(path.runs.size()) + (path.runs.size() == 1 ? " run" : " runs");
    Ordered availability = Ordered::array();
    for (const auto& [b, e] : path.runs) availability.push_back(Interval(path.samples[b].t_s, path.samples[e - 1].t_s));
    p["availability"] = std::move(availability);
    Ordered degrees = Ordered::array();
    for (const PathSample& s : path.samples) {
      degrees.push_back(Rounded(s.t_s, kTimeDecimals));
      degrees.push_back(Rounded(s.wgs84.lon_deg, kDegDecimals));
      degrees.push_back(Rounded(s.wgs84.lat_deg, kDegDecimals));
      degrees.push_back(Rounded(s.wgs84.h_m, kHeightDecimals));
    }
    p["position"] = {{"epoch", epoch_text_},
                     {"interpolationAlgorithm", "LAGRANGE"},
                     {"interpolationDegree", 1},
                     {"cartographicDegrees", std::move(degrees)}};
    p["point"] = {{"pixelSize", o_.point_size_px}, {"color", Rgba(i)}};
    const double span = path.samples.back().t_s - path.samples.front().t_s;
    p["path"] = {{"show", true},
                 {"width", o_.path_width_px},
                 {"leadTime", 0},
                 {"trailTime", Rounded(span, kTimeDecimals) + 1.0},
                 {"resolution", 1},
                 {"material", {{"solidColor", {{"color", Rgba(i)}}}}}};
    Ordered properties = Ordered::object();
    Sigmas(path, &properties);
    properties["status"] = Status(path);
    p["properties"] = std::move(properties);
    return p;
  }

  const GeoTrack& t_;
  const ExportHeader& h_;
  const CzmlOptions& o_;
  double epoch_s_;
  std::string epoch_text_;
};

}  // namespace

const io::OptionTable<CzmlOptions>& CzmlOptions::Table() {
  static const io::OptionTable<CzmlOptions> table =
      io::OptionTable<CzmlOptions>()
          .Real("--path-width", &CzmlOptions::path_width_px, "px", io::Bounds::LeftOpen(0.0, 50.0),
                "Line width of the paths (pixels)")
          .Real("--point-size", &CzmlOptions::point_size_px, "px", io::Bounds::LeftOpen(0.0, 50.0),
                "Size of the moving marker (pixels)");
  return table;
}

std::string CzmlText(const GeoTrack& track, const ExportHeader& header, const CzmlOptions& options) {
  return CzmlDocument(track, header, options).Text();
}

}  // namespace rk::exports

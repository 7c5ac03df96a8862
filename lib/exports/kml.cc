// KML writer; the document's layout in kml.h.
#include "exports/kml.h"

#include <tinyxml2.h>

#include <cmath>
#include <cstdio>

#include "io/number_text.h"
#include "io/utc_time.h"

namespace rk::exports {
namespace {

constexpr const char* kKmlNamespace = "http://www.opengis.net/kml/2.2";
constexpr const char* kSampleSchema = "rk_sample";
// Google Earth's own round icon (shown as a dot; other viewers fall back to their default marker).
constexpr const char* kDotIcon = "http://maps.google.com/mapfiles/kml/shapes/shaded_dot.png";
constexpr double kSampleIconScale = 0.5;

// XML 1.0 forbids most control characters: an id or name holding one has it replaced by '?'.
std::string XmlSafe(const std::string& text) {
  std::string s = text;
  for (char& c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 && c != '\t' && c != '\n' && c != '\r') c = '?';
  }
  return s;
}

std::string Fixed(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

// KML colour aabbggrr (hex) of a path.
std::string KmlColour(std::size_t index) {
  const auto c = PathColour(index);
  char b[16];
  std::snprintf(b, sizeof b, "%02x%02x%02x%02x", c[3], c[2], c[1], c[0]);
  return b;
}

class KmlDocument {
 public:
  KmlDocument(const GeoTrack& track, const ExportHeader& header, const KmlOptions& o)
      : t_(track), h_(header), o_(o), p_(nullptr, false) {}

  std::string Text(KmlCounts* counts) {
    p_.PushDeclaration("xml version=\"1.0\" encoding=\"UTF-8\"");
    p_.OpenElement("kml");
    p_.PushAttribute("xmlns", kKmlNamespace);
    p_.OpenElement("Document");
    Leaf("name", h_.name.empty() ? h_.source : h_.name);
    Leaf("open", "1");
    Leaf("description", Description());
    for (std::size_t i = 0; i < t_.paths.size(); ++i) Styles(i);
    SampleSchema();
    for (std::size_t i = 0; i < t_.paths.size(); ++i) {
      if (!t_.paths[i].samples.empty()) Path(i);
    }
    p_.CloseElement();
    p_.CloseElement();
    if (counts) *counts = counts_;
    return std::string(p_.CStr(), static_cast<std::size_t>(p_.CStrSize() > 0 ? p_.CStrSize() - 1 : 0));
  }

 private:
  void Leaf(const char* name, const std::string& text, bool compact = false) {
    p_.OpenElement(name, compact);
    p_.PushText(XmlSafe(text).c_str());
    p_.CloseElement(compact);
  }

  std::string Description() const {
    std::string d = "rk-export kml of the " + std::string(InputKindWords(t_.kind)) + " " + h_.source + ": " +
                    std::to_string(t_.placed) + " of " + std::to_string(t_.rows) + " rows placed (status ok, " +
                    "reacquired or predicted with a WGS-84 position), " + std::to_string(t_.Runs()) +
                    (t_.Runs() == 1 ? " run. " : " runs. ");
    d += h_.epoch_unix_s ? "Times: t_s after the epoch " + h_.epoch_text + " (UTC). "
                         : "No epoch: no time stamps (t_s is in each sample's data). ";
    d += "Altitudes: the file's WGS-84 ellipsoidal h_m minus a geoid undulation of " +
         io::NumberText(o_.geoid_undulation_m) +
         " m; KML's absolute altitude is above mean sea level, so a path drawn with the wrong undulation sits "
         "that much too high or too low (h_ellipsoid_m in each sample's data is the file's own height).";
    return d;
  }

  void Styles(std::size_t i) {
    const std::string n = std::to_string(i);
    p_.OpenElement("Style");
    p_.PushAttribute("id", ("path-" + n).c_str());
    p_.OpenElement("LineStyle");
    Leaf("color", KmlColour(i));
    Leaf("width", io::NumberText(o_.path_width_px));
    p_.CloseElement();
    p_.CloseElement();
    p_.OpenElement("Style");
    p_.PushAttribute("id", ("sample-" + n).c_str());
    p_.OpenElement("IconStyle");
    Leaf("color", KmlColour(i));
    Leaf("scale", io::NumberText(kSampleIconScale));
    p_.OpenElement("Icon");
    Leaf("href", kDotIcon);
    p_.CloseElement();
    p_.CloseElement();
    p_.OpenElement("LabelStyle");
    Leaf("scale", "0");
    p_.CloseElement();
    p_.CloseElement();
  }

  void SampleSchema() {
    p_.OpenElement("Schema");
    p_.PushAttribute("name", kSampleSchema);
    p_.PushAttribute("id", kSampleSchema);
    const char* fields[][3] = {{"t_s", "double", "t_s (s)"},
                               {"status", "string", "status"},
                               {"sigma_e_m", "double", "1-sigma east (m)"},
                               {"sigma_n_m", "double", "1-sigma north (m)"},
                               {"sigma_u_m", "double", "1-sigma up (m)"},
                               {"n_stations", "int", "stations used"},
                               {"h_ellipsoid_m", "double", "height above the WGS-84 ellipsoid (m)"}};
    for (const auto& f : fields) {
      p_.OpenElement("SimpleField");
      p_.PushAttribute("type", f[1]);
      p_.PushAttribute("name", f[0]);
      Leaf("displayName", f[2]);
      p_.CloseElement();
    }
    p_.CloseElement();
  }

  std::string Coordinates(const PathSample& s) const {
    return Fixed(s.wgs84.lon_deg, kDegDecimals) + "," + Fixed(s.wgs84.lat_deg, kDegDecimals) + "," +
           Fixed(s.wgs84.h_m - o_.geoid_undulation_m, kHeightDecimals);
  }

  std::string When(double t_s, io::Rounding r = io::Rounding::kNearest) const {
    return io::FormatUtcIso(*h_.epoch_unix_s + t_s, kUtcDecimals, r);
  }

  void Geometry(const char* kind, const std::string& coordinates, bool compact) {
    p_.OpenElement(kind, compact);
    Leaf("extrude", o_.extrude ? "1" : "0", compact);
    if (std::string(kind) == "LineString") Leaf("tessellate", "0", compact);
    Leaf("altitudeMode", "absolute", compact);
    Leaf("coordinates", coordinates, compact);
    p_.CloseElement(compact);
  }

  void Data(const char* name, const std::string& value) {
    p_.OpenElement("Data");
    p_.PushAttribute("name", name);
    Leaf("value", value);
    p_.CloseElement();
  }

  // One run as a LineString Placemark (a run of one sample is only its sample Placemark).
  void Run(std::size_t i, std::size_t k) {
    const GeoPath& path = t_.paths[i];
    const auto [b, e] = path.runs[k];
    if (e - b < 2) return;
    const double t0 = path.samples[b].t_s, t1 = path.samples[e - 1].t_s;
    p_.OpenElement("Placemark");
    Leaf("name", "run " + std::to_string(k + 1) + ": t_s " + Fixed(t0, 3) + " to " + Fixed(t1, 3) + " s");
    if (h_.epoch_unix_s) {
      p_.OpenElement("TimeSpan");
      Leaf("begin", When(t0, io::Rounding::kDown));
      Leaf("end", When(t1, io::Rounding::kUp));
      p_.CloseElement();
    }
    Leaf("styleUrl", "#path-" + std::to_string(i));
    p_.OpenElement("ExtendedData");
    Data("rows", std::to_string(e - b));
    Data("t_first_s", Fixed(t0, kTimeDecimals));
    Data("t_last_s", Fixed(t1, kTimeDecimals));
    p_.CloseElement();
    std::string coordinates;
    coordinates.reserve((e - b) * 40);
    for (std::size_t j = b; j < e; ++j) {
      if (j > b) coordinates += ' ';
      coordinates += Coordinates(path.samples[j]);
    }
    Geometry("LineString", coordinates, false);
    p_.CloseElement();
    ++counts_.lines;
  }

  void SimpleData(const char* name, const std::string& value) {
    p_.OpenElement("SimpleData", true);
    p_.PushAttribute("name", name);
    p_.PushText(value.c_str());
    p_.CloseElement(true);
  }

  // One sample as a Point Placemark on one line.
  void Sample(std::size_t i, const PathSample& s) {
    p_.OpenElement("Placemark");
    Leaf("name", "t_s " + Fixed(s.t_s, 3), true);
    if (h_.epoch_unix_s) {
      p_.OpenElement("TimeStamp", true);
      Leaf("when", When(s.t_s), true);
      p_.CloseElement(true);
    }
    Leaf("styleUrl", "#sample-" + std::to_string(i), true);
    p_.OpenElement("ExtendedData", true);
    p_.OpenElement("SchemaData", true);
    p_.PushAttribute("schemaUrl", (std::string("#") + kSampleSchema).c_str());
    SimpleData("t_s", Fixed(s.t_s, kTimeDecimals));
    SimpleData("status", RowStatusName(s.status));
    if (s.sigma_enu_m) {
      const char* names[3] = {"sigma_e_m", "sigma_n_m", "sigma_u_m"};
      for (int c = 0; c < 3; ++c) SimpleData(names[c], Fixed((*s.sigma_enu_m)(c), kSigmaDecimals));
    }
    if (s.n_stations) SimpleData("n_stations", std::to_string(*s.n_stations));
    SimpleData("h_ellipsoid_m", Fixed(s.wgs84.h_m, kHeightDecimals));
    p_.CloseElement(true);
    p_.CloseElement(true);
    Geometry("Point", Coordinates(s), true);
    p_.CloseElement(true);
    ++counts_.placemarks;
  }

  void Path(std::size_t i) {
    const GeoPath& path = t_.paths[i];
    p_.OpenElement("Folder");
    Leaf("name", path.id.empty() ? std::string(InputKindName(t_.kind)) : path.id);
    Leaf("open", "1");
    for (std::size_t k = 0; k < path.runs.size(); ++k) Run(i, k);
    p_.OpenElement("Folder");
    Leaf("name", o_.sample_interval_s > 0.0 ? "samples (every " + io::NumberText(o_.sample_interval_s) + " s)"
                                            : std::string("samples (every row)"));
    for (std::size_t j : SampleMarks(path, o_.sample_interval_s)) Sample(i, path.samples[j]);
    p_.CloseElement();
    p_.CloseElement();
  }

  const GeoTrack& t_;
  const ExportHeader& h_;
  const KmlOptions& o_;
  tinyxml2::XMLPrinter p_;
  KmlCounts counts_;
};

}  // namespace

const io::OptionTable<KmlOptions>& KmlOptions::Table() {
  static const io::OptionTable<KmlOptions> table =
      io::OptionTable<KmlOptions>()
          .Real("--sample-interval", &KmlOptions::sample_interval_s, "s", io::Bounds::AtLeast(0.0).Finite(),
                "A sample Placemark (point with time stamp, sigma and status) at most every this many seconds of "
                "each run, plus each run's first and last row; 0 = every row. The line has every row")
          .Real("--geoid-undulation", &KmlOptions::geoid_undulation_m, "m", io::Bounds::Closed(-120.0, 120.0),
                "Geoid height above the WGS-84 ellipsoid at the range (m): KML altitudes are h_m minus this "
                "(KML's absolute altitude is above mean sea level; the trajectory's h_m is ellipsoidal)")
          .Real("--path-width", &KmlOptions::path_width_px, "px", io::Bounds::LeftOpen(0.0, 50.0),
                "Line width of the paths (pixels)")
          .Flag("--extrude", &KmlOptions::extrude, "Draw the paths and samples down to the ground");
  return table;
}

std::vector<std::size_t> SampleMarks(const GeoPath& path, double interval_s) {
  std::vector<std::size_t> marks;
  for (const auto& [b, e] : path.runs) {
    double last = 0.0;
    for (std::size_t j = b; j < e; ++j) {
      const double t = path.samples[j].t_s;
      if (j == b || j + 1 == e || t - last >= interval_s) {
        marks.push_back(j);
        last = t;
      }
    }
  }
  return marks;
}

std::string KmlText(const GeoTrack& track, const ExportHeader& header, const KmlOptions& options, KmlCounts* counts) {
  return KmlDocument(track, header, options).Text(counts);
}

}  // namespace rk::exports

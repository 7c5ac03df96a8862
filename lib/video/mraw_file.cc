// Photron MRAW recordings: the .cihx (XML, by tinyxml2) and .cih (text) headers, the parsers of
// camera_file.h. One table (kFields) says where each header value is in both forms, its range and
// whether it is required; the parsers differ only in how they find a value.
//
// Frame times: a Photron file holds no per-frame stamps; frame i is the camera's frame number
// start + i·skip, taken at (start + i·skip) / record rate seconds from the trigger (time_source
// "nominal"; camera_ts_s is that time since the trigger).
#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <string_view>
#include <cctype>
#include <utility>

#include "io/error.h"
#include "video/camera_file.h"

namespace rk::video {
namespace {

enum class Field { kWidth, kHeight, kBits, kColorType, kEffectiveDepth, kEffectiveSide, kTotalFrames, kStartFrame,
                   kSkipFrame, kRate, kShutterNs, kShutterSpeed, kFileFormat, kIrig };

struct FieldSpec {
  Field field;
  const char* xml_path;  // element path below <cih>
  const char* cih_key;   // key of the .cih text form ("": not in the .cih)
  bool required;
};

constexpr std::array<FieldSpec, 14> kFields{{
    {Field::kWidth, "imageDataInfo/resolution/width", "Image Width", true},
    {Field::kHeight, "imageDataInfo/resolution/height", "Image Height", true},
    {Field::kBits, "imageDataInfo/colorInfo/bit", "Color Bit", true},
    {Field::kColorType, "imageDataInfo/colorInfo/type", "Color Type", false},
    {Field::kEffectiveDepth, "imageDataInfo/effectiveBit/depth", "EffectiveBit Depth", false},
    {Field::kEffectiveSide, "imageDataInfo/effectiveBit/side", "EffectiveBit Side", false},
    {Field::kTotalFrames, "frameInfo/totalFrame", "Total Frame", true},
    {Field::kStartFrame, "frameInfo/startFrame", "Start Frame", false},
    {Field::kSkipFrame, "frameInfo/skipFrame", "Save Step", false},
    {Field::kRate, "recordInfo/recordRate", "Record Rate(fps)", true},
    {Field::kShutterNs, "recordInfo/shutterSpeedNsec", "Shutter Type2(nsec)", false},
    {Field::kShutterSpeed, "recordInfo/shutterSpeed", "Shutter Speed(s)", false},
    {Field::kFileFormat, "imageFileInfo/fileFormat", "File Format", false},
    {Field::kIrig, "deviceInfo/irig", "", false},  // 1: the camera ran on an IRIG input
}};

// A header value with the line it is on (1-based; the XML line in the .cihx, the text line in the .cih).
struct Value {
  std::string text;
  int line = 0;
};
using Values = std::map<Field, Value>;

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

class HeaderValues {
 public:
  HeaderValues(std::string file, Values values) : file_(std::move(file)), values_(std::move(values)) {}

  [[noreturn]] void Fail(int line, const std::string& what) const {
    throw DataError(file_, static_cast<std::size_t>(line), 0, what);
  }
  const Value* Find(Field f) const {
    auto it = values_.find(f);
    return it == values_.end() ? nullptr : &it->second;
  }
  const char* NameOf(Field f, bool xml) const {
    for (const FieldSpec& s : kFields) {
      if (s.field == f) return xml ? s.xml_path : s.cih_key;
    }
    return "?";
  }
  // The integer value of `f` in [lo, hi]; `fallback` when absent and not required.
  std::int64_t Int(Field f, std::int64_t lo, std::int64_t hi, std::int64_t fallback, bool xml) const {
    const Value* v = Find(f);
    if (!v) return fallback;
    char* end = nullptr;
    const long long x = std::strtoll(v->text.c_str(), &end, 10);
    if (v->text.empty() || *end != '\0' || x < lo || x > hi) {
      Fail(v->line, std::string(NameOf(f, xml)) + " '" + v->text + "' is not an integer in " + std::to_string(lo) + ".." +
                        std::to_string(hi));
    }
    return x;
  }
  // A positive number, or "1/N" (the .cih's shutter speed); NaN when absent.
  double Positive(Field f, bool xml) const {
    const Value* v = Find(f);
    if (!v) return std::nan("");
    std::string t = v->text;
    double scale = 1.0;
    if (t.rfind("1/", 0) == 0) {
      t = t.substr(2);
      scale = -1.0;  // reciprocal
    }
    char* end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !(x > 0) || !std::isfinite(x)) {
      Fail(v->line, std::string(NameOf(f, xml)) + " '" + v->text + "' is not a positive number");
    }
    return scale < 0 ? 1.0 / x : x;
  }
  std::string Text(Field f) const {
    const Value* v = Find(f);
    return v ? v->text : std::string();
  }
  int LineOf(Field f) const {
    const Value* v = Find(f);
    return v ? v->line : 0;
  }

 private:
  std::string file_;
  Values values_;
};

// The CameraFile the header values describe, checked against the size of the .mraw.
CameraFile Describe(const HeaderValues& h, bool xml, const std::string& header_path, const std::string& data_path,
                    std::uint64_t data_size) {
  for (const FieldSpec& s : kFields) {
    if (s.required && !h.Find(s.field)) h.Fail(0, std::string("no ") + (xml ? s.xml_path : s.cih_key) + " in the header");
  }
  CameraFile cf;
  cf.format = "mraw";
  cf.path = data_path;
  cf.header = header_path;
  const std::string format = Lower(h.Text(Field::kFileFormat));
  if (!format.empty() && format != "mraw") h.Fail(h.LineOf(Field::kFileFormat), "file format '" + h.Text(Field::kFileFormat) + "' (only MRaw)");
  const std::string type = Lower(h.Text(Field::kColorType));
  if (!type.empty() && type != "mono" && type != "raw") {
    h.Fail(h.LineOf(Field::kColorType), "colour type '" + h.Text(Field::kColorType) + "' is not supported (Mono or Raw)");
  }
  cf.cfa = "mono";
  cf.width = static_cast<int>(h.Int(Field::kWidth, 1, 65536, 0, xml));
  cf.height = static_cast<int>(h.Int(Field::kHeight, 1, 65536, 0, xml));
  const std::int64_t bits = h.Int(Field::kBits, 1, 64, 0, xml);
  if (bits == 8) {
    cf.packing = Packing::kU8;
  } else if (bits == 12) {
    cf.packing = Packing::kP12BE;
  } else if (bits == 16) {
    cf.packing = Packing::kU16LE;
  } else {
    h.Fail(h.LineOf(Field::kBits), "unknown bit depth " + std::to_string(bits) + " (8, 12 or 16)");
  }
  cf.significant_bits = static_cast<int>(bits);
  if (bits == 16) {
    const std::int64_t depth = h.Int(Field::kEffectiveDepth, 8, 16, 16, xml);
    const std::string side = Lower(h.Text(Field::kEffectiveSide));
    if (!side.empty() && side != "lower" && side != "higher") h.Fail(h.LineOf(Field::kEffectiveSide), "effective bit side '" + side + "' (Lower or Higher)");
    cf.significant_bits = side == "higher" ? 16 : static_cast<int>(depth);
  }
  const std::uint64_t pixels = static_cast<std::uint64_t>(cf.width) * static_cast<std::uint64_t>(cf.height);
  if (!FillsGroups(cf.packing, pixels)) h.Fail(h.LineOf(Field::kWidth), "an odd number of pixels per frame cannot be 12-bit packed");
  cf.frame_bytes = PackedBytes(cf.packing, pixels);
  const std::int64_t total = h.Int(Field::kTotalFrames, 1, std::int64_t{1} << 40, 0, xml);
  const bool fits = static_cast<std::uint64_t>(total) <= UINT64_MAX / cf.frame_bytes;  // the product below
  if (!fits || static_cast<std::uint64_t>(total) * cf.frame_bytes != data_size) {
    h.Fail(h.LineOf(Field::kTotalFrames), std::to_string(total) + " frames of " + std::to_string(cf.width) + "x" +
                                              std::to_string(cf.height) + " " + InfoOf(cf.packing).name + " need " +
                                              (fits ? std::to_string(static_cast<std::uint64_t>(total) * cf.frame_bytes) : "more than 2^64") +
                                              " bytes but " + data_path + " has " + std::to_string(data_size));
  }
  for (std::int64_t i = 0; i < total; ++i) cf.frame_offsets.push_back(static_cast<std::uint64_t>(i) * cf.frame_bytes);
  const double rate = h.Positive(Field::kRate, xml);
  const std::int64_t start = h.Int(Field::kStartFrame, -(std::int64_t{1} << 40), std::int64_t{1} << 40, 0, xml);
  const std::int64_t skip = h.Int(Field::kSkipFrame, 1, 1 << 30, 1, xml);
  double exposure = h.Positive(Field::kShutterNs, xml) * 1e-9;
  if (!std::isfinite(exposure)) {
    const double speed = h.Positive(Field::kShutterSpeed, xml);
    exposure = xml ? 1.0 / speed : speed;  // CIHX: 50000 means 1/50000 s; CIH: "1/50000" (already a time)
  }
  RecordingTimes& t = cf.times;
  t.nominal_rate_hz = rate / static_cast<double>(skip);
  t.absolute = false;
  t.basis = "no per-frame stamps in a Photron file: frame number (start " + std::to_string(start) + ", step " +
            std::to_string(skip) + ") over the record rate";
  t.frames.resize(static_cast<std::size_t>(total));
  if (h.Int(Field::kIrig, 0, 1 << 30, 0, xml) != 0) {
    // Photron publishes no layout for the per-frame IRIG stamps of an MRAW (the sample files have none), so an
    // IRIG recording is timed like any other here; the user must know that these are not UTC times.
    t.warnings.push_back({"irig_not_read", header_path + ":" + std::to_string(h.LineOf(Field::kIrig)) +
                                               ": the camera recorded on IRIG (deviceInfo/irig), but a Photron file's "
                                               "per-frame IRIG stamps are not read: times are the frame numbers over the "
                                               "record rate, from the trigger, not UTC (give --frames for UTC)"});
  }
  for (std::int64_t i = 0; i < total; ++i) {
    FrameStamp& f = t.frames[static_cast<std::size_t>(i)];
    f.camera_ts_s = static_cast<double>(start + i * skip) / rate;
    f.t_s = f.camera_ts_s;
    f.source = TimeSource::kNominal;
    f.exposure_s = exposure;
  }
  return cf;
}

// Where the XML document of a .cihx starts and ends: after Photron's binary preamble, from "<?xml" (or
// "<cih") to the end of "</cih>"; a binary block may follow it.
std::pair<std::uint64_t, std::uint64_t> XmlExtent(const ByteView& v) {
  const char* d = reinterpret_cast<const char*>(v.data());
  const std::string_view all(d, v.size());
  std::size_t begin = all.find("<?xml");
  if (begin == std::string_view::npos) begin = all.find("<cih");
  if (begin == std::string_view::npos) v.Fail(0, "no XML document (<?xml or <cih>) in the .cihx");
  const std::size_t close = all.rfind("</cih>");
  if (close == std::string_view::npos || close < begin) v.Fail(begin, "the XML document has no </cih> end");
  return {begin, close + 6};
}

void CollectXml(const tinyxml2::XMLElement* cih, int line_offset, Values* values) {
  for (const FieldSpec& s : kFields) {
    const tinyxml2::XMLElement* e = cih;
    std::string path = s.xml_path;
    std::size_t p = 0;
    while (e && p <= path.size()) {
      const std::size_t q = std::min(path.find('/', p), path.size());
      e = e->FirstChildElement(path.substr(p, q - p).c_str());
      p = q + 1;
    }
    if (!e) continue;
    const char* text = e->GetText();
    (*values)[s.field] = {Trim(text ? text : ""), e->GetLineNum() + line_offset};
  }
}

}  // namespace

CameraFile ParseCihx(const ByteView& header, const std::string& data_path, std::uint64_t data_size) {
  const auto [begin, end] = XmlExtent(header);
  const char* d = reinterpret_cast<const char*>(header.data());
  const int line_offset = static_cast<int>(std::count(d, d + begin, '\n'));
  tinyxml2::XMLDocument doc;
  if (doc.Parse(d + begin, end - begin) != tinyxml2::XML_SUCCESS) {
    throw DataError(header.file(), static_cast<std::size_t>(doc.ErrorLineNum() + line_offset), 0,
                    std::string("not well-formed XML: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* cih = doc.FirstChildElement("cih");
  if (!cih) header.Fail(begin, "the XML document has no <cih> root element");
  Values values;
  CollectXml(cih, line_offset, &values);
  return Describe(HeaderValues(header.file(), std::move(values)), true, header.file(), data_path, data_size);
}

CameraFile ParseCih(const ByteView& header, const std::string& data_path, std::uint64_t data_size) {
  const std::string_view text(reinterpret_cast<const char*>(header.data()), header.size());
  Values values;
  int line = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    const std::string l(text.substr(pos, nl - pos));
    pos = nl + 1;
    ++line;
    const std::size_t colon = l.find(" : ");
    if (colon == std::string::npos) continue;
    const std::string key = Trim(l.substr(0, colon));
    for (const FieldSpec& s : kFields) {
      if (*s.cih_key != '\0' && key == s.cih_key && !values.count(s.field)) values[s.field] = {Trim(l.substr(colon + 3)), line};
    }
  }
  return Describe(HeaderValues(header.file(), std::move(values)), false, header.file(), data_path, data_size);
}

}  // namespace rk::video

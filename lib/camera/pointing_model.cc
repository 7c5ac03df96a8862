#include "camera/pointing_model.h"

#include <cmath>

#include "geo/angles.h"
#include "io/error.h"
#include "io/file_util.h"

namespace rk::camera {
namespace {

// Largest tilt or elevation-axis error accepted (degrees): a turret further out of level than this is
// not a small error to calibrate but a set-up to redo.
constexpr double kMaxTiltDeg = 10.0;

// An error about the value at JSON pointer `pointer`, at its line and column when the text was indexed.
[[noreturn]] void Fail(const std::string& where, const io::JsonPositions& pos, const std::string& pointer,
                       const std::string& what) {
  const io::TextPosition p = pos.At(pointer);
  throw DataError(where, p.line, p.column, what);
}

// The number at j[key] (degrees), or nullopt when absent or null; anything else is an error at its position.
std::optional<double> Number(const io::Json& j, const char* key, const std::string& pointer, const std::string& name,
                             const std::string& where, const io::JsonPositions& pos) {
  if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
  const io::Json& v = j.at(key);
  if (!v.is_number()) Fail(where, pos, pointer, name + " must be a number");
  return v.get<double>();
}

double ReadTerm(const io::Json& j, const char* key, double max_abs_deg, const std::string& where,
                const io::JsonPositions& pos) {
  const std::string pointer = std::string("/") + key;
  const double deg = Number(j, key, pointer, key, where, pos).value_or(0.0);
  if (!std::isfinite(deg) || std::abs(deg) > max_abs_deg) {
    Fail(where, pos, pointer,
         std::string(key) + " must be finite and within ±" + std::to_string(static_cast<int>(max_abs_deg)) + " degrees");
  }
  return geo::DegToRad(deg);
}

}  // namespace

PointingModel PointingModelFromJson(const io::Json& j, const std::string& where, const io::JsonPositions& pos) {
  if (!j.is_object()) Fail(where, pos, "", "pointing model must be a JSON object");
  PointingModel m;
  std::array<double, 4> t{};
  for (int i = 0; i < 4; ++i) {
    t[static_cast<std::size_t>(i)] = ReadTerm(j, kPointingTermKeys[static_cast<std::size_t>(i)],
                                              i == kAzOffset ? 360.0 : kMaxTiltDeg, where, pos);
  }
  m.SetTermsRad(t);
  if (j.contains("sigma") && !j.at("sigma").is_null()) {
    const io::Json& s = j.at("sigma");
    if (!s.is_object()) Fail(where, pos, "/sigma", "sigma must be an object");
    for (std::size_t i = 0; i < 4; ++i) {
      const std::string key = kPointingTermKeys[i], pointer = "/sigma/" + key, name = "sigma." + key;
      const std::optional<double> deg = Number(s, kPointingTermKeys[i], pointer, name, where, pos);
      if (!deg) continue;
      if (!std::isfinite(*deg) || *deg < 0) Fail(where, pos, pointer, name + " must be finite and >= 0");
      m.sigma_rad[i] = geo::DegToRad(*deg);
    }
  }
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = it.key() == "sigma";
    for (const char* k : kPointingTermKeys) known = known || it.key() == k;
    if (!known) m.extra[it.key()] = it.value();
  }
  return m;
}

PointingModel ParsePointingModel(const std::string& text, const std::string& name) {
  return PointingModelFromJson(io::ParseJson(text, name), name, io::JsonPositions(text));
}

PointingModel LoadPointingModel(const std::string& path) {
  return ParsePointingModel(io::ReadFile(path), io::IsStdStream(path) ? "<stdin>" : path);
}
io::Json PointingModelToJson(const PointingModel& m) {
  io::Json j = m.extra;
  const std::array<double, 4> t = m.TermsRad();
  io::Json sigma = io::Json::object();
  for (int i = 0; i < 4; ++i) {
    j[kPointingTermKeys[i]] = geo::RadToDeg(t[i]);
    if (m.sigma_rad[i]) sigma[kPointingTermKeys[i]] = geo::RadToDeg(*m.sigma_rad[i]);
  }
  j["sigma"] = sigma;
  return j;
}

}  // namespace rk::camera

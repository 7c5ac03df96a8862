#include "camera/pointing_model.h"

#include <cmath>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::camera {
namespace {

// Largest tilt or elevation-axis error accepted (degrees): a turret further out of level than this is
// not a small error to calibrate but a set-up to redo.
constexpr double kMaxTiltDeg = 10.0;

double ReadTerm(const io::Json& j, const char* key, double max_abs_deg, const std::string& where) {
  const double deg = io::NumberOr(j, key, 0.0, where);
  if (!std::isfinite(deg) || std::abs(deg) > max_abs_deg) {
    throw DataError(where, 0, 0, std::string(key) + " must be finite and within ±" + std::to_string(static_cast<int>(max_abs_deg)) + " degrees");
  }
  return geo::DegToRad(deg);
}

}  // namespace

PointingModel PointingModelFromJson(const io::Json& j, const std::string& where) {
  if (!j.is_object()) throw DataError(where, 0, 0, "pointing model must be a JSON object");
  PointingModel m;
  std::array<double, 4> t{};
  for (int i = 0; i < 4; ++i) t[i] = ReadTerm(j, kPointingTermKeys[i], i == kAzOffset ? 360.0 : kMaxTiltDeg, where);
  m.SetTermsRad(t);
  if (j.contains("sigma") && !j.at("sigma").is_null()) {
    const io::Json& s = j.at("sigma");
    const std::string sw = where + ": sigma";
    if (!s.is_object()) throw DataError(where, 0, 0, "sigma must be an object");
    for (int i = 0; i < 4; ++i) {
      if (!s.contains(kPointingTermKeys[i]) || s.at(kPointingTermKeys[i]).is_null()) continue;
      const double deg = io::RequireNumber(s, kPointingTermKeys[i], sw);
      if (!std::isfinite(deg) || deg < 0) {
        throw DataError(where, 0, 0, std::string("sigma.") + kPointingTermKeys[i] + " must be finite and >= 0");
      }
      m.sigma_rad[i] = geo::DegToRad(deg);
    }
  }
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = it.key() == "sigma";
    for (const char* k : kPointingTermKeys) known = known || it.key() == k;
    if (!known) m.extra[it.key()] = it.value();
  }
  return m;
}

PointingModel LoadPointingModel(const std::string& path) { return PointingModelFromJson(io::LoadJson(path), path); }

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
